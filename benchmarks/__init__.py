"""Timing scripts: measurements, not tests, and not part of the installed package.

Run from the repository root against the installed `bearingsim`, e.g.
`taskset -c 1 python -m benchmarks.contacts`.
"""

from __future__ import annotations

import time

def best_time(fn, repeat: int = 5, number: int = 20) -> float:
    """Best mean time of `number` calls over `repeat` runs [s]: the machine may be shared,
    and other work only ever makes a run slower, so the quietest run is the measurement."""
    best = float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter()
        for _ in range(number):
            fn()
        best = min(best, (time.perf_counter() - t0) / number)
    return best
