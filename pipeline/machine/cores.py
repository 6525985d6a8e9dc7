"""How many cores this process may run on: a second core is what work started beside the main
line (the compile-ahead child, the report's FE renders) needs to finish sooner, not later."""

from __future__ import annotations

import os


def usable_cores() -> int:
    """The cores of this process's affinity mask (a `taskset` or a batch scheduler's limit), or all
    of the machine's where the mask cannot be read."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # not on Linux
        return os.cpu_count() or 1
