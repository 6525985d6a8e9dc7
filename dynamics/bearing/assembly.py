"""The bearing's residual pieces in one numba kernel: M a, g(t, q, v) and (on request) the
block-arrow tangents K_t = -dg/dq, C_t = -dg/dv (docs/model.md §4–§9, paper eq. 8).

Per evaluation: 2Z ball–race contacts (race_forces), Z ball–pocket contacts and one
cage–race journal (cage_forces), the viscoelastic hinge (M.19–M.20), external loads on
the inner race, gyroscopic terms, and the prescribed inner-race spin (row replaced).
Every contact force acts equal and opposite on both bodies at the contact point.
"""

from __future__ import annotations

import numba
import numpy as np

from bearingsim.dynamics._kernel_options import NO_REFCOUNT
from bearingsim.dynamics.journal.hybrid import J_OUT_FILM_POWER, J_OUT_MIN_FILM, N_JOURNAL_OUT
from bearingsim.dynamics.multibody.crv import crv_to_matrix
from bearingsim.dynamics.multibody.hinge import hinge_energy, hinge_forces
from bearingsim.dynamics.multibody.joints import prescribe_velocity_residual
from bearingsim.dynamics.multibody.small import mtv, mv
from bearingsim.dynamics.multibody.rigid_body import gyroscopic_moment, material_moment_of_spatial_moment
from bearingsim.dynamics.contact.pocket import (
    N_POCKET_OUT, P_OUT_APPROACH, P_OUT_DFN_DRATE, P_OUT_FRICTION_POWER, P_OUT_IN_CONTACT,
)

from .cage_forces import journal_diag, journal_forces, pocket_diag, pocket_forces, pocket_tangent
from .params import (
    FP_D, FP_FX, FP_FZ, FP_JB, FP_JCX, FP_JCZ, FP_JIX, FP_JIZ, FP_MB, FP_MC, FP_MI, FP_MY,
    FP_MY_STEP, FP_OMEGA_I, FP_OMEGA_O, FP_T_LOAD_STEP, IP_CAGE, IP_GYRO, IP_HINGE, IP_JOURNAL, IP_Z,
)
from .race_forces import (
    N_CONTACT_SCRATCH, N_RC, RC_ACTIVE, RC_ALPHA, RC_CN, RC_EX, RC_EY, RC_FB, RC_FILM,
    RC_FLAG, RC_FR, RC_JT, RC_KP, RC_MB, RC_MR, RC_N, RC_PB, RC_PDISS, RC_PMAX, RC_PR, RC_Q,
    RC_SRR, RC_VHZ, RC_LOAD_SLOPE, RC_WTB, RC_WTR, RC_DN, race_contact,
)
from .tangents import add_pair, point_map, slip_map

# global diagnostics (diag[:N_DG]) then per ball (diag[N_DG + DB*k + ...])
DG_EPS, DG_FX, DG_FY, DG_TORQUE, DG_METAL, DG_FRICTION_POWER, DG_AZIMUTH = 0, 1, 2, 3, 4, 5, 6
DG_DRIVE, DG_P_DRIVE, DG_P_EXT, DG_P_DISS, DG_V_HERTZ, DG_V_HINGE, DG_FLAGS = 7, 8, 9, 10, 11, 12, 13
DG_FILM_POWER, DG_MIN_FILM = 14, 15  # land film: viscous shear power [W], thinnest film [m]
N_DG = 16
DB_QI, DB_QO, DB_AI, DB_AO, DB_HI, DB_HO, DB_SRRI, DB_SRRO, DB_PMI, DB_PMO = range(10)
DB_POCKET = 10  # 5: F_n, in contact, approach speed, orbital position, friction power
DB = 15


def diag_size(Z: int) -> int:
    return N_DG + DB * Z


def mass_diagonal(fp, ip, n):
    """Constant diagonal mass matrix (balls, inner race, cage; material inertias)."""
    Z = int(ip[IP_Z])
    m = np.zeros(n)
    for k in range(Z):
        m[6 * k:6 * k + 3] = fp[FP_MB]
        m[6 * k + 3:6 * k + 6] = fp[FP_JB]
    o = 6 * Z
    m[o:o + 3] = fp[FP_MI]
    m[o + 3:o + 6] = (fp[FP_JIX], fp[FP_JIX], fp[FP_JIZ])
    if ip[IP_CAGE]:
        m[o + 6:o + 9] = fp[FP_MC]
        m[o + 9:o + 12] = (fp[FP_JCX], fp[FP_JCX], fp[FP_JCZ])
    return m


