"""Scratch arrays that start on a cache line, for the vectorised passes that stream through them.

numpy hands out arrays aligned to 16 bytes, so the 64-byte vectors of the traction's node passes
(AVX-512: eight float64 or sixteen float32 lanes) start at a random offset in a cache line, and
a misaligned vector load reads two lines. Which offset an array gets depends on the process's
allocation history, and so would the run time (docs/performance.md); on a line, every process
gets the fastest offset. Alignment changes no result: the compiled
loops do not peel for it, so every sum runs in the same order at any offset
(tests/test_traction_fast.py).
"""

from __future__ import annotations

import numpy as np

CACHE_LINE = 64  # [bytes]


def empty_aligned(shape, dtype=np.float64) -> np.ndarray:
    """An uninitialised C-contiguous array of `shape` and `dtype` whose first element starts on a
    cache line (a view into a slightly larger byte buffer, which it keeps alive)."""
    dtype = np.dtype(dtype)
    shape = (shape,) if isinstance(shape, (int, np.integer)) else tuple(shape)
    size = int(np.prod(shape, dtype=np.int64)) * dtype.itemsize
    raw = np.empty(size + CACHE_LINE, dtype=np.uint8)
    start = (-raw.ctypes.data) % CACHE_LINE
    return raw[start:start + size].view(dtype).reshape(shape)
