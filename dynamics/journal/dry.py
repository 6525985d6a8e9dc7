"""Dry (metal-to-metal) cage–land contact: Lundberg's line-contact load–deflection (docs/model.md §8).

The guide land and the cage rim touch along a line of length l. Lundberg's relation gives
the approach delta for a load Q; the cage model needs the inverse, Q(delta), which has no
closed form. It is solved by Newton from Palmgren's empirical power law, which is within a
few per cent of Lundberg over the working range (tests/test_journal.py).

Kernels: pure functions of floats, SI units (N, m, Pa). `E_eff` is the Hertz effective
modulus E' = 2 / ((1-nu_a^2)/E_a + (1-nu_b^2)/E_b) (dynamics.geometry.effective_modulus);
for equal materials it is E/(1-nu^2), the combination Lundberg's formula is written with.
"""

from __future__ import annotations

import math

import numba

from .._speed.compile_policy import KERNEL

# Palmgren's power law is an empirical fit for steel on steel (Palmgren, Ball and Roller
# Bearing Engineering, 3rd ed., 1959; quoted with Lundberg's formula in Harris & Kotzalas,
# Essential Concepts of Bearing Technology, 5th ed., ch. 6, line-contact deformation).
# The steel constants E = 207 GPa, nu = 0.3 are the ones those texts use.
PALMGREN_E_EFF_STEEL = 207.0e9 / (1.0 - 0.3**2)  # Pa
PALMGREN_COEFFICIENT = 3.84e-5  # mm N^-0.9 mm^0.8

_NEWTON_MAX_ITERATIONS = 50
_NEWTON_RTOL = 1e-13


@numba.njit(**KERNEL)
def lundberg_deflection(Q, l, E_eff):
    """Lundberg line-contact approach delta(Q) [m] (docs/model.md §8, dry part).

    delta = (2 Q / (pi E' l)) ln(pi E' l^2 / Q), Q [N] > 0 the load on a line of length
    l [m], E' [Pa] the effective modulus (E/(1-nu^2) for equal materials). Returns 0 for
    Q <= 0. Valid while Q < pi E' l^2 / e (where d delta / dQ > 0), i.e. loads of MN for
    cage lands — far beyond any physical cage load.
    """
    if Q <= 0.0:
        return 0.0
    return 2.0 * Q / (math.pi * E_eff * l) * math.log(math.pi * E_eff * l * l / Q)


@numba.njit(**KERNEL)
def lundberg_compliance(Q, l, E_eff):
    """d delta / dQ [m/N] of Lundberg's relation (derivative of `lundberg_deflection`)."""
    a = 2.0 / (math.pi * E_eff * l)
    return a * (math.log(math.pi * E_eff * l * l / Q) - 1.0)


@numba.njit(**KERNEL)
def palmgren_load(delta, l, E_eff):
    """Palmgren's guess Q(delta) [N] for a line contact of length l [m].

    Palmgren: delta[mm] = 3.84e-5 Q^0.9 / l[mm]^0.8 (Q in N), fitted for steel on steel.
    Lundberg's delta depends on Q and E' only through Q/E', so for another material pair
    the steel-fitted load is scaled by E'/E'_steel. Returns 0 for delta <= 0.
    """
    if delta <= 0.0:
        return 0.0
    delta_mm = delta * 1e3
    l_mm = l * 1e3
    q_steel = (delta_mm * l_mm**0.8 / PALMGREN_COEFFICIENT) ** (1.0 / 0.9)
    return q_steel * E_eff / PALMGREN_E_EFF_STEEL


@numba.njit(**KERNEL)
def lundberg_load(delta, l, E_eff):
    """Load Q [N] and stiffness dQ/d delta [N/m] of a line contact of length l [m].

    Inverts Lundberg's relation (`lundberg_deflection`, docs/model.md §8) by Newton from
    Palmgren's guess. delta [m] is the approach; delta <= 0 gives (0, 0).

    delta(Q) is increasing and concave, so from any start Newton lands at or below the
    root after one step and then climbs monotonically; a step to Q <= 0 is halved instead.
    Beyond the curve's maximum delta_max = 2 l / e (millimetres of interference for a
    cage land, i.e. a crashed simulation) the load continues linearly so the solver still
    gets a finite, increasing force.
    """
    if delta <= 0.0:
        return 0.0, 0.0
    q_top = math.pi * E_eff * l * l / math.e  # maximum of delta(Q)
    q_cap = 0.5 * q_top
    delta_cap = lundberg_deflection(q_cap, l, E_eff)
    if delta >= delta_cap:
        k_cap = 1.0 / lundberg_compliance(q_cap, l, E_eff)
        return q_cap + k_cap * (delta - delta_cap), k_cap
    Q = min(palmgren_load(delta, l, E_eff), 0.9 * q_cap)
    for _ in range(_NEWTON_MAX_ITERATIONS):
        residual = lundberg_deflection(Q, l, E_eff) - delta
        step = residual / lundberg_compliance(Q, l, E_eff)
        Q_new = Q - step
        if Q_new <= 0.0:
            Q_new = 0.5 * Q
        converged = abs(Q_new - Q) <= _NEWTON_RTOL * Q_new
        Q = Q_new
        if converged:
            break
    return Q, 1.0 / lundberg_compliance(Q, l, E_eff)
