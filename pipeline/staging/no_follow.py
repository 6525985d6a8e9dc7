"""Files that bearingsim appends to or locks in place (`run.log`, `.lock`), opened so that a
link or a special file put there is refused instead of written through.

Everything else in a run directory is written by an atomic rename (pipeline.staging.artefacts),
which replaces a link instead of following it; only files opened for appending or locking
need this guard.
"""

from __future__ import annotations

import os
import stat
from collections.abc import Iterator
from contextlib import contextmanager
from contextvars import ContextVar
from pathlib import Path


class OutputRefused(OSError):
    """bearingsim will not write here: the path is not its own, not a directory, or not
    writable. The message names the path and what to do (exit code 2: a bad option)."""


# how the caller names the output directory: the command line's option, or the argument of
# the Python API (set by `named_in_python` around the API's calls)
_OUT_NAME: ContextVar[str] = ContextVar("out_name", default="--out")


def out_name(path=None) -> str:
    """The output directory as the user gave it: `--out DIR` on the command line,
    `run_dir='DIR'` from Python; without `path`, the option or argument alone."""
    name = _OUT_NAME.get()
    if path is None:
        return name
    return f"{name} {path}" if name.startswith("-") else f"{name}={str(path)!r}"


# set while a command of the command line runs: the API functions it calls keep naming `--out`
_ON_COMMAND_LINE: ContextVar[bool] = ContextVar("on_command_line", default=False)


@contextmanager
def named_in_python(argument: str = "run_dir") -> Iterator[None]:
    """Within this block, messages about the output directory name the Python argument (not when
    a command of the command line called the API function: it names its option)."""
    if _ON_COMMAND_LINE.get():
        yield
        return
    token = _OUT_NAME.set(argument)
    try:
        yield
    finally:
        _OUT_NAME.reset(token)


@contextmanager
def named_on_command_line() -> Iterator[None]:
    """Within this block, messages name `--out`, also inside the API functions it calls."""
    token, name = _ON_COMMAND_LINE.set(True), _OUT_NAME.set("--out")
    try:
        yield
    finally:
        _OUT_NAME.reset(name)
        _ON_COMMAND_LINE.reset(token)


_FLAGS = os.O_RDWR | os.O_CREAT | os.O_APPEND | getattr(os, "O_NOFOLLOW", 0) | getattr(os, "O_CLOEXEC", 0)


def open_no_follow(path: Path, text: bool = True):
    """Open `path` for appending (created if absent), never through a symbolic link and
    only as a regular file; OutputRefused names the path and what to do otherwise."""
    path = Path(path)
    try:
        fd = os.open(path, _FLAGS | getattr(os, "O_NONBLOCK", 0), 0o666)
    except OSError as exc:
        if path.is_symlink():
            raise refused_special_file(path, "is a symbolic link") from None
        raise
    try:
        if not stat.S_ISREG(os.fstat(fd).st_mode):
            raise refused_special_file(path, "is not a regular file")
        os.set_blocking(fd, True)
        return os.fdopen(fd, "a+" if text else "a+b", encoding="utf-8" if text else None)
    except BaseException:
        os.close(fd)
        raise


def refused_special_file(path: Path, what: str) -> OutputRefused:
    """The refusal of a link or a special file where bearingsim appends or locks."""
    return OutputRefused(f"{path} {what}; bearingsim never writes through a link or into a special "
                         f"file: remove it, or give the run its own directory with {out_name()}")
