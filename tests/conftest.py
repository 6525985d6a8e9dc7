"""Test harness: numba's cache keyed by the dynamics sources, as the command line does it
(numba's own per-file cache misses an edit to a kernel's callee in another file)."""

from bearingsim.pipeline.numba_cache import configure_numba_cache

configure_numba_cache()
