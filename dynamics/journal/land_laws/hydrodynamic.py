"""The film alone carries the cage at every eccentricity (docs/model.md §8): no metal contact;
the film formulas are clipped at eps_clip so that they stay finite as eps reaches 1."""

from __future__ import annotations

from typing import NamedTuple

import numba

from ..._speed.compile_policy import KERNEL


class HydrodynamicLand(NamedTuple):
    """No parameters (one placeholder field: numba types a bundle by its fields)."""

    unused: float = 0.0


Params = HydrodynamicLand
UNITS = {"unused": "-"}


def pack(eps0: float) -> HydrodynamicLand:
    return HydrodynamicLand()


@numba.njit(**KERNEL)
def weights(law, eps):
    """Film weights 1, film clearance C, no metal, film terms clipped."""
    return 1.0, 0.0, 1.0, 0.0, 1.0, False, True
