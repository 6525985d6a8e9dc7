"""Timing numba's compile from its own events, for the compile benchmarks.

Importing this module imports numba: a caller that sets `NUMBA_CACHE_DIR` does so first.
"""

from __future__ import annotations

import time

from numba.core import event


class Outermost(event.Listener):
    """Seconds between the outermost start and end events of one numba event kind (nested
    events, such as a compilation inside another, count once)."""

    def __init__(self) -> None:
        self.depth, self.seconds, self.t0 = 0, 0.0, 0.0

    def on_start(self, ev) -> None:
        if self.depth == 0:
            self.t0 = time.perf_counter()
        self.depth += 1

    def on_end(self, ev) -> None:
        self.depth -= 1
        if self.depth == 0:
            self.seconds += time.perf_counter() - self.t0
