"""The bearing's residual and its tangents as two numba kernels: `evaluate_bearing` gives M a,
g(t, q, v) and the diagnostics and, on request, calls `bearing_tangents` for the block-arrow
tangents K_t = -dg/dq, C_t = -dg/dv (docs/model.md §4–§9, paper eq. 8).

Per evaluation: 2Z ball–race contacts (race_forces), Z ball–pocket contacts and one
cage–race journal (cage_forces), the viscoelastic hinge (M.19–M.20), external loads on
the inner race, gyroscopic terms, and the prescribed inner-race spin (row replaced).
Every contact force acts equal and opposite on both bodies at the contact point.

The kernels take named bundles (bundles.py); coordinates follow layout.py and the
diagnostics `diag` the channel table of channels.py.
"""

from __future__ import annotations

import numba
import numpy as np

from .._speed.compile_policy import FIRST_CLASS, INTERNAL, NO_REFCOUNT, WITH_REFCOUNT
from ..contact.pocket import (
    P_OUT_APPROACH, P_OUT_DFN_DRATE, P_OUT_FRICTION_POWER, P_OUT_IN_CONTACT,
)
from ..lubrication.film import film_central_nvm_batch
from ..multibody.crv import crv_to_matrix_into, skew
from ..multibody.hinge import add_hinge_force, hinge_energy, hinge_forces
from ..multibody.joints import prescribe_velocity_residual
from ..multibody.rigid_body import gyroscopic_damping
from ..multibody.small import add_into, eye3, mm, mtv_into, mv, mv_into

from .bundles import Ball, Bodies, Body
from .cage_forces import (journal_diag, journal_forces, journal_race_tangent, journal_tangent, pocket_diag,
                          pocket_forces, pocket_tangent)
from .channels import (
    DB, DB_AI, DB_HI, DB_PMI, DB_QI, DB_SRRI, DG_DRIVE, DG_FLAGS, DG_P_DISS, DG_P_DRIVE, DG_P_EXT,
    DG_V_HERTZ, DG_V_HINGE, N_DG,
)
from .layout import BALL_DOF, CAGE_BORDER, CAGE_DOF, INNER_BORDER, RACE_DOF
from .params import (
    FP_D, FP_FX, FP_FZ, FP_JB, FP_JCX, FP_JCZ, FP_JIX, FP_JIZ, FP_MB, FP_MC, FP_MI, FP_MY,
    FP_MY_STEP, FP_OMEGA_I, FP_OMEGA_O, FP_T_LOAD_STEP, IP_CAGE, IP_GYRO, IP_HINGE, IP_JOURNAL, IP_Z,
    FP_ALPHA_P, FP_E_EFF, FP_ETA0, FP_MIN_FILM, FILM_CONTACT, FILM_NVM, IP_FILM,
)
from .race_forces import (
    RC_ACTIVE, RC_ALPHA, RC_CN, RC_DN, RC_EX, RC_EY, RC_FB, RC_FILM, RC_FLAG,
    RC_FR, RC_JT, RC_KP, RC_LOAD_SLOPE, RC_MB, RC_MR, RC_N, RC_PB, RC_PDISS, RC_PMAX, RC_PR, RC_Q,
    RC_SRR, RC_VHZ, RC_WTB, RC_WTR, CA_FEL, CA_RI, CA_RX, CA_U, film_of_carry, race_contact_forces,
    race_contact_normal,
)
from .tangents import add_congruent, add_pair, point_map, slip_map


def mass_diagonal(fp, ip, n):
    """Constant diagonal mass matrix (balls, inner race, cage; material inertias)."""
    Z = int(ip[IP_Z])
    m = np.zeros(n)
    for k in range(Z):
        b = BALL_DOF * k
        m[b:b + 3] = fp[FP_MB]
        m[b + 3:b + 6] = fp[FP_JB]
    o = BALL_DOF * Z
    m[o:o + 3] = fp[FP_MI]
    m[o + 3:o + 6] = (fp[FP_JIX], fp[FP_JIX], fp[FP_JIZ])
    if ip[IP_CAGE]:
        c = o + RACE_DOF
        m[c:c + 3] = fp[FP_MC]
        m[c + 3:c + 6] = (fp[FP_JCX], fp[FP_JCX], fp[FP_JCZ])
    return m


