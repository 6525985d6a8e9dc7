"""Ctrl-C during a sweep reads as one message, not as Dask's logs from what goes down with it.

Ctrl-C in a terminal reaches every process of its group: the process that runs the sweep and
the worker processes of its local cluster. The sweep reports the interruption once and closes
the cluster; meanwhile Dask, in both, logs what it meets on the way down (connections closing
under a worker, a cancelled call in the client's event-loop thread, workers stopped by force).
Those logs are expected after Ctrl-C, not news to the user, and some come from other threads
before the interruption reaches any `except`. So the handler of SIGINT silences Dask's loggers
first, then does what it would have done anyway: in the sweep's process
(`quiet_on_interrupt`, around `driver.dask_client`), and in each local worker (`dask_setup`, a
worker preload).
"""

from __future__ import annotations

import logging
import os
import signal
import threading
from contextlib import contextmanager

QUIET_ON_INTERRUPT = ("distributed", "tornado", "asyncio")


def silence_then(previous, mute_stderr: bool = False):
    """A SIGINT handler that silences the loggers `QUIET_ON_INTERRUPT`, then hands the signal
    to `previous`: a Python handler (Python's own raises KeyboardInterrupt; a worker's event
    loop cancels its main task), or the default action (the process ends by the signal).
    With `mute_stderr` (a worker's: the sweep's own process says what happened) the process's
    standard error goes to the null device first, so that the traceback multiprocessing
    prints for a worker process ended by KeyboardInterrupt, which is no log, is not shown."""
    def on_interrupt(signum, frame):
        for name in QUIET_ON_INTERRUPT:
            logging.getLogger(name).setLevel(logging.CRITICAL)
        if mute_stderr:
            null = os.open(os.devnull, os.O_WRONLY)
            os.dup2(null, 2)
            os.close(null)
        if callable(previous):
            previous(signum, frame)
        else:
            signal.signal(signum, signal.SIG_DFL)
            os.kill(os.getpid(), signum)
    return on_interrupt


def _install(mute_stderr: bool = False) -> object:
    """Put `silence_then` before this process's SIGINT handler; returns the handler it replaced,
    or None where it was left alone: signals can only be handled in a process's main thread, and
    a process that ignores SIGINT, or whose handler is not Python's, is left as it is."""
    if threading.current_thread() is not threading.main_thread():
        return None
    previous = signal.getsignal(signal.SIGINT)
    if previous is None or previous == signal.SIG_IGN:
        return None
    signal.signal(signal.SIGINT, silence_then(previous, mute_stderr))
    return previous


@contextmanager
def quiet_on_interrupt():
    """While the block runs, SIGINT first silences Dask's logging in this process. The loggers
    stay silent after an interrupted block: the client's event-loop thread may still report on
    the interrupted call after the cluster has gone down (distributed's `sync` cancels it from a
    callback that can fail)."""
    previous = _install()
    try:
        yield
    finally:
        if previous is not None:
            signal.signal(signal.SIGINT, previous)


def dask_setup(worker) -> None:
    """Called by Dask in each worker process as it starts (a nanny's worker runs its event
    loop in the process's main thread)."""
    _install(mute_stderr=True)
