"""The hybrid land law of the reference paper (docs/model.md §8, its eqs. 28–31): the film
carries the cage up to eps = 1, metal alone from eps = 1 + eps0, and the two are blended in
between. The film formulas use the clearance C (1 + eps0), so they stay finite through the blend.

chi = (eps - 1)/eps0; f_F = exp(2 chi/(chi - 1)) weights the film force, f_C = 1 - chi the film
torque. Both are 1 for eps <= 1 and 0 for eps >= 1 + eps0; f_F is C-infinity at eps = 1 + eps0
and has slope -2/eps0 at eps = 1+.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numba

from ..._speed.compile_policy import KERNEL


class HybridLand(NamedTuple):
    """Parameters of the hybrid land law."""

    eps0: float  # boundary-layer width e0/C [-]


Params = HybridLand
UNITS = {"eps0": "-"}


def pack(eps0: float) -> HybridLand:
    """eps0 = `physics.cage_race_boundary`."""
    return HybridLand(float(eps0))


@numba.njit(**KERNEL)
def hybrid_weights(eps, eps0):
    """(f_F, df_F/deps, f_C, df_C/deps) of the blend (module docstring)."""
    if eps <= 1.0:
        return 1.0, 0.0, 1.0, 0.0
    if eps >= 1.0 + eps0:
        return 0.0, 0.0, 0.0, 0.0
    chi = (eps - 1.0) / eps0
    f_f = math.exp(2.0 * chi / (chi - 1.0))
    df_f = -2.0 * f_f / ((chi - 1.0) ** 2 * eps0)
    return f_f, df_f, 1.0 - chi, -1.0 / eps0


@numba.njit(**KERNEL)
def weights(law, eps):
    """The registry's operation (`land_laws.operations.weights`): the blend's weights, the film
    clearance C (1 + eps0), metal from eps = 1, film terms not clipped."""
    f_f, df_f, f_c, df_c = hybrid_weights(eps, law.eps0)
    return f_f, df_f, f_c, df_c, 1.0 + law.eps0, eps > 1.0, False