@numba.njit(cache=True)
def _race_term(k, off, res, R_r, Om_r, w_b, w_r, D, Kd, Ke, Kf, Kb, Cd, Ce, Cf, Cb):
    """Tangents of one ball–race contact (off < 0: fixed race); w_r: race angular velocity."""
    GA = np.zeros((3, 6))
    for i in range(3):
        GA[i, i] = 1.0
    GB = np.empty((3, 6))
    point_map(res[RC_PR:RC_PR + 3], R_r, GB)
    Kp = res[RC_KP:RC_KP + 9].copy().reshape(3, 3)
    Cn = res[RC_CN:RC_CN + 9].copy().reshape(3, 3)
    add_pair(k, off, Kp, GA, GB, Kd, Ke, Kf, Kb, 1.0)
    add_pair(k, off, Cn, GA, GB, Cd, Ce, Cf, Cb, 1.0)
    ex, ey, n = res[RC_EX:RC_EX + 3], res[RC_EY:RC_EY + 3], res[RC_N:RC_N + 3]
    SA = np.empty((3, 6))
    SB = np.empty((3, 6))
    slip_map(ex, ey, n, res[RC_PB:RC_PB + 3], np.eye(3), SA)
    slip_map(ex, ey, n, res[RC_PR:RC_PR + 3], R_r, SB)
    Jt = res[RC_JT:RC_JT + 9].copy().reshape(3, 3)
    add_pair(k, off, Jt, SA, SB, Cd, Ce, Cf, Cb, 1.0)
    _load_coupling(k, off, res, GB, R_r, Kd, Ke, Kf, Kb)
    _kinematic_coupling(k, off, res, Jt, SA, SB, w_b, w_r, D, Kd, Ke, Kf, Kb)
    if off >= 0:
        _race_spin_coupling(k, off, res, Jt, SA, SB, R_r, Om_r, Ke, Kb)


@numba.njit(cache=True)
def _kinematic_coupling(k, off, res, Jt, SA, SB, w_b, w_r, D, Kd, Ke, Kf, Kb):
    """Slip depends on positions (dry and lubricated alike): with p = x_b - (D/2) n,
        d(slip)/dx_b = -w_r~ - (D/2) (w_b - w_r)~ N,   d(w_s)/dx_b = (w_b - w_r)^T N,
    N = dn/dx_b: the race's rotation carries the contact point, and the turning normal
    moves it on the spinning ball. The race's translation acts with the opposite sign.
    K += G^T J_t (ds/dx) in the block pattern (the turning of e_x, e_y is neglected)."""
    ex, ey, n = res[RC_EX:RC_EX + 3], res[RC_EY:RC_EY + 3], res[RC_N:RC_N + 3]
    N = res[RC_DN:RC_DN + 9].copy().reshape(3, 3)
    dw = w_b - w_r
    ds = -_skew(w_r) - 0.5 * D * (_skew(dw) @ N)
    Mx = np.empty((3, 3))  # d(du0, dv0, w_s)/dx_b
    Mx[0, :] = ex @ ds
    Mx[1, :] = ey @ ds
    Mx[2, :] = dw @ N
    JM = Jt @ Mx
    Kd[k, :, 0:3] += SA.T @ JM
    if off < 0:
        return
    Ke[k, :, off:off + 3] -= SA.T @ JM
    Kf[k, off:off + 6, 0:3] -= SB.T @ JM
    Kb[off:off + 6, off:off + 3] += SB.T @ JM


@numba.njit(cache=True)
def _race_spin_coupling(k, off, res, Jt, SA, SB, R_r, Om_r, Ke, Kb):
    """Tilting a spinning race turns its angular velocity, w_r = R Omega: a material rotation
    dTheta gives dw_r = -R Omega~ dTheta, so the slip at the contact changes by
    -dw_r x (p - x_r): d(slip)/dTheta = -r~ R Omega~, d(w_s)/dTheta = n^T R Omega~."""
    ex, ey, n = res[RC_EX:RC_EX + 3], res[RC_EY:RC_EY + 3], res[RC_N:RC_N + 3]
    r = res[RC_PR:RC_PR + 3]
    ROm = R_r @ _skew(Om_r)
    ds = -(_skew(r) @ ROm)
    Mt = np.empty((3, 3))
    Mt[0, :] = ex @ ds
    Mt[1, :] = ey @ ds
    Mt[2, :] = n @ ROm
    JM = Jt @ Mt
    Ke[k, :, off + 3:off + 6] += SA.T @ JM
    Kb[off:off + 6, off + 3:off + 6] -= SB.T @ JM


