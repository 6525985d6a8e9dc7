"""What the short journal bearing calls of a land law: `weights`, resolved by numba, from the
class of the law's bundle, to the function of that name in the law's module (`LAWS`). Called
from Python it does the same lookup."""

from __future__ import annotations

from numba.extending import overload

from . import LAWS


def weights(law, eps):
    """(f_F, df_F/deps, f_C, df_C/deps, film clearance / C, metal can touch, film clipped) at
    eccentricity ratio eps = e/C of the land law of bundle `law`: the film force is weighted by
    f_F and the metal load by 1 - f_F, the film torque by f_C and the metal friction torque by
    1 - f_C."""
    return LAWS.kernel(type(law), "weights")(law, eps)


@overload(weights, inline="always")
def _weights(law, eps):
    function = LAWS.kernel(law, "weights")
    return lambda law, eps: function(law, eps)
