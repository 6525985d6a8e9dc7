"""Exclusive file locks that never follow a link: the run directory's `.lock`, the stage store's
per-key locks and the kernel cache's compile locks.

The locking itself is `filelock` (flock on POSIX, LockFileEx on Windows, released by the
kernel however the process ends). It opens the lock file with O_NOFOLLOW, so a symbolic link
in the lock's place is refused (ELOOP) and its target is neither created nor written; the
callback below refuses a FIFO, a device or a socket there, checked on the descriptor that
holds the lock. filelock's soft-lock fallback (marker files for file systems without flock)
is off: a marker left by a killed process would block every later run.
"""

from __future__ import annotations

import errno
import os
import stat
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path


class LockBusy(RuntimeError):
    """Another process holds the lock (only with `wait=False`)."""


class NotALockFile(OSError):
    """A link, a folder or a special file stands where the lock file belongs."""

    def __init__(self, path: Path, what: str):
        self.path, self.what = Path(path), what
        super().__init__(errno.EINVAL, what, str(path))


def _regular_file_only(fd: int) -> None:
    if not stat.S_ISREG(os.fstat(fd).st_mode):
        raise OSError(errno.EINVAL, "is not a regular file")


def _refusal(path: Path) -> NotALockFile | None:
    """What stands at `path` if it cannot be a lock file (None: absent or a regular file)."""
    try:
        mode = os.lstat(path).st_mode
    except FileNotFoundError:
        return None
    if stat.S_ISLNK(mode):
        return NotALockFile(path, "is a symbolic link")
    if not stat.S_ISREG(mode):
        return NotALockFile(path, "is not a regular file")
    return None


@contextmanager
def exclusive_lock(path: Path, *, wait: bool = True) -> Iterator[None]:
    """Hold an exclusive lock on `path` (created if absent, following the umask) while the block
    runs. `wait=False` raises LockBusy at once when another process holds it. A link, a folder or
    a special file at `path` raises NotALockFile before it is opened (and, if one is put there
    meanwhile, on the opened descriptor); other OS errors pass through."""
    import filelock

    path = Path(path)
    refused = _refusal(path)
    if refused is not None:
        raise refused
    lock = filelock.FileLock(path, timeout=-1 if wait else 0, fallback_to_soft=False,
                             on_acquired=_regular_file_only)
    try:
        lock.acquire()
    except filelock.Timeout:
        raise LockBusy(str(path)) from None
    except OSError as exc:
        raise (_refusal(path) or (NotALockFile(path, "is not a regular file")
                                  if exc.errno == errno.EINVAL else exc)) from None
    try:
        yield
    finally:
        lock.release()
