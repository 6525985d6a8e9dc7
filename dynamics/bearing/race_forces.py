"""One ball–race contact of the dynamic model: geometry (§6.1), Hertz normal load with
normal damping (M.24, §6.2), EHD film (§6.3), traction (§6.4), and what the Newton matrix
needs. A numba kernel writing into a caller-owned row `res` (layout RACE_ROW): the time
loop calls it 2Z times per residual and allocates nothing here.

Tangent ingredients (see assembly.py): the normal force depends on the relative position
of ball centre and race point p through the 3x3 stiffness K_p (M.34) and on the relative
normal velocity through c_n n n^T; traction T = (F_x, F_y, M_z) depends on the slip
s = (du0, dv0, w_s) through J_t = -dT/ds (positive definite-ish).
"""

from __future__ import annotations

import math

import numba
import numpy as np

from .._speed.compile_policy import NO_REFCOUNT
from ..contact.hertz import TAB_KH, hermite, table_position
from ..contact.race import (
    OUT_ALPHA, OUT_DELTA, OUT_EX, OUT_EY, OUT_LEVER, OUT_N, OUT_P, OUT_SLIDE, OUT_SPIN,
    OUT_SRR, OUT_U_SUM, ball_race_contact_kernel,
)
from ..lubrication.film import FILM_BATCH_ROWS
from ..lubrication.film_laws import nvm, operations as film_operations
from ..traction.contact import contact_traction

from .bundles import ContactScratch
from .channels import Channel, RowLayout
from .params import (
    FP_ALPHA_P, FP_D, FP_DI, FP_DM, FP_DO, FP_E_EFF, FP_ETA0, FP_MB, FP_MIN_FILM,
    FP_LOAD_EXPONENT, FP_RI, FP_RO, FP_ZETA, FILM_NONE,
    FILM_NVM, IP_FILM, IP_TRACTION,
)
from .race_table import TAB_FILM, TAB_SEMI_AXES, curvature_radii_kernel

# The result row of one ball-race contact; 3x3 blocks are row-major, vectors global.
RACE_ROW = RowLayout(
    Channel("force_ball", 3, "N", "contact force on the ball"),
    Channel("moment_ball", 3, "N.m", "moment on the ball about its centre (incl. the spin moment)"),
    Channel("force_race", 3, "N", "contact force on the race"),
    Channel("moment_race", 3, "N.m", "moment on the race about its centre"),
    Channel("load", 1, "N", "normal load F_n (elastic + damping, >= 0)"),
    Channel("angle", 1, "rad", "contact angle (docs/model.md M.55)"),
    Channel("film", 1, "m", "central film thickness (0: no film)"),
    Channel("slide_roll", 1, "-", "slide-to-roll ratio"),
    Channel("dissipated_power", 1, "W", "power dissipated by traction and normal damping"),
    Channel("stiffness", 9, "N/m", "K_p = -dF_ball/dx_b of the normal force (M.63); tangent only"),
    Channel("damping", 9, "N.s/m", "c_n n n^T; tangent only"),
    Channel("traction_jacobian", 9, "-", "J_t = -d(F_x, F_y, M_z)/d(du0, dv0, w_s); tangent only"),
    Channel("lever_ball", 3, "m", "contact point - ball centre"),
    Channel("lever_race", 3, "m", "contact point - race centre"),
    Channel("normal", 3, "-", "unit normal n, from the contact towards the ball centre"),
    Channel("e_x", 3, "-", "entrainment direction"),
    Channel("e_y", 3, "-", "n x e_x"),
    Channel("active", 1, "-", "1 in contact"),
    Channel("max_pressure", 1, "Pa", "maximum Hertz pressure"),
    Channel("traction_flags", 1, "-", "flag bits of the traction rule (traction/fast.py FLAG_*)"),
    Channel("spin", 1, "rad/s", "spin w_s"),
    Channel("sum_speed", 1, "m/s", "entrainment (sum) speed u_s"),
    Channel("hertz_energy", 1, "J", "elastic energy 2/5 k_h delta^(5/2)"),
    Channel("load_slope", 1, "1/m", "d ln|T|/d delta: traction's dependence on the approach; tangent only"),
    Channel("traction_wrench_ball", 6, "N, N.m", "traction part of the ball's wrench (spatial); tangent only"),
    Channel("traction_wrench_race", 6, "N, N.m", "traction part of the race's wrench (spatial); tangent only"),
    Channel("normal_turn", 9, "1/m", "dn/dx_b: how the normal turns as the ball moves; tangent only"),
)
RC_FB, RC_MB, RC_FR, RC_MR = (RACE_ROW.slot(n) for n in ("force_ball", "moment_ball", "force_race", "moment_race"))
RC_Q, RC_ALPHA, RC_FILM, RC_SRR, RC_PDISS = (
    RACE_ROW.slot(n) for n in ("load", "angle", "film", "slide_roll", "dissipated_power"))
