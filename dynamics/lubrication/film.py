"""EHD film thickness of an elliptic contact (docs/model.md §6.3).

Two formulas, both numba kernels in SI units:

- Nijenbanning, Venner & Moes (Wear 176, 1994, "Film thickness in elastohydrodynamically
  lubricated elliptic contacts"): central film from the four Moes asymptotes (rigid /
  elastic x isoviscous / piezoviscous) blended as written in §6.3. This is the default.
- Hamrock & Dowson (J. Lubr. Technol. 99, 1977, "Isothermal EHL of point contacts,
  part III"): central and minimum film, a scene option and the cross-check of §6.3.

Conventions (§6.3): x is the entrainment direction, `R_x`, `R_y` the reduced radii of
curvature in x and y, `E_eff` = E' = 2/((1-nu1^2)/E1 + (1-nu2^2)/E2)
(`dynamics.geometry.effective_modulus`), `u_s` the SUM of the surface speeds along x
(Moes' convention); Hamrock-Dowson use the mean speed u_s/2. `eta0` [Pa.s] and `alpha_p`
[1/Pa] are the ambient viscosity and the (approximate) pressure-viscosity coefficient at the
inlet temperature (`Lubricant.eta0`, `Lubricant.alpha_star`).

H_00: §6.3 could not confirm this constant from the paper; 1.8/lambda is used (spec's best
reading). It caps the elastic-isoviscous term where the rigid-isoviscous term takes over,
so it only matters near the RI/EI transition (M of order 1-10); the contacts of the
reference bearing sit at M >~ 100, where changing H_00 by a factor 2 changes H_c by < 0.1 %.

Starvation, thermal inlet reduction and the film's effect on the normal approach are not
modelled (film is reported and used by traction; it does not change the normal load).
"""

from __future__ import annotations

import math

import numba

from .._speed.compile_policy import KERNEL, VEC
from .._speed.simd_math import exp_array, log_array


@numba.njit(**KERNEL)
def moes_parameters(F, Rx, Ry, E_eff, eta0, alpha_p, u_s):
    """Moes dimensionless groups (M, L, lambda) of §6.3.

    M = (F/(E'Rx^2)) (eta0 u_s/(E'Rx))^(-3/4), L = alpha E' (eta0 u_s/(E'Rx))^(1/4),
    lambda = Rx/Ry. F [N], Rx, Ry [m], E_eff [Pa], eta0 [Pa.s], alpha_p [1/Pa], u_s [m/s].
    """
    speed = eta0 * u_s / (E_eff * Rx)
    M = F / (E_eff * Rx * Rx) * speed**-0.75
    L = alpha_p * E_eff * speed**0.25
    return M, L, Rx / Ry


@numba.njit(**KERNEL)
def nvm_asymptotes(M, L, lam):
    """The four Moes asymptotes (H_RI, H_EI, H_RP, H_EP) of §6.3 for lambda = Rx/Ry."""
    c = 1.0 + 0.006 * math.log(lam) + 0.63 * lam ** (4.0 / 7.0)
    H_RI = 145.0 * (1.0 + 0.796 * lam ** (14.0 / 15.0)) ** (-15.0 / 7.0) / lam / (M * M)
    H_EI = 3.18 * c ** (-14.0 / 25.0) * lam ** (-1.0 / 15.0) * M ** (-2.0 / 15.0)
    H_RP = 1.29 * (1.0 + 0.691 * lam) ** (-2.0 / 3.0) * L ** (2.0 / 3.0)
    H_EP = 1.48 * c ** (-7.0 / 20.0) * lam ** (-1.0 / 24.0) * M ** (-1.0 / 12.0) * L**0.75
    return H_RI, H_EI, H_RP, H_EP


@numba.njit(**KERNEL)
def nvm_central_dimensionless(M, L, lam):
    """Central film H_c = (h_c/Rx)(eta0 u_s/(E'Rx))^(-1/2) (NVM 1994 as in §6.3).

    H_00 = 1.8/lambda (see module docstring). L = 0 is allowed (isoviscous).
    """
    H_RI, H_EI, H_RP, H_EP = nvm_asymptotes(M, L, lam)
    H_00 = 1.8 / lam
    s = 1.5 * (1.0 + math.exp(-1.2 * H_EI / H_RI))
    iso = (H_RI**1.5 + (H_EI**-4.0 + H_00**-4.0) ** -0.375) ** (2.0 * s / 3.0)
    if L > 0.0:
        piezo = (H_RP**-8.0 + H_EP**-8.0) ** (-s / 8.0)
    else:
        piezo = 0.0
    return (iso + piezo) ** (1.0 / s)


