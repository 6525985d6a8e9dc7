"""Central film of Nijenbanning, Venner & Moes (docs/model.md §6.3): the four Moes asymptotes
(rigid / elastic x isoviscous / piezoviscous) blended.

Nijenbanning, G., Venner, C. H. and Moes, H., "Film thickness in elastohydrodynamically
lubricated elliptic contacts", Wear 176 (1994) 217-229. With the speed group
U = eta0 u_s/(E' Rx) (u_s the sum of the surface speeds), M = (F/(E' Rx^2)) U^(-3/4),
L = alpha E' U^(1/4) and lambda = Rx/Ry:

    H_RI = 145 (1 + 0.796 lambda^(14/15))^(-15/7) lambda^-1 M^-2
    H_EI = 3.18 c^(-14/25) lambda^(-1/15) M^(-2/15),      c = 1 + 0.006 ln lambda + 0.63 lambda^(4/7)
    H_RP = 1.29 (1 + 0.691 lambda)^(-2/3) L^(2/3)
    H_EP = 1.48 c^(-7/20) lambda^(-1/24) M^(-1/12) L^(3/4)
    s = 1.5 (1 + exp(-1.2 H_EI/H_RI))
    H_c = [ (H_RI^(3/2) + (H_EI^-4 + H_00^-4)^(-3/8))^(2s/3) + (H_RP^-8 + H_EP^-8)^(-s/8) ]^(1/s)
    h_c = H_c Rx U^(1/2)

H_00: §6.3 could not confirm this constant from the paper; 1.8/lambda is used (spec's best
reading). It caps the elastic-isoviscous term where the rigid-isoviscous term takes over, so it
only matters near the RI/EI transition (M of order 1-10); the contacts of the reference bearing
sit at M >~ 100, where changing H_00 by a factor 2 changes H_c by < 0.1 %.

The law is written once, in logarithms: every power x^p is exp(p ln x), on logarithms taken
once. The stage functions below hold every constant and every step between one exp or log and
the next; `central_film_from_terms` takes the exp and log of one contact with libm, and the time
loop's batch (`lubrication.film.film_central_nvm_batch`) takes them for every contact at once
in vectorised passes, calling the same stages. The part that depends on lambda alone
(`geometry_terms`) is split off so that a caller with fixed curvatures can tabulate it
(`bearing.race_table`).

Conventions (§6.3): x is the entrainment direction, `Rx`, `Ry` the reduced radii of curvature,
`E_eff` = E' = 2/((1-nu1^2)/E1 + (1-nu2^2)/E2), `eta0` [Pa.s] and `alpha_p` [1/Pa] the ambient
viscosity and pressure-viscosity coefficient at the inlet temperature. Starvation, thermal inlet
reduction and the film's effect on the normal approach are not modelled.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numba

from ..._speed.compile_policy import KERNEL

_LN_145, _LN_3_18, _LN_1_29, _LN_1_48 = math.log(145.0), math.log(3.18), math.log(1.29), math.log(1.48)
EXP_UNDERFLOW = -746.0  # exp(x) rounds to 0.0 for every x below about -745.13


class NVM(NamedTuple):
    """No parameters (one placeholder field: numba types a bundle by its fields)."""

    unused: float = 0.0


Params = NVM
UNITS = {"unused": "-"}


def pack(options, lubricant) -> NVM:
    return NVM()


@numba.njit(**KERNEL)
def geometry_terms(Rx, Ry):
    """The parts of the logarithms of the four asymptotes that depend on lambda = Rx/Ry alone:
    (ln_RI0, ln_EI0, H_00^-4, ln_RP0, ln_EP0), H_00 = 1.8/lambda (`asymptote_logs` adds the rest)."""
    lam = Rx / Ry
    ln_lam = math.log(lam)
    ln_c = math.log(1.0 + 0.006 * ln_lam + 0.63 * math.exp(4.0 / 7.0 * ln_lam))
    ln_RI0 = _LN_145 - 15.0 / 7.0 * math.log(1.0 + 0.796 * math.exp(14.0 / 15.0 * ln_lam)) - ln_lam
    ln_EI0 = _LN_3_18 - 14.0 / 25.0 * ln_c - ln_lam / 15.0
    ln_RP0 = _LN_1_29 - 2.0 / 3.0 * math.log(1.0 + 0.691 * lam)
    ln_EP0 = _LN_1_48 - 0.35 * ln_c - ln_lam / 24.0
    return ln_RI0, ln_EI0, (lam / 1.8) ** 4, ln_RP0, ln_EP0


@numba.njit(cache=True, inline="always")
def groups(F, Rx, E_eff, eta0, u_s):
    """(U, F/(E' Rx^2)): the speed group and the load group, whose logarithms `asymptote_logs` takes."""
    return eta0 * u_s / (E_eff * Rx), F / (E_eff * Rx * Rx)


@numba.njit(cache=True, inline="always")
def asymptote_logs(ln_speed, ln_load, ln_alpha_E, ln_RI0, ln_EI0, ln_RP0, ln_EP0):
    """(ln H_RI, ln H_EI, ln H_RP, ln H_EP) from ln U, ln(F/(E' Rx^2)), ln(alpha E') and the
    geometry terms: ln M = ln load - (3/4) ln U, ln L = ln(alpha E') + (1/4) ln U."""
    ln_M = ln_load - 0.75 * ln_speed
    ln_L = ln_alpha_E + 0.25 * ln_speed
    return (ln_RI0 - 2.0 * ln_M, ln_EI0 - 2.0 / 15.0 * ln_M,
            ln_RP0 + 2.0 / 3.0 * ln_L, ln_EP0 - ln_M / 12.0 + 0.75 * ln_L)


@numba.njit(cache=True, inline="always")
def power_logs(ln_RI, ln_EI, ln_RP, ln_EP):
    """The logarithms of H_EI/H_RI, H_EI^-4, H_RI^(3/2), H_RP^-8 and H_EP^-8."""
    return ln_EI - ln_RI, -4.0 * ln_EI, 1.5 * ln_RI, -8.0 * ln_RP, -8.0 * ln_EP


@numba.njit(cache=True, inline="always")
def blend_exponent(ratio):
    """-1.2 H_EI/H_RI, the exponent of the blend order's exp."""
    return -1.2 * ratio


@numba.njit(cache=True, inline="always")
def blend_order(exp_blend):
    """s = 1.5 (1 + exp(-1.2 H_EI/H_RI)) from that exp."""
    return 1.5 * (1.0 + exp_blend)


@numba.njit(cache=True, inline="always")
def elastic_exponent(ln_elastic_sum):
    """-3/8 ln(H_EI^-4 + H_00^-4): the exponent of (H_EI^-4 + H_00^-4)^(-3/8)."""
    return -0.375 * ln_elastic_sum


@numba.njit(cache=True, inline="always")
def isoviscous_exponent(s, ln_iso_sum):
    """(2s/3) ln(H_RI^(3/2) + (H_EI^-4 + H_00^-4)^(-3/8)): the isoviscous term's exponent."""
    return 2.0 * s / 3.0 * ln_iso_sum


@numba.njit(cache=True, inline="always")
def piezoviscous_exponent(s, ln_piezo_sum):
    """-(s/8) ln(H_RP^-8 + H_EP^-8): the piezoviscous term's exponent."""
    return -s / 8.0 * ln_piezo_sum


@numba.njit(cache=True, inline="always")
def film_exponent(s, ln_total, ln_speed):
    """ln(H_c U^(1/2)) = ln(iso + piezo)/s + ln(U)/2; h_c = Rx exp of it."""
    return ln_total / s + 0.5 * ln_speed


@numba.njit(**KERNEL)
def central_film_from_terms(F, Rx, E_eff, eta0, alpha_p, u_s, terms):
    """h_c [m] from the geometry terms (`geometry_terms`, a 5-tuple); 0 when F <= 0 or u_s <= 0
    (no contact / no entrainment). alpha_p = 0 is the isoviscous film."""
    if F <= 0.0 or u_s <= 0.0:
        return 0.0
    ln_RI0, ln_EI0, h00_m4, ln_RP0, ln_EP0 = terms
    speed, load = groups(F, Rx, E_eff, eta0, u_s)
    ln_speed = math.log(speed)
    piezo_on = alpha_p > 0.0
    ln_aE = math.log(alpha_p * E_eff) if piezo_on else 0.0
    ln_RI, ln_EI, ln_RP, ln_EP = asymptote_logs(ln_speed, math.log(load), ln_aE, ln_RI0, ln_EI0, ln_RP0, ln_EP0)
    ratio, ei_m4, ri_15, rp_m8, ep_m8 = power_logs(ln_RI, ln_EI, ln_RP, ln_EP)
    # the blend's exp underflows to 0 for H_EI/H_RI > 621 (well into the elastic regime), and an
    # underflowing exp takes libm's error path (errno): skip the call there, the result is 0
    blend = blend_exponent(math.exp(ratio))
    s = blend_order(math.exp(blend) if blend > EXP_UNDERFLOW else 0.0)
    elastic = math.exp(elastic_exponent(math.log(math.exp(ei_m4) + h00_m4)))
    iso = math.exp(isoviscous_exponent(s, math.log(math.exp(ri_15) + elastic)))
    piezo = math.exp(piezoviscous_exponent(s, math.log(math.exp(rp_m8) + math.exp(ep_m8)))) if piezo_on else 0.0
    return Rx * math.exp(film_exponent(s, math.log(iso + piezo), ln_speed))


@numba.njit(**KERNEL)
def film_central_nvm(F, Rx, Ry, E_eff, eta0, alpha_p, u_s):
    """Central film thickness h_c [m] (module docstring): F [N], Rx, Ry [m], E_eff [Pa],
    eta0 [Pa.s], alpha_p [1/Pa], u_s [m/s] (sum of surface speeds); 0 when F <= 0 or u_s <= 0."""
    return central_film_from_terms(F, Rx, E_eff, eta0, alpha_p, u_s, geometry_terms(Rx, Ry))


@numba.njit(**KERNEL)
def central_film(law, F, Rx, Ry, E_eff, eta0, alpha_p, u_s):
    """The registry's operation (`film_laws.operations.central_film`): `film_central_nvm`."""
    return film_central_nvm(F, Rx, Ry, E_eff, eta0, alpha_p, u_s)
