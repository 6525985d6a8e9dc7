"""SIGTERM handled like Ctrl-C: a batch system's or `timeout`'s stop raises in the main thread
where the process is, so the interrupted stage's temporary folder is removed on the way out
(pipeline.staging.artefacts.staged_directory) and the command logs it and exits 143."""

from __future__ import annotations

import signal
import threading


class Terminated(KeyboardInterrupt):
    """The process received SIGTERM; a KeyboardInterrupt so every Ctrl-C path cleans up."""


def _raise_terminated(signum, frame):
    raise Terminated()


def stop_on_sigterm() -> None:
    """Raise Terminated on SIGTERM in the main thread (elsewhere signals cannot be handled)."""
    if threading.current_thread() is threading.main_thread() and hasattr(signal, "SIGTERM"):
        signal.signal(signal.SIGTERM, _raise_terminated)


def interruption(exc: KeyboardInterrupt) -> tuple[str, int]:
    """(how to name the interruption, exit code): SIGTERM 143, Ctrl-C 130 (128 + signal)."""
    return ("SIGTERM", 143) if isinstance(exc, Terminated) else ("Ctrl-C", 130)
