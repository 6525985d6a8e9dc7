"""Zeroed output buffers in ordinary pages (docs/model.md §9, *Output buffers*).

numpy asks the kernel for transparent huge pages on every array of 4 MB or more
(madvise(MADV_HUGEPAGE)). Where the kernel's THP `defrag` setting is `madvise` (the default of
most Linux distributions), the first write to each 2 MB page of such an array then waits for
the kernel to compact memory into a free huge page. The step-end records of a 0.8 s run of the
reference bearing are ≈ 400 MB written a row at a time inside the time loop, so that first
touch can cost a tenth of the integration, ten times what it costs in 4 KiB pages
(docs/performance.md). An anonymous memory map is zero-filled like
`np.zeros`, but numpy does not advise it, so it is backed by ordinary pages on every platform.
"""

from __future__ import annotations

import mmap

import numpy as np


def zeroed(shape, dtype=np.float64) -> np.ndarray:
    """A zero-filled, writable, C-contiguous array backed by an anonymous memory map (module
    docstring); it owns the map, which is released with the last view of the array."""
    shape = (shape,) if np.isscalar(shape) else tuple(shape)
    dtype = np.dtype(dtype)
    size = int(np.prod(shape, dtype=np.int64)) * dtype.itemsize
    if size == 0:
        return np.zeros(shape, dtype=dtype)
    return np.frombuffer(mmap.mmap(-1, size), dtype=dtype).reshape(shape)