RC_KP, RC_CN, RC_JT = (RACE_ROW.slot(n) for n in ("stiffness", "damping", "traction_jacobian"))
RC_PB, RC_PR, RC_N, RC_EX, RC_EY = (RACE_ROW.slot(n) for n in ("lever_ball", "lever_race", "normal", "e_x", "e_y"))
RC_ACTIVE, RC_PMAX, RC_FLAG, RC_SPIN, RC_USUM, RC_VHZ = (
    RACE_ROW.slot(n) for n in ("active", "max_pressure", "traction_flags", "spin", "sum_speed", "hertz_energy"))
RC_LOAD_SLOPE = RACE_ROW.slot("load_slope")
RC_WTB, RC_WTR = RACE_ROW.slot("traction_wrench_ball"), RACE_ROW.slot("traction_wrench_race")
RC_DN = RACE_ROW.slot("normal_turn")
N_RC = RACE_ROW.size
# A residual-only call clears only the slots it writes or reads: the two runs of slots between
# the tangent-only fields (their descriptions end in "tangent only"), which the tangent pass
# alone reads and a tangent call clears with the rest (clearing the whole row for every
# contact shows in a profile of the time loop)
RC_RESIDUAL_SPANS = ((0, RC_KP), (RC_PB, RC_LOAD_SLOPE))
N_CONTACT_SCRATCH = 27


# What one contact carries from `race_contact_normal` to `race_contact_forces`: the Hertz
# ellipse, the slip, the loads, and the film's inputs (NVM: R_x and its lambda terms at the
# contact angle, read from the race table), so that the time loop can take every contact's
# film in one batch between the two (`assembly._ball_forces`).
(CA_AX, CA_BY, CA_PMAX, CA_DU0, CA_DV0, CA_WS, CA_FN, CA_FEL, CA_DELTA, CA_DDOT, CA_KN, CA_U,
 CA_RX, CA_RI, CA_EI, CA_H00, CA_RP, CA_EP) = range(18)
N_CARRY = 18


def contact_scratch(n: int) -> ContactScratch:
    """Fresh `bundles.ContactScratch` for n ball–race contacts."""
    return ContactScratch(np.zeros((n, N_CONTACT_SCRATCH)), np.zeros(12), np.zeros((n, N_CARRY)),
                          np.zeros((8, n)), np.zeros(n), np.zeros((FILM_BATCH_ROWS, 5 * n)),
                          np.zeros(5 * n, dtype=np.int64))