@numba.njit(**KERNEL)
def film_central_nvm(F, Rx, Ry, E_eff, eta0, alpha_p, u_s):
    """Central film thickness h_c [m] by Nijenbanning-Venner-Moes (docs/model.md §6.3).

    F [N] > 0, Rx, Ry [m], E_eff [Pa], eta0 [Pa.s], alpha_p [1/Pa], u_s [m/s] > 0 (sum of
    surface speeds). Returns 0 when F <= 0 or u_s <= 0 (no contact / no entrainment).

    It works with logarithms: every power x^p becomes exp(p ln x) on logarithms taken once
    (~21 exp/log instead of ~20 pow, which cost more). The time loop
    takes the same formula for all its contacts at once (`film_central_nvm_batch`).
    `nvm_central_dimensionless` is the direct, readable form; tests hold the two equal to
    rounding. Split in two so that a caller with fixed
    curvatures can tabulate the first part: `nvm_geometry_terms` (Rx/Ry only) and
    `film_central_nvm_terms` (load and speed).
    """
    ln_RI0, ln_EI0, h00_m4, ln_RP0, ln_EP0 = nvm_geometry_terms(Rx, Ry)
    return film_central_nvm_terms(F, Rx, E_eff, eta0, alpha_p, u_s, ln_RI0, ln_EI0, h00_m4, ln_RP0, ln_EP0)


@numba.njit(**KERNEL)
def nvm_geometry_terms(Rx, Ry):
    """The parts of the logarithms of the four Moes asymptotes that depend on lambda = Rx/Ry
    alone: (ln_RI0, ln_EI0, (lambda/1.8)^4, ln_RP0, ln_EP0), see `film_central_nvm_terms`."""
    lam = Rx / Ry
    ln_lam = math.log(lam)
    ln_c = math.log(1.0 + 0.006 * ln_lam + 0.63 * math.exp(4.0 / 7.0 * ln_lam))
    ln_RI0 = _LN_145 - 15.0 / 7.0 * math.log(1.0 + 0.796 * math.exp(14.0 / 15.0 * ln_lam)) - ln_lam
    ln_EI0 = _LN_3_18 - 14.0 / 25.0 * ln_c - ln_lam / 15.0
    ln_RP0 = _LN_1_29 - 2.0 / 3.0 * math.log(1.0 + 0.691 * lam)
    ln_EP0 = _LN_1_48 - 0.35 * ln_c - ln_lam / 24.0
    return ln_RI0, ln_EI0, (lam / 1.8) ** 4, ln_RP0, ln_EP0


@numba.njit(**KERNEL)
def film_central_nvm_terms(F, Rx, E_eff, eta0, alpha_p, u_s, ln_RI0, ln_EI0, h00_m4, ln_RP0, ln_EP0):
    """`film_central_nvm` [m] from the geometry terms of `nvm_geometry_terms`:
    ln H_RI = ln_RI0 - 2 ln M, ln H_EI = ln_EI0 - (2/15) ln M, ln H_RP = ln_RP0 + (2/3) ln L,
    ln H_EP = ln_EP0 - (1/12) ln M + (3/4) ln L, H_00^-4 = h00_m4 (H_00 = 1.8/lambda)."""
    if F <= 0.0 or u_s <= 0.0:
        return 0.0
    speed = eta0 * u_s / (E_eff * Rx)
    ln_speed = math.log(speed)
    ln_M = math.log(F / (E_eff * Rx * Rx)) - 0.75 * ln_speed
    ln_RI = ln_RI0 - 2.0 * ln_M
    ln_EI = ln_EI0 - 2.0 / 15.0 * ln_M
    # the blend's exp underflows to 0 for H_EI/H_RI > 621 (well into the elastic regime, where
    # the loaded contacts of the reference bearing sit), and an underflowing exp takes libm's
    # error path (errno): skip the call there, the result is the same 0
    blend = -1.2 * math.exp(ln_EI - ln_RI)
    s = 1.5 * (1.0 + (math.exp(blend) if blend > _EXP_UNDERFLOW else 0.0))
    # (H_EI^-4 + H_00^-4)^(-3/8)
    elastic = math.exp(-0.375 * math.log(math.exp(-4.0 * ln_EI) + h00_m4))
    iso = math.exp(2.0 * s / 3.0 * math.log(math.exp(1.5 * ln_RI) + elastic))
    piezo = 0.0
    if alpha_p > 0.0:
        ln_L = math.log(alpha_p * E_eff) + 0.25 * ln_speed
        ln_RP = ln_RP0 + 2.0 / 3.0 * ln_L
        ln_EP = ln_EP0 - ln_M / 12.0 + 0.75 * ln_L
        piezo = math.exp(-s / 8.0 * math.log(math.exp(-8.0 * ln_RP) + math.exp(-8.0 * ln_EP)))
    H = math.exp(math.log(iso + piezo) / s)
    return H * Rx * math.sqrt(speed)


