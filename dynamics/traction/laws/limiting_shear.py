"""Limiting-shear law of Bair & Winer: a linear (Newtonian) film that saturates at a limiting
shear stress tau_L (docs/model.md §6.4, M.79).

Bair, S. and Winer, W. O., "A rheological model for elastohydrodynamic contacts based on primary
laboratory data", J. Lubr. Technol. 101 (1979) 258-265: in steady shear their model reads

    tau = tau_L (1 - exp(-eta |s| / (tau_L h))) s/|s|,

Newtonian (tau = eta |s|/h) at small slip and tau -> tau_L at large slip. tau_L grows in
proportion to the pressure, tau_L = Lambda p (their measurements and those of Höglund give
Lambda ~ 0.05-0.1 for mineral and synthetic oils); here it is taken at the contact's mean Hertz
pressure, tau_L = Lambda 2 p_h / 3, so that the fully sliding contact has the friction
coefficient Lambda. Lambda is `physics.limiting_shear_coefficient`.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numba

# Below this argument x = k r the series of 1 - exp(-x) is used (cancellation otherwise)
SERIES_X = 1e-4




class LimitingShear(NamedTuple):
    """Parameters of the limiting-shear law."""

    coefficient: float  # Lambda: limiting shear stress over pressure [-]


Params = LimitingShear
UNITS = {"coefficient": "-"}


def pack(options, lubricant) -> LimitingShear:
    """Lambda = `physics.limiting_shear_coefficient`."""
    return LimitingShear(float(options.limiting_shear_coefficient))


@numba.njit(cache=True)
def stress_scale(law, p_h):
    """tau_L = Lambda 2 p_h / 3 [Pa]: p_h the maximum Hertz pressure [Pa]."""
    return law.coefficient * (2.0 / 3.0) * p_h


@numba.njit(cache=True)
def response(law, k, r):
    """(g, c) with tau = g s and d tau/d s = g I + c s s^T, for tau_L = 1.

    k = eta/(tau_L h) [s/m], r = |s| [m/s], x = k r: g = (1 - e^-x)/r [s/m] and
    c = (x e^-x - (1 - e^-x))/r^3 [s^3/m^3]. The stress has a kink at s = 0 (its slope k is
    not odd in s), so c grows like 1/r there while c s s^T vanishes; at r = 0 exactly c = 0."""
    x = k * r
    if x < SERIES_X:  # 1 - e^-x = x - x^2/2 + x^3/6, x e^-x - (1 - e^-x) = -x^2/2 + x^3/3
        if r == 0.0:
            return k, 0.0
        return k * (1.0 - 0.5 * x + x * x / 6.0), k * k * (-0.5 + x / 3.0) / r
    e = math.exp(-x)
    return (1.0 - e) / r, (x * e - (1.0 - e)) / (r * r * r)
