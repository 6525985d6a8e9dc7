"""A Newtonian film: tau = eta s / h at every slip (no shear thinning), as a traction law."""

from __future__ import annotations

from typing import NamedTuple

import numba


class Newtonian(NamedTuple):
    unused: float = 0.0


Params = Newtonian
UNITS = {"unused": "-"}


def pack(options, lubricant) -> Newtonian:
    return Newtonian()


@numba.njit(cache=True)
def stress_scale(law, p_h):
    """tau_s = 1 Pa: then k = eta/h and tau = k s."""
    return 1.0


@numba.njit(cache=True)
def response(law, k, r):
    """g = k, c = 0: tau = k s, d tau/d s = k I."""
    return k, 0.0
