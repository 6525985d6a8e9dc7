"""The film laws by code, for the kernels: the one place that maps a law's code (`laws.LAWS`) to
its module's functions. numba compiles the branch taken for a given code into straight code."""

from __future__ import annotations

import numba

from . import LIMITING_SHEAR, eyring, limiting_shear


@numba.njit(cache=True, inline="always")
def stress_scale(law, parameter, p_h):
    """The stress scale tau_s [Pa] of film law `law` (tau = tau_s g s): its module's `stress_scale`."""
    if law == LIMITING_SHEAR:
        return limiting_shear.stress_scale(parameter, p_h)
    return eyring.stress_scale(parameter, p_h)


@numba.njit(cache=True, inline="always")
def response(law, k, r):
    """(g, c) of film law `law` at k = eta/(tau_s h) [s/m] and r = |s| [m/s]: its module's `response`."""
    if law == LIMITING_SHEAR:
        return limiting_shear.response(k, r)
    return eyring.response(k, r)
