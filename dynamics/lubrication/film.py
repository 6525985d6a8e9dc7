"""The time loop's EHD film: the NVM central film of every ball–race contact at once
(docs/model.md §6.3).

The law is `film_laws.nvm`; this is the engine that takes its 16 exp and log for all contacts
in one vectorised pass each (`_speed.simd_math`) instead of one libm call after the other,
several times faster for the 44 contacts of the reference bearing (`python -m benchmarks.film`,
docs/performance.md). Between the passes it calls the law's stage functions, which hold every
constant and step of the formula.
"""

from __future__ import annotations

import math

import numba

from .._speed.compile_policy import VEC
from .._speed.simd_math import exp_array, log_array
from .film_laws import nvm

FILM_INPUT_ROWS = 8  # rows of `film_central_nvm_batch`'s input: F, R_x, u_s and the five NVM terms
FILM_BATCH_ROWS = 13  # rows of `film_central_nvm_batch`'s float scratch, each 5n long


@numba.njit(**VEC)
def film_central_nvm_batch(film_in, n, E_eff, eta0, alpha_p, h, work, iwork):
    """`nvm.central_film_from_terms` for n contacts at once: h[m] [m] of contact m from column m
    of film_in, (FILM_INPUT_ROWS, >= n) float64 whose rows are F > 0 [N], Rx [m], u_s > 0 [m/s]
    and the geometry terms of `nvm.geometry_terms` (ln_RI0, ln_EI0, h00_m4, ln_RP0, ln_EP0);
    E_eff, eta0, alpha_p as there. Agrees with it to ~1e-14 relative (tests/test_film.py).
    work: (FILM_BATCH_ROWS, >= 5n) float64, iwork: (>= 5n,) int64 scratch.
    """
    F, Rx, u_s = film_in[0], film_in[1], film_in[2]
    ln_RI0, ln_EI0, h00_m4, ln_RP0, ln_EP0 = film_in[3], film_in[4], film_in[5], film_in[6], film_in[7]
    arg, lns, x, ex, y, ey, t = work[0], work[1], work[2], work[3], work[4], work[5], work[6]
    ln_RI, ln_EI, ln_RP, ln_EP, s, scratch = work[7], work[8], work[9], work[10], work[11], work[12]
    for m in range(n):
        arg[m], arg[n + m] = nvm.groups(F[m], Rx[m], E_eff, eta0, u_s[m])
    log_array(arg, 2 * n, scratch, iwork, lns)
    piezo = alpha_p > 0.0
    ln_aE = math.log(alpha_p * E_eff) if piezo else 0.0
    for m in range(n):
        ln_RI[m], ln_EI[m], ln_RP[m], ln_EP[m] = nvm.asymptote_logs(
            lns[m], lns[n + m], ln_aE, ln_RI0[m], ln_EI0[m], ln_RP0[m], ln_EP0[m])
        # H_EI/H_RI, H_EI^-4, H_RI^1.5, H_RP^-8, H_EP^-8
        x[m], x[n + m], x[2 * n + m], x[3 * n + m], x[4 * n + m] = nvm.power_logs(ln_RI[m], ln_EI[m], ln_RP[m],
                                                                               ln_EP[m])
    exp_array(x, 5 * n, scratch, iwork, ex)
    for m in range(n):
        x[m] = nvm.blend_exponent(ex[m])
        y[m] = ex[n + m] + h00_m4[m]             # H_EI^-4 + H_00^-4
        y[n + m] = ex[3 * n + m] + ex[4 * n + m] if piezo else 1.0
    exp_array(x, n, scratch, iwork, t)                # exp(blend): 0 below EXP_MIN, as libm's underflow
    log_array(y, 2 * n, scratch, iwork, ey)
    for m in range(n):
        s[m] = nvm.blend_order(t[m])
        x[m] = nvm.elastic_exponent(ey[m])
    exp_array(x, n, scratch, iwork, t)                # (H_EI^-4 + H_00^-4)^(-3/8)
    for m in range(n):
        y[m] = ex[2 * n + m] + t[m]
    log_array(y, n, scratch, iwork, t)
    for m in range(n):
        x[m] = nvm.isoviscous_exponent(s[m], t[m])
        x[n + m] = nvm.piezoviscous_exponent(s[m], ey[n + m])
    exp_array(x, 2 * n, scratch, iwork, t)
    for m in range(n):
        y[m] = t[m] + (t[n + m] if piezo else 0.0)
    log_array(y, n, scratch, iwork, x)
    for m in range(n):
        x[m] = nvm.film_exponent(s[m], x[m], lns[m])
    exp_array(x, n, scratch, iwork, t)
    for m in range(n):
        h[m] = t[m] * Rx[m]
