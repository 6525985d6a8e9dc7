"""What the pocket contact calls of a pocket law: `normal_force`, resolved by numba, from the
class of the law's bundle, to the function of that name in the law's module (`LAWS`). Called
from Python it does the same lookup."""

from __future__ import annotations

from numba.extending import overload

from . import LAWS


def normal_force(law, delta, delta_dot, impact_speed):
    """(F_n [N], dF_n/d delta [N/m], dF_n/d delta_dot [N s/m]) of the pocket law of bundle `law`
    at penetration delta [m], approach rate delta_dot [m/s] (+ closing) and remembered impact
    speed [m/s] (0: not tracked); all 0 for delta <= 0."""
    return LAWS.kernel(type(law), "normal_force")(law, delta, delta_dot, impact_speed)


@overload(normal_force, inline="always")
def _normal_force(law, delta, delta_dot, impact_speed):
    function = LAWS.kernel(law, "normal_force")
    return lambda law, delta, delta_dot, impact_speed: function(law, delta, delta_dot, impact_speed)