@numba.njit(**FIRST_CLASS)
def evaluate_bearing(t, q, v, a, data, want_tangent, ma, g, diag, K, C):
    """Fill ma = M a, g = g(t, q, v), diag (channels.py) and, when want_tangent, the
    tangent blocks K, C (`linear_solvers.Blocks`). data: `bundles.BearingData` (the model's
    arrays and its tangent kernel). Returns the drive moment [N m] that holds the inner-race
    spin (M.52).

    One kernel for the Newton iterations' residual-only calls and the refactorisations' tangent
    calls, with want_tangent a run-time flag. The residual allocates nothing and runs without
    reference counting (`NO_REFCOUNT`); with want_tangent the contact rows keep their tangent
    ingredients, and the tangent blocks are then filled by `bearing_tangents`, which this kernel
    calls as a first-class function value (`data.tangents`): the two are separate libraries that
    compile apart, in two processes on a machine's first run (docs/performance.md, *Compiling*)."""
    model = data.arrays
    ip = model.ip
    g[:] = 0.0
    diag[:] = 0.0
    for i in range(ma.shape[0]):
        ma[i] = model.mass[i] * a[i]
    # the model's scratch (`bundles.ResidualWork`), not fresh arrays: ~16 allocations per call
    # with their reference counts would show in a profile of the run
    work = model.work
    _turn_bodies(q, v, model)
    bodies = _bodies(q, v, model)
    loads = work.loads
    for i in range(3):
        loads.F_inner[i] = 0.0
        loads.M_inner[i] = 0.0
        loads.F_cage[i] = 0.0
        loads.M_cage[i] = 0.0
    rows = work.rows  # one row per ball-race contact: inner 2k, outer 2k + 1
    pocket_rows = work.pocket_rows
    _ball_forces(q, v, model, bodies, work.scratch, rows, pocket_rows, g, diag, loads, bool(want_tangent))
    drive = _border(t, v, model, bodies, loads, ma, g, diag)
    if want_tangent:
        data.tangents(q, v, model, K, C)
    return drive


@numba.njit(**FIRST_CLASS, **INTERNAL)  # called only as a first-class function value
def bearing_tangents(q, v, model, K, C):
    """The tangent blocks K = -dg/dq, C = -dg/dv (`linear_solvers.Blocks`) at the state that
    `evaluate_bearing` has just evaluated with want_tangent, from what it left in the model's
    scratch (`bundles.ResidualWork`: the contact and pocket rows, the border bodies' rotations,
    the material moments, the cage–land row). model: `bundles.ModelArrays`. Returns 0.0.

    The tangent terms build small arrays: they are kernels with reference counting
    (`_ball_tangents`, `_hinge_tangent`, `_inner_race_tangent`, `_cage_tangent`), added in a
    fixed order (balls, hinge, inner race, cage, cage land)."""
    for M in (K, C):
        M.D[:] = 0.0
        M.E[:] = 0.0
        M.F[:] = 0.0
        M.B[:] = 0.0
    bodies = _bodies(q, v, model)
    work = model.work
    _ball_tangents(v, model, bodies, work.rows, work.pocket_rows, q, K, C)
    _border_tangents(v, model, bodies, K.B, C.B)
    return 0.0


