"""What an OSError of a run means to the user: which file, what went wrong, what to do.

A full disk, a missing permission, an address-space limit (ulimit -v) and a cache folder that is
a file all reach the command line as OSError; each is named for what it is, and the path named is
the one that failed, inside the run directory or not.
"""

from __future__ import annotations

import errno
from pathlib import Path

MEMORY_HINT = "shorten solver.duration or raise output.sample_interval"


def describe_os_error(exc: OSError, run_dir: Path | None = None) -> str:
    """One sentence on `exc`: the errno's meaning, the file it concerns and what to try."""
    reason = exc.strerror or str(exc) or type(exc).__name__
    path = Path(exc.filename) if exc.filename else None
    where = _where(path, run_dir)
    if exc.errno == errno.ENOMEM:
        return (f"out of memory ({reason}{f', at {path}' if path else ''}): the process may not allocate "
                f"more (its address-space limit, ulimit -v, or the machine's memory); {MEMORY_HINT}")
    if exc.errno in (errno.ENOSPC, getattr(errno, "EDQUOT", errno.ENOSPC)):
        return (f"no space left on the device{f' of {path}' if path else ''} ({reason}){where}: free space "
                f"there{' or give --out on another file system' if run_dir is not None else ''}; "
                "nothing half-written is kept")
    if exc.errno == errno.EFBIG:
        return (f"{path or 'a file'}: {reason}{where}: larger than the file system or the process's file-size "
                "limit (ulimit -f) allows; nothing half-written is kept")
    if exc.errno in (errno.EACCES, errno.EPERM, errno.EROFS):
        return f"{path or 'a file'}: {reason}{where}; give a place this user may write"
    if exc.errno in (errno.ENOTDIR, errno.EISDIR, errno.EEXIST):
        return f"{path or 'a path'}: {reason}{where}; a file stands where a folder belongs (or the other way)"
    return f"{path or 'a file'}: {reason}{where}"


def _where(path: Path | None, run_dir: Path | None) -> str:
    """' (in the run directory)', ' (outside the run directory ...)' or ''."""
    if path is None or run_dir is None:
        return ""
    try:
        path.absolute().relative_to(Path(run_dir).absolute())
    except ValueError:
        return f" (outside the run directory {run_dir}/)"
    return ""
