"""What the kernels call of a film law: `central_film`, resolved by numba, from the class of the
law's bundle, to the function of that name in the law's module (`LAWS`, `dynamics.registry`).
Called from Python it does the same lookup."""

from __future__ import annotations

from numba.extending import overload

from . import LAWS


def central_film(law, F, Rx, Ry, E_eff, eta0, alpha_p, u_s):
    """Central film h_c [m] of a contact by the law of bundle `law`: load F [N], reduced radii
    Rx, Ry [m], E' [Pa], eta0 [Pa.s], alpha* [1/Pa], u_s [m/s] the sum of the surface speeds."""
    return LAWS.kernel(type(law), "central_film")(law, F, Rx, Ry, E_eff, eta0, alpha_p, u_s)


@overload(central_film, inline="always")
def _central_film(law, F, Rx, Ry, E_eff, eta0, alpha_p, u_s):
    function = LAWS.kernel(law, "central_film")
    return lambda law, F, Rx, Ry, E_eff, eta0, alpha_p, u_s: function(law, F, Rx, Ry, E_eff, eta0, alpha_p, u_s)