@numba.njit(cache=True, inline="always")
def _turn_bodies(q, v, model):
    """The rotations and spatial angular velocities of the inner race and the cage at (q, v),
    and the outer race's speed, into the model's scratch (`_bodies` reads them)."""
    fp, ip, work = model.fp, model.ip, model.work
    o_i = BALL_DOF * ip[IP_Z]
    crv_to_matrix_into(q[o_i + 3:o_i + 6], work.R_inner)
    mv_into(work.R_inner, v[o_i + 3:o_i + 6], work.w_inner)
    work.outer.w[2] = fp[FP_OMEGA_O]  # the parameters are the one source of the outer race's speed
    if ip[IP_CAGE]:
        o_c = o_i + RACE_DOF
        crv_to_matrix_into(q[o_c + 3:o_c + 6], work.R_cage)
        mv_into(work.R_cage, v[o_c + 3:o_c + 6], work.w_cage)


@numba.njit(cache=True, inline="always")
def _bodies(q, v, model):
    """The inner race, outer race and cage as `bundles.Bodies`: views of q and v and the
    rotations `_turn_bodies` left in the model's scratch."""
    ip, work = model.ip, model.work
    o_i = BALL_DOF * ip[IP_Z]
    inner = Body(q[o_i:o_i + 3], work.R_inner, v[o_i:o_i + 3], work.w_inner)
    cage = inner  # a placeholder of the same type: read only when the bearing has a cage
    if ip[IP_CAGE]:
        o_c = o_i + RACE_DOF
        cage = Body(q[o_c:o_c + 3], work.R_cage, v[o_c:o_c + 3], work.w_cage)
    return Bodies(inner, work.outer, cage)


@numba.njit(**NO_REFCOUNT, **INTERNAL)
def _ball_forces(q, v, model, bodies, scratch, rows, pocket_rows, g, diag, loads, want_tangent):
    """Forces of every ball's race and pocket contacts into g, the wrench sums on the inner
    race and the cage (`loads`) and diag; the contact rows (with their tangent ingredients
    when want_tangent) stay in rows (2k inner, 2k + 1 outer) and, with a cage, pocket_rows
    for the tangent pass. Allocation-free and without reference counting
    (dynamics/_speed/compile_policy.py): this loop, with its per-ball views, is the hot path of
    every residual.

    Three passes: every ball–race contact's geometry and normal load (`race_contact_normal`);
    the NVM film of all of them at once (`film.film_central_nvm_batch`, whose exp and log
    vectorise over the contacts);
    then each contact's traction and wrenches (`race_contact_forces`) and each ball's pockets.
    """
    fp, ip, races, cage = model.fp, model.ip, model.races, model.cage
    Z = ip[IP_Z]
    film = ip[IP_FILM]
    film_in = scratch.film_in
    for k in range(Z):
        b = BALL_DOF * k
        ball = Ball(q[b:b + 3], v[b:b + 3], v[b + 3:b + 6])
        for j in range(2):
            c = 2 * k + j
            res = rows[c]
            # one call site with a run-time is_outer: two call sites with the constants True and
            # False made numba compile the contact kernels twice (see `_ball_tangents`)
            is_outer = j == 1
            carry = scratch.carry[c]
            hit = race_contact_normal(ball, bodies.outer if is_outer else bodies.inner, is_outer, fp, ip,
                                      races.outer if is_outer else races.inner, scratch.contact[c], carry, res,
                                      want_tangent)
            diag[N_DG + DB * k + DB_AI + j] = res[RC_ALPHA]
            res[RC_ACTIVE] = 1.0 if hit else 0.0
            if film == FILM_NVM:
                if hit:
                    film_in[0, c] = carry[CA_FEL]
                    film_in[1, c] = carry[CA_RX]
                    film_in[2, c] = carry[CA_U]
                    for i in range(5):
                        film_in[3 + i, c] = carry[CA_RI + i]
                else:  # any finite film: the batch has no branches, and this result is not read
                    film_in[0, c] = film_in[1, c] = film_in[2, c] = 1.0
                    for i in range(5):
                        film_in[3 + i, c] = 0.0
    if film == FILM_NVM:
        film_central_nvm_batch(film_in, 2 * Z, fp[FP_E_EFF], fp[FP_ETA0], fp[FP_ALPHA_P], scratch.film_h,
                               scratch.film_work, scratch.film_iwork)
    for k in range(Z):
        b = BALL_DOF * k
        ball = Ball(q[b:b + 3], v[b:b + 3], v[b + 3:b + 6])
        d = N_DG + DB * k
        for j in range(2):
            c = 2 * k + j
            res = rows[c]
            if res[RC_ACTIVE] == 0.0:
                continue
            is_outer = j == 1
            carry = scratch.carry[c]
            h = 0.0
            if film == FILM_NVM:
                h = max(scratch.film_h[c], fp[FP_MIN_FILM])
            elif film == FILM_CONTACT:
                h = film_of_carry(carry, res[RC_ALPHA], is_outer, fp, ip, model.film)
            race_contact_forces(ball, bodies.outer if is_outer else bodies.inner, fp, ip, model.traction,
                                scratch.contact[c], scratch.traction, carry, h, res, want_tangent)
            for i in range(3):
                g[b + i] += res[RC_FB + i]
                g[b + 3 + i] += res[RC_MB + i]
                if j == 0:
                    loads.F_inner[i] += res[RC_FR + i]
                    loads.M_inner[i] += res[RC_MR + i]
            diag[d + DB_QI + j] = res[RC_Q]
            diag[d + DB_HI + j] = res[RC_FILM]
            diag[d + DB_SRRI + j] = res[RC_SRR]
            diag[d + DB_PMI + j] = res[RC_PMAX]
            diag[DG_P_DISS] += res[RC_PDISS]
            diag[DG_V_HERTZ] += res[RC_VHZ]
            if res[RC_FLAG] != 0.0:
                diag[DG_FLAGS] += 1.0
        if ip[IP_CAGE]:
            pres = pocket_rows[k]
            pocket_forces(ball, bodies.cage, cage.cos_psi[k], cage.sin_psi[k], cage.impact_speeds[k], cage.pocket,
                          pres, g, b,
                          loads.F_cage, loads.M_cage)
            pocket_diag(pres, diag, d)
            # friction power + hysteresis-damping power (damping force = dF_n/d(delta_dot) delta_dot)
            diag[DG_P_DISS] += pres[P_OUT_FRICTION_POWER] + pres[P_OUT_DFN_DRATE] * pres[P_OUT_APPROACH] ** 2


