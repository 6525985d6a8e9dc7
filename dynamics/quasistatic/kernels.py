"""Numba kernels of the quasi-static bearing solver (docs/model.md §10, §6.1–6.2).

Each ball lives in its azimuth plane with coordinates (r, z): r radial from the bearing
axis, z axial. The outer race is fixed, its groove curvature centre at (d_o/2, 0). The
inner race moves by q = (u_x, u_y, u_z, θ_x, θ_y) from the centred position (axes
coincident, curvature-centre planes coplanar); its groove curvature centre for the ball
at azimuth ψ is C_i = u + R(θ) (d_i/2) e_r(ψ), seen in the ball's azimuth plane
(components along e_r and e_z; see `dynamics.quasistatic.solver`). The kernels take C_i and
G = ∂C_i/∂q (2×5) per ball.

Contact on the ball from race j (M.24): F_j = k_h(α_j) δ_j^{3/2} n_j, n_j = w_j/|w_j|,
w_j = C_j − x_b, δ_j = |w_j| − (r_j − D/2). Ball equilibrium:
F_i + F_o + m ω_c² r e_r + F_gyro = 0. The inner race receives f = −F_i at C_i, i.e. the
generalised force Gᵀ f.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numba
import numpy as np

from .._speed.compile_policy import KERNEL
from ..contact.hertz import hertz_table_eval


class Grooves(NamedTuple):
    """The two grooves a ball sits between: Hertz tables (contact.hertz.race_hertz_table)
    and gaps r - D/2 [m] of the inner and outer race."""

    tab_i: np.ndarray
    tab_o: np.ndarray
    gap_i: float
    gap_o: float


class BallLoads(NamedTuple):
    """Per ball (Z,): m_b omega_c^2 [N/m] (centrifugal force m_b omega_c^2 r, docs/model.md
    §10) and the frozen gyroscopic friction magnitudes g_i, g_o [N] at the inner and outer
    contact (see `ball_residual`)."""

    m_om2: np.ndarray
    g_i: np.ndarray
    g_o: np.ndarray


BALL_COLUMNS = 11
B_QI, B_QO, B_AI, B_AO, B_DI, B_DO, B_STATUS, B_FRIC_R, B_FRIC_Z, B_FR, B_FZ = range(BALL_COLUMNS)
STATUS_OK, STATUS_LOOSE, STATUS_FAILED = 0.0, 1.0, 2.0


@numba.njit(**KERNEL)
def contact_2d(w_r, w_z, gap, table, is_outer):
    """Force on the ball from one groove and its Jacobian with respect to w = C − x_b.

    Returns (Q, α, δ, F_r, F_z, J_rr, J_rz, J_zr, J_zz): Q = k_h δ^{3/2} [N] (M.24), α the
    signed contact angle (dynamics.contact.race convention), F = Q n [N], J = ∂F/∂w [N/m]
    = (3/2)k_h δ^{1/2} nnᵀ + (Q/s)(I − nnᵀ) + δ^{3/2} (dk_h/dα) n tᵀ/s, t = (−n_z, n_r).
    gap = r − D/2 [m]. δ ≤ 0 returns zeros (no contact).
    """
    s = math.sqrt(w_r * w_r + w_z * w_z)
    n_r, n_z = w_r / s, w_z / s
    if is_outer:
        alpha = math.atan2(-n_z, -n_r)
    else:
        alpha = math.atan2(n_z, n_r)
    delta = s - gap
    if delta <= 0.0:
        return 0.0, alpha, delta, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
    k_h, dk, _, _, _ = hertz_table_eval(table, alpha)
    root = math.sqrt(delta)
    q = k_h * delta * root
    k_n = 1.5 * k_h * root
    k_t = q / s
    k_a = delta * root * dk / s
    t_r, t_z = -n_z, n_r
    j_rr = k_n * n_r * n_r + k_t * (1.0 - n_r * n_r) + k_a * n_r * t_r
    j_rz = k_n * n_r * n_z - k_t * n_r * n_z + k_a * n_r * t_z
    j_zr = k_n * n_z * n_r - k_t * n_z * n_r + k_a * n_z * t_r
    j_zz = k_n * n_z * n_z + k_t * (1.0 - n_z * n_z) + k_a * n_z * t_z
    return q, alpha, delta, q * n_r, q * n_z, j_rr, j_rz, j_zr, j_zz


@numba.njit(**KERNEL)
def ball_residual(x_r, x_z, ci_r, ci_z, co_r, co_z, grooves, m_om2, g_i, g_o):
    """Residual r = ΣF on the ball at (x_r, x_z) [N] and ∂r/∂x_b, plus both contacts (tuple of
    floats). (ci_r, ci_z), (co_r, co_z): inner and outer curvature centres [m]; grooves:
    `Grooves`. m_om2 = m_b ω_c² [N/m] (centrifugal force m_b ω_c² r, docs/model.md §10).
    g_i, g_o [N]: frozen gyroscopic friction magnitudes along τ = (−n_z, n_r) at the
    inner/outer contact (applied only while that contact is loaded; its Jacobian is neglected).
    """
    # flags typed bool, not Literal[bool]: numba compiles a callee once per literal argument
    ci = contact_2d(ci_r - x_r, ci_z - x_z, grooves.gap_i, grooves.tab_i, np.bool_(False))
    co = contact_2d(co_r - x_r, co_z - x_z, grooves.gap_o, grooves.tab_o, np.bool_(True))
    res_r = ci[3] + co[3] + m_om2 * x_r
    res_z = ci[4] + co[4]
    fr_r = fr_z = 0.0
    if g_i != 0.0 and ci[0] > 0.0:
        fr_r, fr_z = -g_i * ci[4] / ci[0], g_i * ci[3] / ci[0]
        res_r += fr_r
        res_z += fr_z
    if g_o != 0.0 and co[0] > 0.0:
        res_r += -g_o * co[4] / co[0]
        res_z += g_o * co[3] / co[0]
    # ∂r/∂x = −J_i − J_o + diag(m ω², 0)
    a_rr = -ci[5] - co[5] + m_om2
    a_rz = -ci[6] - co[6]
    a_zr = -ci[7] - co[7]
    a_zz = -ci[8] - co[8]
    return res_r, res_z, a_rr, a_rz, a_zr, a_zz, ci, co, fr_r, fr_z


@numba.njit(**KERNEL)
def _initial_ball_position(ci_r, ci_z, co_r, co_z, grooves, m_om2, x):
    """Collinear (no centrifugal force) solution, or the ball resting on the outer groove.

    Without centrifugal force the loaded ball lies on the segment C_o–C_i with
    k_i δ_i^{3/2} = k_o δ_o^{3/2}, δ_i + δ_o = |C_i − C_o| − gap_i − gap_o (exact, both
    contacts share the line so share α). Returns True when that total approach is ≤ 0.
    """
    tab_i, tab_o, gap_i, gap_o = grooves.tab_i, grooves.tab_o, grooves.gap_i, grooves.gap_o
    e_r, e_z = ci_r - co_r, ci_z - co_z
    length = math.sqrt(e_r * e_r + e_z * e_z)
    approach = length - gap_i - gap_o
    if length > 0.0 and approach > 0.0:
        e_r, e_z = e_r / length, e_z / length
        alpha = math.atan2(e_z, e_r)
        k_i = hertz_table_eval(tab_i, alpha)[0]
        k_o = hertz_table_eval(tab_o, alpha)[0]
        c_i, c_o = k_i ** (-2.0 / 3.0), k_o ** (-2.0 / 3.0)
        s_i = gap_i + approach * c_i / (c_i + c_o)
        x[0], x[1] = ci_r - s_i * e_r, ci_z - s_i * e_z
        return False
    if m_om2 > 0.0:  # centrifugal force seats the ball in the outer groove bottom
        k_o = hertz_table_eval(tab_o, 0.0)[0]
        seat = (m_om2 * co_r / k_o) ** (2.0 / 3.0)
        x[0], x[1] = co_r + gap_o + seat, co_z
        return True
    # free ball: mid-play on the segment C_o → C_i, touching neither groove
    if length > 0.0:
        e_r, e_z = e_r / length, e_z / length
    else:
        e_r, e_z = 1.0, 0.0
    t = 0.5 * (length - gap_i + gap_o)
    x[0], x[1] = co_r + t * e_r, co_z + t * e_z
    return True


@numba.njit(**KERNEL)
def _newton_ball(ci_r, ci_z, co_r, co_z, grooves, m_om2, g_i, g_o, x):
    """Damped Newton on the ball residual from x (in/out); True when converged."""
    tol = 1e-14  # [m] Newton step at which we stop: ~1e-9 of a Hertz approach
    for _ in range(60):
        out = ball_residual(x[0], x[1], ci_r, ci_z, co_r, co_z, grooves, m_om2, g_i, g_o)
        r_r, r_z, a_rr, a_rz, a_zr, a_zz = out[0], out[1], out[2], out[3], out[4], out[5]
        det = a_rr * a_zz - a_rz * a_zr
        if det == 0.0 or not math.isfinite(det):
            return False
        dx_r = -(a_zz * r_r - a_rz * r_z) / det
        dx_z = -(-a_zr * r_r + a_rr * r_z) / det
        norm0 = r_r * r_r + r_z * r_z
        dx_len = math.sqrt(dx_r * dx_r + dx_z * dx_z)
        if dx_len <= tol:  # round-off level: the residual is noise, do not line-search it
            x[0] += dx_r
            x[1] += dx_z
            return True
        step = 1.0
        for _ls in range(40):  # backtrack on |r|² (a full step may open a contact)
            t = ball_residual(x[0] + step * dx_r, x[1] + step * dx_z, ci_r, ci_z, co_r, co_z,
                              grooves, m_om2, g_i, g_o)
            if t[0] * t[0] + t[1] * t[1] <= norm0 or step < 1e-6:
                break
            step *= 0.5
        x[0] += step * dx_r
        x[1] += step * dx_z
    return False


@numba.njit(**KERNEL)
def solve_ball(ci_r, ci_z, co_r, co_z, grooves, m_om2, g_i, g_o, x, warm):
    """Equilibrium position x = (r, z) of one ball (in/out); returns a status.

    warm: start from x, falling back to the cold start if that fails. STATUS_LOOSE: no
    centrifugal force and no contact closure — the ball carries nothing and x is left at
    a guess. STATUS_FAILED: no convergence.
    """
    if m_om2 <= 0.0:
        e_r, e_z = ci_r - co_r, ci_z - co_z
        if math.sqrt(e_r * e_r + e_z * e_z) <= grooves.gap_i + grooves.gap_o:
            _initial_ball_position(ci_r, ci_z, co_r, co_z, grooves, m_om2, x)
            return STATUS_LOOSE
    if warm and math.isfinite(x[0]) and math.isfinite(x[1]):
        if _newton_ball(ci_r, ci_z, co_r, co_z, grooves, m_om2, g_i, g_o, x):
            return STATUS_OK
    _initial_ball_position(ci_r, ci_z, co_r, co_z, grooves, m_om2, x)
    if _newton_ball(ci_r, ci_z, co_r, co_z, grooves, m_om2, g_i, g_o, x):
        return STATUS_OK
    return STATUS_FAILED


@numba.njit(**KERNEL)
def bearing_equilibrium(ci, gmat, R_co, grooves, loads, xb, warm, out_force, out_stiffness, out_ball):
    """Contact load on the inner race and its condensed stiffness, balls in equilibrium.

    ci (Z, 2): inner curvature centres (r, z) [m]; gmat (Z, 2, 5): ∂C_i/∂q; R_co = d_o/2 [m];
    grooves: `Grooves`; loads: `BallLoads`. xb (Z, 2): ball positions (in/out; used as
    the start when warm). Writes out_force (5) = Σ Gᵀ(−F_i − F_fric,i) [N, N·m],
    out_stiffness (5×5) = Σ Gᵀ [J_i − J_i (J_i + J_o − C)⁻¹ J_i] G (−∂out_force/∂q with
    the balls re-equilibrated, at fixed G; friction Jacobian neglected), out_ball (Z,
    BALL_COLUMNS) with the force (f_r, f_z) on the race in B_FR, B_FZ.
    Returns the number of balls whose Newton failed.
    """
    failed = 0
    out_force[:] = 0.0
    out_stiffness[:, :] = 0.0
    for k in range(ci.shape[0]):
        ci_r, ci_z = ci[k, 0], ci[k, 1]
        m_om2, g_i, g_o = loads.m_om2[k], loads.g_i[k], loads.g_o[k]
        status = solve_ball(ci_r, ci_z, R_co, 0.0, grooves, m_om2, g_i, g_o, xb[k], warm)
        res = ball_residual(xb[k, 0], xb[k, 1], ci_r, ci_z, R_co, 0.0, grooves, m_om2, g_i, g_o)
        c_i, c_o, fr_r, fr_z = res[6], res[7], res[8], res[9]
        if status == STATUS_FAILED:
            failed += 1
        # force on the race at C_i (friction treated as acting there too: lever error ~D/2)
        f_r, f_z = -c_i[3] - fr_r, -c_i[4] - fr_z
        row = out_ball[k]
        row[B_QI], row[B_QO], row[B_AI], row[B_AO] = c_i[0], c_o[0], c_i[1], c_o[1]
        row[B_DI], row[B_DO], row[B_STATUS] = c_i[2], c_o[2], status
        row[B_FRIC_R], row[B_FRIC_Z], row[B_FR], row[B_FZ] = fr_r, fr_z, f_r, f_z
        if c_i[0] <= 0.0:
            continue
        g = gmat[k]
        for j in range(5):
            out_force[j] += g[0, j] * f_r + g[1, j] * f_z
        # condensed 2×2 stiffness: J_i − J_i A⁻¹ J_i, A = J_i + J_o − C = −∂r/∂x
        a_rr, a_rz, a_zr, a_zz = -res[2], -res[3], -res[4], -res[5]
        det = a_rr * a_zz - a_rz * a_zr
        j_rr, j_rz, j_zr, j_zz = c_i[5], c_i[6], c_i[7], c_i[8]
        # A⁻¹ J_i
        b_rr = (a_zz * j_rr - a_rz * j_zr) / det
        b_rz = (a_zz * j_rz - a_rz * j_zz) / det
        b_zr = (-a_zr * j_rr + a_rr * j_zr) / det
        b_zz = (-a_zr * j_rz + a_rr * j_zz) / det
        k_rr = j_rr - (j_rr * b_rr + j_rz * b_zr)
        k_rz = j_rz - (j_rr * b_rz + j_rz * b_zz)
        k_zr = j_zr - (j_zr * b_rr + j_zz * b_zr)
        k_zz = j_zz - (j_zr * b_rz + j_zz * b_zz)
        for a in range(5):
            ga_r, ga_z = g[0, a], g[1, a]
            for b in range(5):
                gb_r, gb_z = g[0, b], g[1, b]
                out_stiffness[a, b] += ga_r * (k_rr * gb_r + k_rz * gb_z) + ga_z * (k_zr * gb_r + k_zz * gb_z)
    return failed


@numba.njit(**KERNEL)
def ball_kinematics(alpha_i, alpha_o, x_r, D, omega_i, omega_o, inner_control):
    """Orbital speed ω_m and ball angular velocity (ω_r, ω_z) [rad/s] from pure rolling.

    Pure rolling (no slip along e_t) at both contact points p = x_b − (D/2) n, plus zero
    spin (ω_b − Ω_race e_z)·n = 0 at the controlling race ("race control", Jones 1960;
    Harris & Kotzalas vol. 2 ch. 3). α: signed contact angles, x_r: ball orbit radius [m],
    Ω_i, Ω_o: race speeds about +z [rad/s]. Linear 3×3 system, solved by Cramer's rule.
    """
    ni_r, ni_z = math.cos(alpha_i), math.sin(alpha_i)
    no_r, no_z = -math.cos(alpha_o), -math.sin(alpha_o)
    h = 0.5 * D
    di_r, di_z = -h * ni_r, -h * ni_z
    do_r, do_z = -h * no_r, -h * no_z
    # rows: [ω_m, ω_r, ω_z] coefficients | rhs
    m = np.empty((3, 3))
    rhs = np.empty(3)
    m[0, 0], m[0, 1], m[0, 2], rhs[0] = x_r, -di_z, di_r, omega_i * (x_r + di_r)
    m[1, 0], m[1, 1], m[1, 2], rhs[1] = x_r, -do_z, do_r, omega_o * (x_r + do_r)
    if inner_control:
        m[2, 0], m[2, 1], m[2, 2], rhs[2] = 0.0, ni_r, ni_z, ni_z * omega_i
    else:
        m[2, 0], m[2, 1], m[2, 2], rhs[2] = 0.0, no_r, no_z, no_z * omega_o
    det = np.linalg.det(m)
    sol = np.empty(3)
    for c in range(3):
        mc = m.copy()
        for i in range(3):  # not `mc[:, c] = rhs`: see `multibody.small.add_into`
            mc[i, c] = rhs[i]
        sol[c] = np.linalg.det(mc) / det
    return sol[0], sol[1], sol[2]
