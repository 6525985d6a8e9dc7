"""Central and minimum film of Hamrock & Dowson (docs/model.md §6.3), a scene option and the
cross-check of the NVM law.

Hamrock, B. J. and Dowson, D., "Isothermal elastohydrodynamic lubrication of point contacts,
part III -- fully flooded results", J. Lubr. Technol. 99 (1977) 264-276:

    h_c/Rx   = 2.69 U^0.67 G^0.53 W^-0.067 (1 - 0.61 exp(-0.73 k)),
    h_min/Rx = 3.63 U^0.68 G^0.49 W^-0.073 (1 - exp(-0.68 k)),

with the mean speed in U = eta0 (u_s/2)/(E' Rx), G = alpha E', W = F/(E' Rx^2) and their
ellipticity k = 1.03 (Ry/Rx)^0.64. Arguments and units as `nvm.film_central_nvm`.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numba

from ..._speed.compile_policy import KERNEL


class HamrockDowson(NamedTuple):
    """No parameters (one placeholder field: numba types a bundle by its fields)."""

    unused: float = 0.0


Params = HamrockDowson
UNITS = {"unused": "-"}


def pack(options, lubricant) -> HamrockDowson:
    return HamrockDowson()


@numba.njit(**KERNEL)
def ellipticity(Rx, Ry):
    """k = 1.03 (Ry/Rx)^0.64, the ellipticity Hamrock & Dowson used in their fits."""
    return 1.03 * (Ry / Rx) ** 0.64


@numba.njit(**KERNEL)
def film_hamrock_dowson(F, Rx, Ry, E_eff, eta0, alpha_p, u_s):
    """(h_c, h_min) [m] (module docstring); (0, 0) when F <= 0 or u_s <= 0."""
    if F <= 0.0 or u_s <= 0.0:
        return 0.0, 0.0
    U = eta0 * 0.5 * u_s / (E_eff * Rx)
    G = alpha_p * E_eff
    W = F / (E_eff * Rx * Rx)
    k = ellipticity(Rx, Ry)
    h_c = Rx * 2.69 * U**0.67 * G**0.53 * W**-0.067 * (1.0 - 0.61 * math.exp(-0.73 * k))
    h_min = Rx * 3.63 * U**0.68 * G**0.49 * W**-0.073 * (1.0 - math.exp(-0.68 * k))
    return h_c, h_min


@numba.njit(**KERNEL)
def central_film(law, F, Rx, Ry, E_eff, eta0, alpha_p, u_s):
    """The registry's operation: h_c of `film_hamrock_dowson`."""
    return film_hamrock_dowson(F, Rx, Ry, E_eff, eta0, alpha_p, u_s)[0]