# The helpers of one contact's tangents are inlined into `_ball_tangents` in numba's IR
# (inline="always": one caller each): compiled as functions of their own, each would be a
# library with its callees linked in, optimised and emitted again by LLVM in every caller up the
# chain (docs/performance.md, *Compiling*).
@numba.njit(**WITH_REFCOUNT, **INTERNAL)
def _ball_tangents(v, model, bodies, rows, pocket_rows, q, K, C):
    """Newton blocks of every ball's contacts, from the rows `_ball_forces` left."""
    inner, outer = bodies.inner, bodies.outer
    Om_i = v[BALL_DOF * model.ip[IP_Z] + 3:BALL_DOF * model.ip[IP_Z] + 6]
    D = model.fp[FP_D]
    for k in range(model.ip[IP_Z]):
        b = BALL_DOF * k
        w_b = v[b + 3:b + 6]
        for j in range(2):
            # the border offset is a run-time value: numba compiles a function once per literal
            # argument, and the constants INNER_BORDER and -1 at two call sites compiled
            # _race_term and the four coupling kernels under it twice (cold start, docs/performance.md)
            off = INNER_BORDER if j == 0 else -1
            if rows[2 * k + j, RC_ACTIVE] > 0.0:
                _race_term(k, off, rows[2 * k + j], inner if j == 0 else outer, Om_i, w_b, D, K, C)
        if model.ip[IP_CAGE] and pocket_rows[k, P_OUT_IN_CONTACT] > 0.0:
            pocket_tangent(k, q[b:b + 3], bodies.cage, model.cage.pocket, pocket_rows[k], K, C)


