"""Regularised Coulomb friction of a dry contact (docs/model.md §6.4, M.78).

Not a film law: the traction follows from the normal load F_n and a friction coefficient mu, so
it has its own kernel rather than a response for the film engine.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numba

from ..._speed.compile_policy import NO_REFCOUNT


class Coulomb(NamedTuple):
    """Parameters of regularised Coulomb friction."""

    mu: float     # friction coefficient [-]
    v_reg: float  # slip speed over which the friction reaches its full value [m/s]


Params = Coulomb
UNITS = {"mu": "-", "v_reg": "m/s"}


def pack(options, lubricant) -> Coulomb:
    """`physics.dry_friction` and `physics.coulomb_regularisation`."""
    return Coulomb(float(options.dry_friction), float(options.coulomb_regularisation))


@numba.njit(**NO_REFCOUNT)
def dry_traction(law, F_n, a_x, b_y, du0, dv0, w_s, out):
    """`coulomb_traction` with the law's mu and v_reg."""
    coulomb_traction(F_n, a_x, b_y, du0, dv0, w_s, law.mu, law.v_reg, out)


@numba.njit(**NO_REFCOUNT)
def coulomb_traction(F_n, a_x, b_y, du0, dv0, w_s, mu, v_reg, out):
    """Regularised Coulomb traction on the ball: T = -mu F_n s/sqrt(|s|^2 + v_reg^2) and a
    spin moment -mu F_n r_s w_s r_s/sqrt((w_s r_s)^2 + v_reg^2), r_s = (3 pi/16) sqrt(a b)
    (Johnson, Contact Mechanics, 1985, §5.8: the spin moment of a Hertzian circle under
    full sliding is 3 pi mu P a / 16). out[0:3] = T, out[3:12] = dT/ds row-major."""
    g2 = du0 * du0 + dv0 * dv0 + v_reg * v_reg
    g = math.sqrt(g2)
    f = mu * F_n / g
    out[0], out[1] = -f * du0, -f * dv0
    out[3] = -f * (1.0 - du0 * du0 / g2)
    out[4] = f * du0 * dv0 / g2
    out[6] = out[4]
    out[7] = -f * (1.0 - dv0 * dv0 / g2)
    r_s = 3.0 * math.pi / 16.0 * math.sqrt(a_x * b_y)
    ws = w_s * r_s
    gs = math.sqrt(ws * ws + v_reg * v_reg)
    out[2] = -mu * F_n * r_s * ws / gs
    out[11] = -mu * F_n * r_s * r_s * v_reg * v_reg / (gs * gs * gs)
    out[5] = out[8] = out[9] = out[10] = 0.0