@numba.njit(**NO_REFCOUNT)
def film_of_carry(carry, alpha, is_outer, fp, ip, film):
    """Central film thickness [m] of one contact from its carry (CA_*), floored at
    FP_MIN_FILM: the NVM law (FILM_NVM) from the table terms `race_contact_normal` read; any
    other law (FILM_CONTACT) by its bundle `film` (`film_laws.operations.central_film`), with
    R_x, R_y from the contact angle alpha. (The time loop takes NVM for all contacts at once:
    `film.film_central_nvm_batch`, then the same floor.)"""
    if ip[IP_FILM] == FILM_NVM:
        terms = (carry[CA_RI], carry[CA_EI], carry[CA_H00], carry[CA_RP], carry[CA_EP])
        h = nvm.central_film_from_terms(carry[CA_FEL], carry[CA_RX], fp[FP_E_EFF], fp[FP_ETA0], fp[FP_ALPHA_P],
                                        carry[CA_U], terms)
        return max(h, fp[FP_MIN_FILM])
    Rx, Ry = curvature_radii_kernel(alpha, is_outer, fp[FP_D], fp[FP_DM], fp[FP_RO] if is_outer else fp[FP_RI])
    h = film_operations.central_film(film, carry[CA_FEL], Rx, Ry, fp[FP_E_EFF], fp[FP_ETA0], fp[FP_ALPHA_P],
                                     carry[CA_U])
    return max(h, fp[FP_MIN_FILM])


@numba.njit(**NO_REFCOUNT)
def race_contact(ball, race, is_outer, fp, ip, table, traction, film, scratch, res, want_tangent):
    """Forces of one ball on one race and (want_tangent) their tangent ingredients, into
    res (RACE_ROW); the tangent-only fields stay zero otherwise: the two phases below with
    this contact's film between them (the time loop takes the film of all contacts at once
    between the phases, `assembly._ball_forces`).

    ball: `bundles.Ball` (centre [m], velocity [m/s], angular velocity [rad/s]); race:
    `bundles.Body` (centre, rotation race -> global, velocity, spatial angular velocity);
    fp, ip: the model's parameter vectors (params.FP_*, IP_*); table: the race's contact
    table (race_table.race_contact_table); traction: the `TractionRule` (the traction law's
    bundle, and the film engine's table and nodes); film: the film law's bundle; scratch: `bundles.ContactScratch` (its first contact and carry rows are used).
    Returns True when in contact.
    """
    cbuf, carry = scratch.contact[0], scratch.carry[0]
    if not race_contact_normal(ball, race, is_outer, fp, ip, table, cbuf, carry, res, want_tangent):
        return False
    h = 0.0
    if ip[IP_FILM] != FILM_NONE:
        h = film_of_carry(carry, res[RC_ALPHA], is_outer, fp, ip, film)
    race_contact_forces(ball, race, fp, ip, traction, cbuf, scratch.traction, carry, h, res, want_tangent)
    return True