@numba.njit(cache=True, inline="always")
def _race_term(k, off, res, race, Om_r, w_b, D, K, C):
    """Tangents of one ball–race contact (off < 0: fixed race). race: `bundles.Body`;
    Om_r: its material angular velocity (used only when it moves)."""
    GA = np.zeros((3, 6))
    for i in range(3):
        GA[i, i] = 1.0
    GB = np.empty((3, 6))
    point_map(res[RC_PR:RC_PR + 3], race.R, GB)
    Kp = res[RC_KP:RC_KP + 9].copy().reshape(3, 3)
    Cn = res[RC_CN:RC_CN + 9].copy().reshape(3, 3)
    add_pair(k, off, Kp, GA, GB, K)
    add_pair(k, off, Cn, GA, GB, C)
    ex, ey, n = res[RC_EX:RC_EX + 3], res[RC_EY:RC_EY + 3], res[RC_N:RC_N + 3]
    SA = np.empty((3, 6))
    SB = np.empty((3, 6))
    slip_map(ex, ey, n, res[RC_PB:RC_PB + 3], eye3(), SA)
    slip_map(ex, ey, n, res[RC_PR:RC_PR + 3], race.R, SB)
    Jt = res[RC_JT:RC_JT + 9].copy().reshape(3, 3)
    add_pair(k, off, Jt, SA, SB, C)
    _load_coupling(k, off, res, GB, race.R, K)
    _kinematic_coupling(k, off, res, Jt, SA, SB, w_b, race.w, D, K)
    if off >= 0:
        _race_spin_coupling(k, off, res, Jt, SA, SB, race.R, Om_r, K)


@numba.njit(cache=True, inline="always")
def _kinematic_coupling(k, off, res, Jt, SA, SB, w_b, w_r, D, K):
    """Slip depends on positions (dry and lubricated alike): with p = x_b - (D/2) n,
        d(slip)/dx_b = -w_r~ - (D/2) (w_b - w_r)~ N,   d(w_s)/dx_b = (w_b - w_r)^T N,
    N = dn/dx_b: the race's rotation carries the contact point, and the turning normal
    moves it on the spinning ball. The race's translation acts with the opposite sign.
    K += G^T J_t (ds/dx) in the block pattern (the turning of e_x, e_y is neglected)."""
    ex, ey = res[RC_EX:RC_EX + 3], res[RC_EY:RC_EY + 3]
    N = res[RC_DN:RC_DN + 9].copy().reshape(3, 3)
    dw = w_b - w_r
    ds = -skew(w_r) - 0.5 * D * mm(skew(dw), N)
    Mx = np.empty((3, 3))  # d(du0, dv0, w_s)/dx_b
    for j in range(3):
        Mx[0, j] = ex[0] * ds[0, j] + ex[1] * ds[1, j] + ex[2] * ds[2, j]
        Mx[1, j] = ey[0] * ds[0, j] + ey[1] * ds[1, j] + ey[2] * ds[2, j]
        Mx[2, j] = dw[0] * N[0, j] + dw[1] * N[1, j] + dw[2] * N[2, j]
    add_congruent(K.D[k, :, 0:3], SA, Jt, Mx, 1.0)
    if off < 0:
        return
    add_congruent(K.E[k, :, off:off + 3], SA, Jt, Mx, -1.0)
    add_congruent(K.F[k, off:off + 6, 0:3], SB, Jt, Mx, -1.0)
    add_congruent(K.B[off:off + 6, off:off + 3], SB, Jt, Mx, 1.0)


