"""No traction: the ball–race contacts carry their normal load only (a study's ablation)."""

from __future__ import annotations

from typing import NamedTuple

import numba

from ..._speed.compile_policy import NO_REFCOUNT


class NoTraction(NamedTuple):
    """No parameters (one placeholder field: numba types a bundle by its fields)."""

    unused: float = 0.0


Params = NoTraction
UNITS = {"unused": "-"}


def pack(options, lubricant) -> NoTraction:
    return NoTraction()


@numba.njit(**NO_REFCOUNT)
def dry_traction(law, F_n, a_x, b_y, du0, dv0, w_s, out):
    """Zero force, moment and Jacobian."""
    for i in range(12):
        out[i] = 0.0
