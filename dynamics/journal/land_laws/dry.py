"""Metal alone (docs/model.md §8): Lundberg's line contact with full-slip friction once the cage
reaches the land (eps > 1), no film."""

from __future__ import annotations

from typing import NamedTuple

import numba

from ..._speed.compile_policy import KERNEL


class DryLand(NamedTuple):
    """No parameters (one placeholder field: numba types a bundle by its fields)."""

    unused: float = 0.0


Params = DryLand
UNITS = {"unused": "-"}


def pack(eps0: float) -> DryLand:
    return DryLand()


@numba.njit(**KERNEL)
def weights(law, eps):
    """Film weights 0, metal from eps = 1."""
    return 0.0, 0.0, 0.0, 0.0, 1.0, eps > 1.0, False