@numba.njit(cache=True)
def _load_coupling(k, off, res, GB, R_r, Kd, Ke, Kf, Kb):
    """Traction scales with the normal load: d(wrench)/d(delta) = slope x wrench, with
    d delta/dx_b = -n and d delta/dW_race = n^T G_B (the race point map)."""
    slope = res[RC_LOAD_SLOPE]
    if slope == 0.0:
        return
    n = res[RC_N:RC_N + 3]
    wb = res[RC_WTB:RC_WTB + 6]
    for i in range(6):
        for j in range(3):
            Kd[k, i, j] += slope * wb[i] * n[j]
    if off < 0:
        return
    nG = n @ GB  # (6,): d delta / d W_race
    wr = np.empty(6)
    wr[:3] = res[RC_WTR:RC_WTR + 3]
    wr[3:] = R_r.T @ res[RC_WTR + 3:RC_WTR + 6]  # material moment rows
    for i in range(6):
        for j in range(6):
            Ke[k, i, off + j] -= slope * wb[i] * nG[j]
            Kb[off + i, off + j] -= slope * wr[i] * nG[j]
        for j in range(3):
            Kf[k, off + i, j] += slope * wr[i] * n[j]


@numba.njit(cache=True)
def evaluate_bearing(t, q, v, a, fp, ip, tab_i, tab_o, eta_table, rule, work, iwork,
                     pp, jp, psi, Hu, Hpsi, Gu, Gpsi, xA, RA, v0, mass, want_tangent,
                     ma, g, diag, Kd, Ke, Kf, Kb, Cd, Ce, Cf, Cb):
    """Fill ma = M a, g = g(t, q, v), diag and (want_tangent) K, C blocks. Returns the
    drive moment [N m] that holds the inner-race spin."""
    Z = ip[IP_Z]
    o_i = 6 * Z
    o_c = o_i + 6 if ip[IP_CAGE] else -1
    g[:] = 0.0
    diag[:] = 0.0
    for i in range(ma.shape[0]):
        ma[i] = mass[i] * a[i]
    if want_tangent:
        Kd[:] = 0.0
        Ke[:] = 0.0
        Kf[:] = 0.0
        Kb[:] = 0.0
        Cd[:] = 0.0
        Ce[:] = 0.0
        Cf[:] = 0.0
        Cb[:] = 0.0
    x_i = q[o_i:o_i + 3]
    R_i = crv_to_matrix(q[o_i + 3:o_i + 6])
    v_i = v[o_i:o_i + 3]
    Om_i = v[o_i + 3:o_i + 6]
    w_i = mv(R_i, Om_i)
    x_o = np.zeros(3)
    R_o = np.eye(3)
    w_o = np.array([0.0, 0.0, fp[FP_OMEGA_O]])
    F_i = np.zeros(3)
    M_i = np.zeros(3)
    F_c = np.zeros(3)
    M_c = np.zeros(3)
    if o_c >= 0:
        x_c = q[o_c:o_c + 3]
        R_c = crv_to_matrix(q[o_c + 3:o_c + 6])
        v_c = v[o_c:o_c + 3]
        w_c = mv(R_c, v[o_c + 3:o_c + 6])
    else:
        x_c, R_c, v_c, w_c = x_o, R_o, x_o, x_o
    rows = np.empty((2 * Z, N_RC))  # one row per ball-race contact: inner 2k, outer 2k + 1
    pocket_rows = np.empty((Z, N_POCKET_OUT))
    _ball_forces(q, v, fp, ip, tab_i, tab_o, eta_table, rule, work, iwork, pp, psi, v0, x_i, R_i, v_i, w_i,
                 x_o, R_o, w_o, x_c, R_c, v_c, w_c, o_c >= 0, np.empty(N_CONTACT_SCRATCH), np.empty(12),
                 rows, pocket_rows, g, diag, F_i, M_i, F_c, M_c, want_tangent)
    if want_tangent:
        for k in range(Z):
            w_b = v[6 * k + 3:6 * k + 6]
            if rows[2 * k, RC_ACTIVE] > 0.0:
                _race_term(k, 0, rows[2 * k], R_i, Om_i, w_b, w_i, fp[FP_D], Kd, Ke, Kf, Kb, Cd, Ce, Cf, Cb)
            if rows[2 * k + 1, RC_ACTIVE] > 0.0:
                _race_term(k, -1, rows[2 * k + 1], R_o, Om_i, w_b, w_o, fp[FP_D], Kd, Ke, Kf, Kb, Cd, Ce, Cf, Cb)
            if o_c >= 0 and pocket_rows[k, P_OUT_IN_CONTACT] > 0.0:
                pocket_tangent(k, q[6 * k:6 * k + 3], x_c, R_c, pp, pocket_rows[k], 6, Kd, Ke, Kf, Kb, Cd, Ce, Cf, Cb)
    return _border(t, q, v, fp, ip, Hu, Hpsi, Gu, Gpsi, xA, RA, jp, want_tangent, ma, g, diag,
                   Kb, Cb, o_i, o_c, x_i, R_i, v_i, w_i, F_i, M_i, x_c, R_c, v_c, w_c, F_c, M_c)