@numba.njit(**NO_REFCOUNT, inline="always")
def race_contact_normal(ball, race, is_outer, fp, ip, table, cbuf, carry, res, want_tangent):
    """First phase of one contact: geometry into cbuf (`contact.race`'s OUT_* layout), the
    Hertz load with normal damping and (want_tangent) its stiffness and damping into res
    (which it clears first), the rest of what the second phase needs into carry (CA_*).
    Returns True when in contact."""
    x_b, v_b, w_b = ball.x, ball.v, ball.w
    x_r, R_r, v_r, w_r = race.x, race.R, race.v, race.w
    if want_tangent:
        res[:] = 0.0
    else:  # RC_RESIDUAL_SPANS: the tangent-only slots are the tangent pass's alone
        for lo, hi in RC_RESIDUAL_SPANS:
            for i in range(lo, hi):
                res[i] = 0.0
    d_g = fp[FP_DO] if is_outer else fp[FP_DI]
    r_g = fp[FP_RO] if is_outer else fp[FP_RI]
    ball_race_contact_kernel(x_b, v_b, w_b, x_r, R_r, v_r, w_r, d_g, r_g, fp[FP_D], is_outer, cbuf)
    delta = cbuf[OUT_DELTA]
    res[RC_ALPHA] = cbuf[OUT_ALPHA]
    if delta <= 0.0:
        return False
    n = cbuf[OUT_N:OUT_N + 3]
    p = cbuf[OUT_P:OUT_P + 3]
    sqrt_delta = math.sqrt(delta)
    # k_h and the Hertz semi-axes per sqrt(delta) from the race table (no cube root); the
    # major axis b_y lies across the rolling direction
    j, t, step = table_position(table, cbuf[OUT_ALPHA])
    # columns typed int64, not Literal[int]: numba compiles a callee once per literal argument
    k_h = hermite(table, j, np.int64(TAB_KH), t, step)[0]
    b_y = hermite(table, j, np.int64(TAB_SEMI_AXES), t, step)[0] * sqrt_delta
    a_x = hermite(table, j, np.int64(TAB_SEMI_AXES + 2), t, step)[0] * sqrt_delta
    # relative normal velocity: delta grows when the ball moves against n relative to the race
    vr_p0 = v_r[0] + w_r[1] * (p[2] - x_r[2]) - w_r[2] * (p[1] - x_r[1])
    vr_p1 = v_r[1] + w_r[2] * (p[0] - x_r[0]) - w_r[0] * (p[2] - x_r[2])
    vr_p2 = v_r[2] + w_r[0] * (p[1] - x_r[1]) - w_r[1] * (p[0] - x_r[0])
    delta_dot = -(n[0] * (v_b[0] - vr_p0) + n[1] * (v_b[1] - vr_p1) + n[2] * (v_b[2] - vr_p2))
    k_n = 1.5 * k_h * sqrt_delta
    c_n = 2.0 * fp[FP_ZETA] * math.sqrt(k_n * fp[FP_MB])
    F_el = k_h * delta * sqrt_delta
    F_n = max(F_el + c_n * delta_dot, 0.0)  # no adhesion
    if want_tangent:
        _contact_stiffness(k_n, F_el, delta, n, x_b, x_r, R_r, d_g, cbuf, res)
        if F_n > 0.0:
            # r and c, not j: j is the table position the film's terms are read at below
            # (tests/test_source_checks.py guards against such a loop target)
            for r in range(3):
                for c in range(3):
                    res[RC_CN + 3 * r + c] = c_n * n[r] * n[c]
    slide, ex, ey = cbuf[OUT_SLIDE:OUT_SLIDE + 3], cbuf[OUT_EX:OUT_EX + 3], cbuf[OUT_EY:OUT_EY + 3]
    carry[CA_AX] = a_x
    carry[CA_BY] = b_y
    carry[CA_PMAX] = 1.5 * F_el / (math.pi * a_x * b_y)
    carry[CA_DU0] = slide[0] * ex[0] + slide[1] * ex[1] + slide[2] * ex[2]
    carry[CA_DV0] = slide[0] * ey[0] + slide[1] * ey[1] + slide[2] * ey[2]
    carry[CA_WS] = cbuf[OUT_SPIN]
    carry[CA_FN] = F_n
    carry[CA_FEL] = F_el
    carry[CA_DELTA] = delta
    carry[CA_DDOT] = delta_dot
    carry[CA_KN] = k_n
    carry[CA_U] = max(cbuf[OUT_U_SUM], 1e-6)
    if ip[IP_FILM] == FILM_NVM:
        nvm_terms_into(table, j, t, step, carry)
    return True


@numba.njit(**NO_REFCOUNT)
def nvm_terms_into(table, j, t, step, carry):
    """R_x and the lambda-only NVM terms (`film_laws.nvm.geometry_terms`) at the race table's
    position (j, t, step) of the contact angle (`hertz.table_position`) into carry[CA_RX:CA_EP + 1]."""
    for i in range(6):
        carry[CA_RX + i] = hermite(table, j, TAB_FILM + 2 * i, t, step)[0]


