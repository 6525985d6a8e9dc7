"""Half film, half metal at every eccentricity, as a land law: film force and torque weighted
0.5, metal from eps = 1, film clearance C."""

from __future__ import annotations

from typing import NamedTuple

import numba


class HalfFilmLand(NamedTuple):
    unused: float = 0.0


Params = HalfFilmLand
UNITS = {"unused": "-"}


def pack(eps0) -> HalfFilmLand:
    return HalfFilmLand()


@numba.njit(cache=True)
def weights(law, eps):
    return 0.5, 0.0, 0.5, 0.0, 1.0, eps > 1.0, True