@numba.njit(**NO_REFCOUNT)
def _ball_forces(q, v, fp, ip, tab_i, tab_o, eta_table, rule, work, iwork, pp, psi, v0, x_i, R_i, v_i, w_i,
                 x_o, R_o, w_o, x_c, R_c, v_c, w_c, with_cage, cbuf, tbuf, rows, pocket_rows, g, diag,
                 F_i, M_i, F_c, M_c, want_tangent):
    """Forces of every ball's race and pocket contacts into g, the race and cage wrench sums
    (F_i, M_i, F_c, M_c) and diag; the contact rows (with their tangent ingredients when
    want_tangent) stay in rows (2k inner, 2k + 1 outer) and, with a cage, pocket_rows for
    the tangent pass. Allocation-free and without reference counting (dynamics/_kernel_options.py):
    this loop, with its per-ball views, is the hot path of every residual."""
    for k in range(ip[IP_Z]):
        b = 6 * k
        x_b, v_b, w_b = q[b:b + 3], v[b:b + 3], v[b + 3:b + 6]
        d = N_DG + DB * k
        for j in range(2):
            res = rows[2 * k + j]
            if j == 1:
                hit = race_contact(x_b, v_b, w_b, x_o, R_o, x_o, w_o, True, fp, ip, tab_o, eta_table,
                                   rule, work, iwork, cbuf, tbuf, res, want_tangent)
            else:
                hit = race_contact(x_b, v_b, w_b, x_i, R_i, v_i, w_i, False, fp, ip, tab_i, eta_table,
                                   rule, work, iwork, cbuf, tbuf, res, want_tangent)
            diag[d + DB_AI + j] = res[RC_ALPHA]
            if not hit:
                continue
            for i in range(3):
                g[b + i] += res[RC_FB + i]
                g[b + 3 + i] += res[RC_MB + i]
                if j == 0:
                    F_i[i] += res[RC_FR + i]
                    M_i[i] += res[RC_MR + i]
            diag[d + DB_QI + j] = res[RC_Q]
            diag[d + DB_HI + j] = res[RC_FILM]
            diag[d + DB_SRRI + j] = res[RC_SRR]
            diag[d + DB_PMI + j] = res[RC_PMAX]
            diag[DG_P_DISS] += res[RC_PDISS]
            diag[DG_V_HERTZ] += res[RC_VHZ]
            if res[RC_FLAG] != 0.0:
                diag[DG_FLAGS] += 1.0
        if with_cage:
            pres = pocket_rows[k]
            pocket_forces(x_b, v_b, w_b, x_c, R_c, v_c, w_c, psi[k], v0[k], pp, pres, g, b, F_c, M_c)
            pocket_diag(pres, diag[d + DB_POCKET:d + DB_POCKET + 5])
            # friction power + hysteresis-damping power (damping force = dF_n/d(delta_dot) delta_dot)
            diag[DG_P_DISS] += pres[P_OUT_FRICTION_POWER] + pres[P_OUT_DFN_DRATE] * pres[P_OUT_APPROACH] ** 2