@numba.njit(**NO_REFCOUNT, inline="always")
def race_contact_forces(ball, race, fp, ip, traction, cbuf, tbuf, carry, h, res, want_tangent):
    """Second phase of one contact that touches: traction with the film h [m] (0: none), the
    wrenches on ball and race, and the contact's diagnostics, into res. cbuf and carry as
    `race_contact_normal` left them; tbuf: the traction's scratch (12)."""
    x_b, x_r = ball.x, race.x
    n = cbuf[OUT_N:OUT_N + 3]
    p = cbuf[OUT_P:OUT_P + 3]
    a_x, b_y, p_max = carry[CA_AX], carry[CA_BY], carry[CA_PMAX]
    du0, dv0, w_s = carry[CA_DU0], carry[CA_DV0], carry[CA_WS]
    F_n, F_el, delta, delta_dot, k_n = carry[CA_FN], carry[CA_FEL], carry[CA_DELTA], carry[CA_DDOT], carry[CA_KN]
    acting = ip[IP_TRACTION] != 0
    # traction T = tbuf[0:3] and dT/ds = tbuf[3:12] (row-major), on the ball, by the rule's law
    if acting:
        # the film's transit speed is the mean surface speed, half the sum speed (`traction.inlet`)
        res[RC_FLAG] = contact_traction(traction, F_n, a_x, b_y, p_max, h, du0, dv0, w_s, 0.5 * carry[CA_U], tbuf,
                                        want_tangent)
    else:
        tbuf[:] = 0.0
    _wrenches(res, n, p, x_b, x_r, cbuf, F_n, tbuf, want_tangent)
    if want_tangent and F_n > 0.0 and acting:
        # |T| ~ F_n^e at fixed slip (the law's flag "load_exponent", `traction.laws`)
        res[RC_LOAD_SLOPE] = fp[FP_LOAD_EXPONENT] * k_n / F_n
    for i in range(3):
        res[RC_N + i] = n[i]
        res[RC_EX + i] = cbuf[OUT_EX + i]
        res[RC_EY + i] = cbuf[OUT_EY + i]
    if want_tangent:
        for i in range(9):
            res[RC_JT + i] = -tbuf[3 + i]
    res[RC_Q] = F_n
    res[RC_FILM] = h
    res[RC_SRR] = cbuf[OUT_SRR]
    res[RC_SPIN] = w_s
    res[RC_USUM] = cbuf[OUT_U_SUM]
    res[RC_PMAX] = p_max
    res[RC_VHZ] = 0.4 * F_el * delta  # Hertz elastic energy 2/5 k_h delta^(5/2) [J]
    res[RC_PDISS] = -(tbuf[0] * du0 + tbuf[1] * dv0 + tbuf[2] * w_s) + max(F_n - F_el, 0.0) * delta_dot
    res[RC_ACTIVE] = 1.0


@numba.njit(**NO_REFCOUNT)
def _contact_stiffness(k_n, F_n, delta, n, x_b, x_r, R_r, d_g, cbuf, res):
    """K_p = -dF_ball/dx_b (3x3) of the Hertz force F_n n (M.34), with the normal's rotation
    resolved by direction: across the groove (e_y) the curvature centre C stays put and n
    turns by dx/s; along the circumference (e_g) C follows the ball's azimuth, so n turns by
    (1 - d/(2 rho)) dx/s. s = |C - x_b|, rho = distance of the ball centre from the race
    axis, d = groove curvature-centre diameter. (M.34 neglects dk_h/dalpha; so does this.)"""
    s = cbuf[OUT_LEVER]
    ax0, ax1, ax2 = R_r[0, 2], R_r[1, 2], R_r[2, 2]
    r0, r1, r2 = x_b[0] - x_r[0], x_b[1] - x_r[1], x_b[2] - x_r[2]
    along = r0 * ax0 + r1 * ax1 + r2 * ax2
    r0, r1, r2 = r0 - along * ax0, r1 - along * ax1, r2 - along * ax2
    rho = math.sqrt(r0 * r0 + r1 * r1 + r2 * r2)
    g0, g1, g2 = (ax1 * r2 - ax2 * r1) / rho, (ax2 * r0 - ax0 * r2) / rho, (ax0 * r1 - ax1 * r0) / rho
    ey = cbuf[OUT_EY:OUT_EY + 3]
    k_y = F_n / s
    k_g = F_n * (1.0 - 0.5 * d_g / rho) / s
    e_g = (g0, g1, g2)
    for i in range(3):
        for j in range(3):
            res[RC_KP + 3 * i + j] = k_n * n[i] * n[j] + k_y * ey[i] * ey[j] + k_g * e_g[i] * e_g[j]
            # dn/dx_b = -(e_y e_y^T + (1 - d/(2 rho)) e_g e_g^T) / s (same geometry as above)
            res[RC_DN + 3 * i + j] = -(ey[i] * ey[j] + (1.0 - 0.5 * d_g / rho) * e_g[i] * e_g[j]) / s


