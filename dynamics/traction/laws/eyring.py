"""Eyring shear-thinning law (docs/model.md §6.4, M.72): tau = tau0 asinh(eta |s| / (tau0 h)) s/|s|.

A film law gives the shear stress of the film at one point as a function of the sliding velocity
s there, in the form the traction integrals take: tau = tau_s g(k, r) s with r = |s| [m/s],
k = eta(p) / (tau_s h) [s/m] and tau_s the law's stress scale [Pa] (here the Eyring stress tau0).
`response` returns g and c, where d tau/d s = tau_s (g I + c s s^T).

The law is stated once, in the node functions `argument`, `stress_factor` and `stress_slope`:
the reference quadrature reaches them through `response`, and the fast engine
(dynamics/traction/fast.py) calls them in its vectorised passes, in float64 or float32 (they
compute in the width of their arguments), with asinh x = ln(x + sqrt(1 + x^2)) taken there by
a vectorisable log.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numba

from ..._speed.width import like

# Below this argument x = k r the series are used: asinh(x)/x = 1 - x^2/6 + 3x^4/40 (next term
# 5x^6/112 < 5e-14 here) and (x/sqrt(1+x^2) - asinh x)/x^3 = -1/3 + 3x^2/10 - 15x^4/56, which
# would otherwise cancel to a few digits
SERIES_X = 1e-2
# x is clamped here so that x^2 cannot overflow, in float32 either (3.4e38): the stress is then
# 42 tau0, and no film the model accepts comes near it
ARGUMENT_MAX = 1e18


class Eyring(NamedTuple):
    """Parameters of the Eyring law."""

    tau0: float  # Eyring stress [Pa]


Params = Eyring
UNITS = {"tau0": "Pa"}


def pack(options, lubricant) -> Eyring:
    """The lubricant's Eyring stress (`Lubricant.eyring_stress`)."""
    return Eyring(float(lubricant.eyring_stress))


@numba.njit(cache=True)
def stress_scale(law, p_h):
    """The law's stress scale [Pa]: the Eyring stress tau0, whatever the pressure."""
    return law.tau0


@numba.njit(cache=True, inline="always")
def argument(k, r):
    """The Eyring argument x = k r = eta |s|/(tau0 h), clamped at ARGUMENT_MAX."""
    return min(k * r, like(k, ARGUMENT_MAX))


@numba.njit(cache=True, inline="always")
def stress_factor(k, r, x, ash):
    """g = asinh(x)/r [s/m] (tau/tau0 = g s) from k, r, x = `argument(k, r)` and ash = asinh x;
    its series below SERIES_X. The division's operand is 1 where the series is taken, so that a
    vectorised select never divides by a zero r."""
    small = x < like(x, SERIES_X)
    x2 = x * x
    series = k * (like(x, 1.0) - x2 * (like(x, 1.0 / 6.0) - like(x, 3.0 / 40.0) * x2))
    return series if small else ash / (like(r, 1.0) if small else r)


@numba.njit(cache=True, inline="always")
def stress_slope(k, r, x, root, ash):
    """c = (x/sqrt(1 + x^2) - asinh x)/r^3 [s^3/m^3] (d tau/d s = tau0 (g I + c s s^T)) from k,
    r, x, root = sqrt(1 + x^2) and ash = asinh x; its series below SERIES_X (c s s^T stays
    bounded as r -> 0)."""
    small = x < SERIES_X
    x2 = x * x
    inv_r = 1.0 / (1.0 if small else r)
    series = k * k * k * (-1.0 / 3.0 + x2 * (0.3 - 15.0 / 56.0 * x2))
    return series if small else (x / root - ash) * inv_r * inv_r * inv_r


@numba.njit(cache=True)
def response(law, k, r):
    """(g, c) with tau = tau0 g s and d tau/d s = tau0 (g I + c s s^T).

    k = eta/(tau0 h) [s/m], r = |s| [m/s]. g = asinh(k r)/r [s/m],
    c = (k r/sqrt(1+(kr)^2) - asinh(k r))/r^3 [s^3/m^3].
    """
    x = argument(k, r)
    root = math.sqrt(1.0 + x * x)
    ash = math.asinh(x)
    return stress_factor(k, r, x, ash), stress_slope(k, r, x, root, ash)
