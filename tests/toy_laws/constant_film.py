"""A film of one thickness at every contact, as a film law."""

from __future__ import annotations

from typing import NamedTuple

import numba


class ConstantFilm(NamedTuple):
    h: float  # [m]


Params = ConstantFilm
UNITS = {"h": "m"}


def pack(options, lubricant) -> ConstantFilm:
    return ConstantFilm(3.0e-7)


@numba.njit(cache=True)
def central_film(law, F, Rx, Ry, E_eff, eta0, alpha_p, u_s):
    return law.h if F > 0.0 else 0.0