@numba.njit(cache=True, inline="always")
def _race_spin_coupling(k, off, res, Jt, SA, SB, R_r, Om_r, K):
    """Tilting a spinning race turns its angular velocity, w_r = R Omega: a material rotation
    dTheta gives dw_r = -R Omega~ dTheta, so the slip at the contact changes by
    -dw_r x (p - x_r): d(slip)/dTheta = -r~ R Omega~, d(w_s)/dTheta = n^T R Omega~."""
    ex, ey, n = res[RC_EX:RC_EX + 3], res[RC_EY:RC_EY + 3], res[RC_N:RC_N + 3]
    r = res[RC_PR:RC_PR + 3]
    ROm = mm(R_r, skew(Om_r))
    ds = mm(skew(r), ROm)  # its negative, d(slip)/dTheta: the sign goes into Mt's rows
    Mt = np.empty((3, 3))
    for j in range(3):
        Mt[0, j] = -(ex[0] * ds[0, j] + ex[1] * ds[1, j] + ex[2] * ds[2, j])
        Mt[1, j] = -(ey[0] * ds[0, j] + ey[1] * ds[1, j] + ey[2] * ds[2, j])
        Mt[2, j] = n[0] * ROm[0, j] + n[1] * ROm[1, j] + n[2] * ROm[2, j]
    add_congruent(K.E[k, :, off + 3:off + 6], SA, Jt, Mt, 1.0)
    add_congruent(K.B[off:off + 6, off + 3:off + 6], SB, Jt, Mt, -1.0)


@numba.njit(cache=True, inline="always")
def _load_coupling(k, off, res, GB, R_r, K):
    """Traction scales with the normal load: d(wrench)/d(delta) = slope x wrench, with
    d delta/dx_b = -n and d delta/dW_race = n^T G_B (the race point map)."""
    slope = res[RC_LOAD_SLOPE]
    if slope == 0.0:
        return
    n = res[RC_N:RC_N + 3]
    wb = res[RC_WTB:RC_WTB + 6]
    for i in range(6):
        for j in range(3):
            K.D[k, i, j] += slope * wb[i] * n[j]
    if off < 0:
        return
    nG = n @ GB  # (6,): d delta / d W_race
    wm = R_r.T @ res[RC_WTR + 3:RC_WTR + 6]  # material moment rows
    wr = np.empty(6)
    for i in range(3):  # element by element, not a slice assignment (`small.add_into`)
        wr[i] = res[RC_WTR + i]
        wr[3 + i] = wm[i]
    for i in range(6):
        for j in range(6):
            K.E[k, i, off + j] -= slope * wb[i] * nG[j]
            K.B[off + i, off + j] -= slope * wr[i] * nG[j]
        for j in range(3):
            K.F[k, off + i, j] += slope * wr[i] * n[j]