_LN_145, _LN_3_18, _LN_1_29, _LN_1_48 = math.log(145.0), math.log(3.18), math.log(1.29), math.log(1.48)
_EXP_UNDERFLOW = -746.0  # exp(x) rounds to 0.0 for every x below about -745.13


FILM_INPUT_ROWS = 8  # rows of `film_central_nvm_batch`'s input: F, R_x, u_s and the five NVM terms
FILM_BATCH_ROWS = 13  # rows of `film_central_nvm_batch`'s float scratch, each 5n long


@numba.njit(**VEC)
def film_central_nvm_batch(film_in, n, E_eff, eta0, alpha_p, h, work, iwork):
    """`film_central_nvm_terms` for n contacts at once: h[m] [m] of contact m from column m of
    film_in, (FILM_INPUT_ROWS, >= n) float64 whose rows are F > 0 [N], Rx [m], u_s > 0 [m/s]
    and the geometry terms of `nvm_geometry_terms` (ln_RI0, ln_EI0, h00_m4, ln_RP0, ln_EP0);
    E_eff, eta0, alpha_p as there. Agrees with it to ~1e-14 relative (tests/test_film.py).

    The same formula, its 16 exp and log taken for every contact in one vectorised pass each
    (`_speed.simd_math`) instead of one libm call after the other, several times faster for
    the 44 contacts of the reference bearing (`python -m benchmarks.film`, docs/performance.md).
    work: (FILM_BATCH_ROWS, >= 5n) float64, iwork: (>= 5n,) int64 scratch.
    """
    F, Rx, u_s = film_in[0], film_in[1], film_in[2]
    ln_RI0, ln_EI0, h00_m4, ln_RP0, ln_EP0 = film_in[3], film_in[4], film_in[5], film_in[6], film_in[7]
    arg, lns, x, ex, y, ey, t = work[0], work[1], work[2], work[3], work[4], work[5], work[6]
    ln_RI, ln_EI, ln_RP, ln_EP, s, scratch = work[7], work[8], work[9], work[10], work[11], work[12]
    for m in range(n):
        arg[m] = eta0 * u_s[m] / (E_eff * Rx[m])  # the speed group
        arg[n + m] = F[m] / (E_eff * Rx[m] * Rx[m])  # the load group
    log_array(arg, 2 * n, scratch, iwork, lns)
    piezo = alpha_p > 0.0
    ln_aE = math.log(alpha_p * E_eff) if piezo else 0.0
    for m in range(n):
        ln_speed = lns[m]
        ln_M = lns[n + m] - 0.75 * ln_speed
        ln_L = ln_aE + 0.25 * ln_speed
        ln_RI[m] = ln_RI0[m] - 2.0 * ln_M
        ln_EI[m] = ln_EI0[m] - 2.0 / 15.0 * ln_M
        ln_RP[m] = ln_RP0[m] + 2.0 / 3.0 * ln_L
        ln_EP[m] = ln_EP0[m] - ln_M / 12.0 + 0.75 * ln_L
        x[m] = ln_EI[m] - ln_RI[m]       # H_EI / H_RI
        x[n + m] = -4.0 * ln_EI[m]       # H_EI^-4
        x[2 * n + m] = 1.5 * ln_RI[m]    # H_RI^1.5
        x[3 * n + m] = -8.0 * ln_RP[m]   # H_RP^-8
        x[4 * n + m] = -8.0 * ln_EP[m]   # H_EP^-8
    exp_array(x, 5 * n, scratch, iwork, ex)
    for m in range(n):
        x[m] = -1.2 * ex[m]                      # the blend's exponent
        y[m] = ex[n + m] + h00_m4[m]             # H_EI^-4 + H_00^-4
        y[n + m] = ex[3 * n + m] + ex[4 * n + m] if piezo else 1.0
    exp_array(x, n, scratch, iwork, t)                # exp(blend): 0 below EXP_MIN, as libm's underflow
    log_array(y, 2 * n, scratch, iwork, ey)
    for m in range(n):
        s[m] = 1.5 * (1.0 + t[m])
        x[m] = -0.375 * ey[m]
    exp_array(x, n, scratch, iwork, t)                # (H_EI^-4 + H_00^-4)^(-3/8)
    for m in range(n):
        y[m] = ex[2 * n + m] + t[m]
    log_array(y, n, scratch, iwork, t)
    for m in range(n):
        x[m] = 2.0 * s[m] / 3.0 * t[m]           # ln iso
        x[n + m] = -s[m] / 8.0 * ey[n + m]       # ln piezo
    exp_array(x, 2 * n, scratch, iwork, t)
    for m in range(n):
        y[m] = t[m] + (t[n + m] if piezo else 0.0)
    log_array(y, n, scratch, iwork, x)
    for m in range(n):
        x[m] = x[m] / s[m] + 0.5 * lns[m]        # ln(H sqrt(speed))
    exp_array(x, n, scratch, iwork, t)
    for m in range(n):
        h[m] = t[m] * Rx[m]


