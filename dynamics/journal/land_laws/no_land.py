"""No cage–land contact at all (a study's ablation): the cage is held by its pockets only."""

from __future__ import annotations

from typing import NamedTuple

import numba

from ..._speed.compile_policy import KERNEL


class NoLand(NamedTuple):
    """No parameters (one placeholder field: numba types a bundle by its fields)."""

    unused: float = 0.0


Params = NoLand
UNITS = {"unused": "-"}


def pack(eps0: float) -> NoLand:
    return NoLand()


@numba.njit(**KERNEL)
def weights(law, eps):
    """No film, no metal."""
    return 0.0, 0.0, 0.0, 0.0, 1.0, False, False