@numba.njit(cache=True, inline="always")
def _border(t, v, model, bodies, loads, ma, g, diag):
    """Inner race (loads M.53, hinge M.54, gyroscopic, spin M.52) and cage (journal §8,
    gyroscopic). Returns the drive moment.

    The residual terms are written without temporaries (`mtv_into` into the model's scratch, and
    `rigid_body.gyroscopic_moment`'s arithmetic on scalars, so the same bits): ~30 small arrays
    per call would show in a profile of the run. The material moments stay in the scratch for the
    tangents (`_border_tangents`)."""
    fp, ip, hinge, work = model.fp, model.ip, model.hinge, model.work
    inner, cage = bodies.inner, bodies.cage
    o_i = BALL_DOF * ip[IP_Z]
    R_i = inner.R
    if ip[IP_CAGE] and ip[IP_JOURNAL]:
        # first: an inner-guided cage's land reaction acts on the inner race, whose rows follow
        jres = work.journal_row
        inner_guided = model.cage.journal.guidance < 0.0
        fixed = work.fixed_reaction  # the fixed outer race takes its reaction: nothing reads it
        fixed[:] = 0.0
        power = journal_forces(cage, inner if inner_guided else bodies.outer, model.cage.journal, jres,
                               work.journal_squeeze, g, o_i + RACE_DOF,
                               loads.F_inner if inner_guided else fixed[0],
                               loads.M_inner if inner_guided else fixed[1])
        journal_diag(jres, diag)
        diag[DG_P_DISS] -= power
    ext_f, ext_m = work.ext_f, work.ext_m
    ext_f[0], ext_f[1], ext_f[2] = fp[FP_FX], 0.0, fp[FP_FZ]
    # a sudden load step (stability suite): the moment jumps at t = FP_T_LOAD_STEP
    ext_m[0], ext_m[1], ext_m[2] = 0.0, fp[FP_MY] if t < fp[FP_T_LOAD_STEP] else fp[FP_MY_STEP], 0.0
    Om_i = v[o_i + 3:o_i + 6]
    for i in range(3):
        g[o_i + i] += loads.F_inner[i] + ext_f[i]
    # material moments R_i^T M_inner + R_i^T m_ext (M.53: the load held fixed in space)
    m_contact, m_load = work.moment_contact, work.moment_load
    mtv_into(R_i, loads.M_inner, m_contact)
    mtv_into(R_i, ext_m, m_load)
    for i in range(3):
        g[o_i + 3 + i] += m_contact[i] + m_load[i]
    diag[DG_P_EXT] = _dot3(ext_f, inner.v) + _dot3(ext_m, inner.w)
    if ip[IP_GYRO]:
        _add_gyroscopic(fp[FP_JIX], fp[FP_JIX], fp[FP_JIZ], Om_i, g, o_i + 3)
    if ip[IP_HINGE]:
        diag[DG_P_DISS] += add_hinge_force(inner.x, R_i, inner.v, Om_i, hinge.x_A, hinge.R_A, hinge.H_u,
                                           hinge.H_psi, hinge.G_u, hinge.G_psi, g, o_i)
        diag[DG_V_HINGE] = hinge_energy(inner.x, R_i, hinge.x_A, hinge.R_A, hinge.H_u, hinge.H_psi)
    if ip[IP_CAGE]:
        o_c = o_i + RACE_DOF
        Om_c = v[o_c + 3:o_c + 6]
        for i in range(3):
            g[o_c + i] += loads.F_cage[i]
        m_cage = work.moment_cage
        mtv_into(cage.R, loads.M_cage, m_cage)
        for i in range(3):
            g[o_c + 3 + i] += m_cage[i]
        if ip[IP_GYRO]:
            _add_gyroscopic(fp[FP_JCX], fp[FP_JCX], fp[FP_JCZ], Om_c, g, o_c + 3)
    drive = prescribe_velocity_residual(o_i + 5, v, fp[FP_OMEGA_I], 1.0, ma, g)
    diag[DG_DRIVE] = drive
    diag[DG_P_DRIVE] = drive * fp[FP_OMEGA_I]
    return drive


@numba.njit(cache=True, inline="always")
def _border_tangents(v, model, bodies, Kb, Cb):
    """The border blocks Kb, Cb of the tangents: hinge, inner race (its moments held fixed in
    space, gyroscopic damping), cage (the same) and the cage–land journal, from what `_border`
    left in the model's scratch."""
    fp, ip, work = model.fp, model.ip, model.work
    o_i = BALL_DOF * ip[IP_Z]
    Om_i = v[o_i + 3:o_i + 6]
    if ip[IP_HINGE]:
        _hinge_tangent(bodies.inner, Om_i, model.hinge, Kb, Cb)
    _inner_race_tangent(fp, bool(ip[IP_GYRO]), Om_i, work.moment_load, work.moment_contact, Kb, Cb)
    if ip[IP_CAGE]:
        o_c = o_i + RACE_DOF
        _cage_tangent(fp, bool(ip[IP_GYRO]), v[o_c + 3:o_c + 6], work.moment_cage, Kb, Cb)
        if ip[IP_JOURNAL]:
            cage_block = slice(CAGE_BORDER, CAGE_BORDER + CAGE_DOF)
            journal_tangent(work.journal_row, Kb[cage_block, cage_block], Cb[cage_block, cage_block])
            if model.cage.journal.guidance < 0.0:
                journal_race_tangent(work.journal_row, Kb, Cb)