@numba.njit(**NO_REFCOUNT)
def _wrenches(res, n, p, x_b, x_r, cbuf, F_n, T, want_tangent):
    """Force on the ball f = F_n n + F_x e_x + F_y e_y at p, its moment about the ball centre
    plus the spin moment M_z n; the race gets the opposite force at p (moment about x_r);
    with want_tangent also the traction part alone (RC_WTB, RC_WTR)."""
    ex = cbuf[OUT_EX:OUT_EX + 3]
    ey = cbuf[OUT_EY:OUT_EY + 3]
    for i in range(3):
        res[RC_FB + i] = F_n * n[i] + T[0] * ex[i] + T[1] * ey[i]
        res[RC_FR + i] = -res[RC_FB + i]
        res[RC_PB + i] = p[i] - x_b[i]
        res[RC_PR + i] = p[i] - x_r[i]
    f0, f1, f2 = res[RC_FB], res[RC_FB + 1], res[RC_FB + 2]
    b0, b1, b2 = res[RC_PB], res[RC_PB + 1], res[RC_PB + 2]
    q0, q1, q2 = res[RC_PR], res[RC_PR + 1], res[RC_PR + 2]
    res[RC_MB] = b1 * f2 - b2 * f1 + T[2] * n[0]
    res[RC_MB + 1] = b2 * f0 - b0 * f2 + T[2] * n[1]
    res[RC_MB + 2] = b0 * f1 - b1 * f0 + T[2] * n[2]
    res[RC_MR] = -(q1 * f2 - q2 * f1) - T[2] * n[0]
    res[RC_MR + 1] = -(q2 * f0 - q0 * f2) - T[2] * n[1]
    res[RC_MR + 2] = -(q0 * f1 - q1 * f0) - T[2] * n[2]
    if not want_tangent:
        return
    # the traction part alone (for the load-coupling tangent)
    t0, t1, t2 = T[0] * ex[0] + T[1] * ey[0], T[0] * ex[1] + T[1] * ey[1], T[0] * ex[2] + T[1] * ey[2]
    res[RC_WTB], res[RC_WTB + 1], res[RC_WTB + 2] = t0, t1, t2
    res[RC_WTB + 3] = b1 * t2 - b2 * t1 + T[2] * n[0]
    res[RC_WTB + 4] = b2 * t0 - b0 * t2 + T[2] * n[1]
    res[RC_WTB + 5] = b0 * t1 - b1 * t0 + T[2] * n[2]
    res[RC_WTR], res[RC_WTR + 1], res[RC_WTR + 2] = -t0, -t1, -t2
    res[RC_WTR + 3] = -(q1 * t2 - q2 * t1) - T[2] * n[0]
    res[RC_WTR + 4] = -(q2 * t0 - q0 * t2) - T[2] * n[1]
    res[RC_WTR + 5] = -(q0 * t1 - q1 * t0) - T[2] * n[2]