@numba.njit(**KERNEL)
def film_central_nvm_direct(F, Rx, Ry, E_eff, eta0, alpha_p, u_s):
    """`film_central_nvm` written directly with powers (the reference twin of the tests)."""
    if F <= 0.0 or u_s <= 0.0:
        return 0.0
    M, L, lam = moes_parameters(F, Rx, Ry, E_eff, eta0, alpha_p, u_s)
    H = nvm_central_dimensionless(M, L, lam)
    return H * Rx * math.sqrt(eta0 * u_s / (E_eff * Rx))


@numba.njit(**KERNEL)
def hamrock_dowson_ellipticity(Rx, Ry):
    """k = 1.03 (Ry/Rx)^0.64, the ellipticity Hamrock & Dowson (1977) used in their fits."""
    return 1.03 * (Ry / Rx) ** 0.64


@numba.njit(**KERNEL)
def film_hamrock_dowson(F, Rx, Ry, E_eff, eta0, alpha_p, u_s):
    """Central and minimum film (h_c, h_min) [m] by Hamrock & Dowson (1977), docs/model.md §6.3.

    h_c/Rx = 2.69 U^0.67 G^0.53 W^-0.067 (1 - 0.61 exp(-0.73 k)),
    h_min/Rx = 3.63 U^0.68 G^0.49 W^-0.073 (1 - exp(-0.68 k)),
    with U = eta0 (u_s/2)/(E'Rx) (mean speed), G = alpha E', W = F/(E'Rx^2),
    k = 1.03 (Ry/Rx)^0.64. Same arguments and units as film_central_nvm.
    """
    if F <= 0.0 or u_s <= 0.0:
        return 0.0, 0.0
    U = eta0 * 0.5 * u_s / (E_eff * Rx)
    G = alpha_p * E_eff
    W = F / (E_eff * Rx * Rx)
    k = hamrock_dowson_ellipticity(Rx, Ry)
    h_c = Rx * 2.69 * U**0.67 * G**0.53 * W**-0.067 * (1.0 - 0.61 * math.exp(-0.73 * k))
    h_min = Rx * 3.63 * U**0.68 * G**0.49 * W**-0.073 * (1.0 - math.exp(-0.68 * k))
    return h_c, h_min


FILM_NVM = 0
FILM_HAMROCK_DOWSON = 1
FILM_CODES = {"nvm": FILM_NVM, "hamrock-dowson": FILM_HAMROCK_DOWSON}


@numba.njit(**KERNEL)
def film_central(method, F, Rx, Ry, E_eff, eta0, alpha_p, u_s):
    """Central film h_c [m] by the method code (FILM_NVM default, FILM_HAMROCK_DOWSON)."""
    if method == FILM_HAMROCK_DOWSON:
        return film_hamrock_dowson(F, Rx, Ry, E_eff, eta0, alpha_p, u_s)[0]
    return film_central_nvm(F, Rx, Ry, E_eff, eta0, alpha_p, u_s)