# The border's tangent terms: kernels with reference counting (they build small arrays), called
# by `bearing_tangents`.
@numba.njit(**WITH_REFCOUNT, **INTERNAL)
def _hinge_tangent(inner, Om_i, hinge, Kb, Cb):
    """The hinge's tangents into the inner race's border blocks, from `hinge_forces` (whose force
    the residual adds with `add_hinge_force`, equal to rounding)."""
    _, Kh, Ch = hinge_forces(inner.x, inner.R, inner.v, Om_i, hinge.x_A, hinge.R_A, hinge.H_u, hinge.H_psi,
                             hinge.G_u, hinge.G_psi)
    add_into(Kb[INNER_BORDER:INNER_BORDER + 6, INNER_BORDER:INNER_BORDER + 6], Kh)
    add_into(Cb[INNER_BORDER:INNER_BORDER + 6, INNER_BORDER:INNER_BORDER + 6], Ch)


@numba.njit(**WITH_REFCOUNT, **INTERNAL)
def _inner_race_tangent(fp, gyro, Om_i, m_load, m_contact, Kb, Cb):
    """The contact moment M_i and the external moment are held fixed in space under a material
    rotation increment: K = -(R^T m)~ each (rigid_body.material_moment_of_spatial_moment), with
    m_load, m_contact the material moments; with gyro, the gyroscopic damping block."""
    i3 = INNER_BORDER + 3
    add_into(Kb[i3:i3 + 3, i3:i3 + 3], -skew(m_load) - skew(m_contact))
    if gyro:
        add_into(Cb[i3:i3 + 3, i3:i3 + 3], gyroscopic_damping(_diagonal(fp[FP_JIX], fp[FP_JIX], fp[FP_JIZ]), Om_i))


@numba.njit(**WITH_REFCOUNT, **INTERNAL)
def _cage_tangent(fp, gyro, Om_c, m_contact, Kb, Cb):
    """The cage's contact moment held fixed in space (m_contact: material) and, with gyro, its
    gyroscopic damping block."""
    c3 = CAGE_BORDER + 3
    add_into(Kb[c3:c3 + 3, c3:c3 + 3], -skew(m_contact))
    if gyro:
        add_into(Cb[c3:c3 + 3, c3:c3 + 3], gyroscopic_damping(_diagonal(fp[FP_JCX], fp[FP_JCX], fp[FP_JCZ]), Om_c))


@numba.njit(cache=True, inline="always")
def _dot3(a, b):
    """a . b of two 3-vectors, not numba's `@` (a library of its own on a machine's first run)."""
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


@numba.njit(cache=True, inline="always")
def _diagonal(a, b, c):
    """diag(a, b, c) (3x3), without `np.diag`'s own library."""
    J = np.zeros((3, 3))
    J[0, 0], J[1, 1], J[2, 2] = a, b, c
    return J


@numba.njit(cache=True, inline="always")
def _add_gyroscopic(Jx, Jy, Jz, Om, g, off):
    """g[off:off + 3] += -Om x (J Om) for J = diag(Jx, Jy, Jz) [N m] (material): the arithmetic
    of `rigid_body.gyroscopic_moment` (`mv` over the diagonal matrix, then `np.cross`) on scalars."""
    j0 = 0.0 + Jx * Om[0] + 0.0 * Om[1] + 0.0 * Om[2]
    j1 = 0.0 + 0.0 * Om[0] + Jy * Om[1] + 0.0 * Om[2]
    j2 = 0.0 + 0.0 * Om[0] + 0.0 * Om[1] + Jz * Om[2]
    g[off] += -(Om[1] * j2 - Om[2] * j1)
    g[off + 1] += -(Om[2] * j0 - Om[0] * j2)
    g[off + 2] += -(Om[0] * j1 - Om[1] * j0)
