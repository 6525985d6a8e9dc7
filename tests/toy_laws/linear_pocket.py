"""A linear spring-dashpot pocket wall, F_n = k delta + c delta_dot (clamped at 0), as a pocket law."""

from __future__ import annotations

from typing import NamedTuple

import numba


class LinearPocket(NamedTuple):
    k: float  # [N/m]
    c: float  # [N s/m]


Params = LinearPocket
UNITS = {"k": "N/m", "c": "N s/m"}


def pack(hertz_constant, restitution, damping_model="flores", reference_impact_speed=0.1) -> LinearPocket:
    return LinearPocket(1.0e8, 50.0)


@numba.njit(cache=True)
def normal_force(law, delta, delta_dot, impact_speed):
    if delta <= 0.0:
        return 0.0, 0.0, 0.0
    f = law.k * delta + law.c * delta_dot
    if f <= 0.0:
        return 0.0, 0.0, 0.0
    return f, law.k, law.c
