"""Eyring shear-thinning law (docs/model.md §6.4, M.72): tau = tau0 asinh(eta |s| / (tau0 h)) s/|s|.

A law is the shear stress of the film at one point as a function of the sliding velocity s
there, in the form the traction integrals take: tau = tau_s g(k, r) s with r = |s| [m/s],
k = eta(p) / (tau_s h) [s/m] and tau_s the law's stress scale [Pa] (here the Eyring stress tau0).
`response` returns g and c, where d tau/d s = tau_s (g I + c s s^T): the same two functions
serve the reference quadrature and the fast engine (dynamics/traction/fast.py).
"""

from __future__ import annotations

import math

import numba

# Below this Eyring argument x = k r the series of asinh is used: it keeps tiny slips exact
# (relative error ~x^6/40 < 1e-25) where asinh(x)/x would lose digits to cancellation.
SERIES_X = 1e-4


@numba.njit(cache=True, inline="always")
def stress_scale(tau0, p_h):
    """The law's stress scale [Pa]: the Eyring stress tau0, whatever the pressure."""
    return tau0


@numba.njit(cache=True, inline="always")
def response(k, r):
    """(g, c) with tau = g s and d tau/d s = g I + c s s^T, for tau0 = 1.

    k = eta/(tau0 h) [s/m], r = |s| [m/s]. g = asinh(k r)/r [s/m],
    c = (k r/sqrt(1+(kr)^2) - asinh(k r))/r^3 [s^3/m^3] (c s s^T stays bounded as r -> 0).
    """
    x = k * r
    if x < SERIES_X:
        x2 = x * x
        return k * (1.0 - x2 / 6.0), k * k * k * (-1.0 / 3.0 + 0.3 * x2)
    ash = math.asinh(x)
    return ash / r, (x / math.sqrt(1.0 + x * x) - ash) / (r * r * r)
