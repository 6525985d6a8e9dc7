"""Hertz with hysteresis damping, the Hunt–Crossley family (docs/model.md §7):

    F_n = k_h delta^(3/2) (1 + c_d delta_dot / v_0),   clamped at >= 0 (no adhesion)

k_h is the Hertz constant of the ball in its pocket (`contact.pocket.pocket_hertz_constant`).
c_d comes from the restitution coefficient e: by default Flores et al. (2011),
c_d = 8(1-e)/(5e), which reproduces e over 0.3–1 better than the Hunt–Crossley 3(1-e)/2 or
Lankarani–Nikravesh 3(1-e^2)/4 factors (both offered). v_0 is the impact (approach) speed the
bearing model remembers per pocket (`bearing.model.track_impacts`), floored at a reference
speed so that a slow, persistent contact (a ball pushing the cage) is not given unbounded
damping; a caller that does not track it passes 0 and gets v_0 = the reference speed.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numba

from ..._speed.compile_policy import KERNEL

DAMPING_MODELS = ("flores", "hunt-crossley", "lankarani-nikravesh")


class HertzHysteresis(NamedTuple):
    """Parameters of the hysteresis-damped Hertz law."""

    k_h: float    # Hertz constant [N/m^1.5]
    c_d: float    # hysteresis factor [-]
    v_ref: float  # floor and default of the impact speed v_0 [m/s]


Params = HertzHysteresis
UNITS = {"k_h": "N/m^1.5", "c_d": "-", "v_ref": "m/s"}


def hysteresis_factor(restitution: float, model: str = "flores") -> float:
    """c_d in F_n = k delta^1.5 (1 + c_d delta_dot / v_0) from the restitution e.

    flores: 8(1-e)/(5e) (Flores, Machado, Silva & Martins, Multibody Syst. Dyn. 25 (2011)
    357–375); hunt-crossley: 3(1-e)/2 (Hunt & Crossley, J. Appl. Mech. 42 (1975) 440);
    lankarani-nikravesh: 3(1-e^2)/4 (J. Mech. Des. 112 (1990) 369).
    """
    if not 0.0 < restitution <= 1.0:
        raise ValueError(f"pocket contact: restitution = {restitution!r} must be in (0, 1]")
    if model == "flores":
        return 8.0 * (1.0 - restitution) / (5.0 * restitution)
    if model == "hunt-crossley":
        return 1.5 * (1.0 - restitution)
    if model == "lankarani-nikravesh":
        return 0.75 * (1.0 - restitution**2)
    raise ValueError(f"pocket contact: damping model {model!r}; allowed: {', '.join(DAMPING_MODELS)}")


def pack(hertz_constant: float, restitution: float, damping_model: str = "flores",
         reference_impact_speed: float = 0.1) -> HertzHysteresis:
    """The bundle from k_h [N/m^1.5], the restitution e [-], the damping model and v_ref [m/s]."""
    if not reference_impact_speed > 0.0:
        raise ValueError(f"pocket contact: reference_impact_speed [m/s] = {reference_impact_speed!r} must be > 0")
    return HertzHysteresis(float(hertz_constant), hysteresis_factor(restitution, damping_model),
                           float(reference_impact_speed))


@numba.njit(**KERNEL)
def hertz_hysteresis_force(delta, delta_dot, impact_speed, k_h, c_d):
    """F_n = k_h delta^1.5 (1 + c_d delta_dot / v_0), clamped at 0, and its slopes: delta [m],
    delta_dot [m/s] (+ closing), v_0 = impact_speed [m/s] > 0, k_h [N/m^1.5], c_d [-].
    Returns (F_n [N], dF_n/d delta [N/m], dF_n/d delta_dot [N s/m]); all 0 for delta <= 0."""
    if delta <= 0.0:
        return 0.0, 0.0, 0.0
    root = math.sqrt(delta)
    elastic = k_h * delta * root
    damping = 1.0 + c_d * delta_dot / impact_speed
    f_n = elastic * damping
    if f_n <= 0.0:  # fast separation: the law would pull, a contact cannot
        return 0.0, 0.0, 0.0
    return f_n, 1.5 * k_h * root * damping, elastic * c_d / impact_speed


@numba.njit(**KERNEL)
def normal_force(law, delta, delta_dot, impact_speed):
    """The registry's operation (`pocket_laws.operations.normal_force`), v_0 floored at v_ref."""
    return hertz_hysteresis_force(delta, delta_dot, max(impact_speed, law.v_ref), law.k_h, law.c_d)