@numba.njit(cache=True)
def _border(t, q, v, fp, ip, Hu, Hpsi, Gu, Gpsi, xA, RA, jp, want_tangent, ma, g, diag, Kb, Cb,
            o_i, o_c, x_i, R_i, v_i, w_i, F_i, M_i, x_c, R_c, v_c, w_c, F_c, M_c):
    """Inner race (loads, hinge, gyroscopic, spin) and cage (journal, gyroscopic)."""
    ext_f = np.array([fp[FP_FX], 0.0, fp[FP_FZ]])
    # a sudden load step (stability suite): the moment jumps at t = FP_T_LOAD_STEP
    ext_m = np.array([0.0, fp[FP_MY] if t < fp[FP_T_LOAD_STEP] else fp[FP_MY_STEP], 0.0])
    Om_i = v[o_i + 3:o_i + 6]
    tau_ext, K_ext = material_moment_of_spatial_moment(R_i, ext_m)
    for i in range(3):
        g[o_i + i] += F_i[i] + ext_f[i]
    g[o_i + 3:o_i + 6] += mtv(R_i, M_i) + tau_ext
    diag[DG_P_EXT] = ext_f @ v_i + ext_m @ w_i
    J_i = np.array([fp[FP_JIX], fp[FP_JIX], fp[FP_JIZ]])
    if ip[IP_GYRO]:
        g_gyr, C_gyr = gyroscopic_moment(np.diag(J_i), Om_i)
        g[o_i + 3:o_i + 6] += g_gyr
    if ip[IP_HINGE]:
        gh, Kh, Ch = hinge_forces(x_i, R_i, v_i, Om_i, xA, RA, Hu, Hpsi, Gu, Gpsi)
        g[o_i:o_i + 6] += gh
        diag[DG_V_HINGE] = hinge_energy(x_i, R_i, xA, RA, Hu, Hpsi)
        diag[DG_P_DISS] += mv(Ch, v[o_i:o_i + 6]) @ v[o_i:o_i + 6]
    if want_tangent:
        # contact moment M_i is held fixed in space under a material rotation increment
        Kb[3:6, 3:6] += K_ext - _skew(mtv(R_i, M_i))
        if ip[IP_GYRO]:
            Cb[3:6, 3:6] += C_gyr
        if ip[IP_HINGE]:
            Kb[0:6, 0:6] += Kh
            Cb[0:6, 0:6] += Ch
    if o_c >= 0:
        Om_c = v[o_c + 3:o_c + 6]
        for i in range(3):
            g[o_c + i] += F_c[i]
        g[o_c + 3:o_c + 6] += mtv(R_c, M_c)
        if want_tangent:
            Kb[9:12, 9:12] += -_skew(mtv(R_c, M_c))
        if ip[IP_GYRO]:
            J_c = np.diag(np.array([fp[FP_JCX], fp[FP_JCX], fp[FP_JCZ]]))
            g_gyr_c, C_gyr_c = gyroscopic_moment(J_c, Om_c)
            g[o_c + 3:o_c + 6] += g_gyr_c
            if want_tangent:
                Cb[9:12, 9:12] += C_gyr_c
        if ip[IP_JOURNAL]:
            jres = np.empty(N_JOURNAL_OUT)
            power = journal_forces(x_c, v_c, w_c, np.zeros(3), np.zeros(3), fp[FP_OMEGA_O], jp, jres,
                                   g, o_c, R_c, want_tangent, Kb[6:12, 6:12], Cb[6:12, 6:12])
            journal_diag(jres, diag[DG_EPS:DG_EPS + 7])
            diag[DG_FILM_POWER] = jres[J_OUT_FILM_POWER]
            diag[DG_MIN_FILM] = jres[J_OUT_MIN_FILM]
            diag[DG_P_DISS] -= power
    drive = prescribe_velocity_residual(o_i + 5, v, fp[FP_OMEGA_I], 1.0, ma, g)
    diag[DG_DRIVE] = drive
    diag[DG_P_DRIVE] = drive * fp[FP_OMEGA_I]
    return drive


@numba.njit(cache=True)
def _skew(a):
    s = np.zeros((3, 3))
    s[0, 1], s[0, 2] = -a[2], a[1]
    s[1, 0], s[1, 2] = a[2], -a[0]
    s[2, 0], s[2, 1] = -a[1], a[0]
    return s
