"""Contact kernels, bodies, hinge joint, HHT-α integrator, bearing model, quasi-static
solver (MODEL.md §4–§10). Stands alone: never imports fe_model or pipeline."""

from ._numba_cache import configure_numba_cache

configure_numba_cache()
