"""The dynamic short-bearing film: Ocvirk's short bearing with the squeeze and whirl terms
of the Reynolds equation, in closed form (docs/model.md §8, eqs. M.94b–M.94e).

Why: the static short bearing (paper eqs. 25–26) is the film of a journal whose centre
does not move. A cage centre moves, and the Reynolds equation's time term dh/dt is of the
same order as its wedge term; without it the film has no radial damping at all. The
dynamic form below is the complete short-bearing solution (Ocvirk's assumption
d/dx << d/dz, Gümbel's half film) for any centre velocity, as used for lubricated joints in
multibody codes (Flores, Ambrósio, Claro & Lankarani, Mech. Mach. Theory 41 (2006) 247–261;
the general π-film by the velocity direction is the short-bearing "impedance" of Childs,
Moes & van Leeuwen, J. Lubr. Technol. 99 (1977) 321–331).

Short-bearing pressure (Reynolds with d/dx neglected) for a journal at offset e (2), centre
velocity v (2), surfaces turning at omega = omega_journal + omega_bearing:

    p(theta, z) = 6 mu (L^2/4 - z^2) (V . n) / h^3,    V = v - (omega/2) e_z x e       (M.94b)

with n = (cos theta, sin theta) and h = C - e . n. Gümbel's condition keeps p > 0, the half
film facing V. The force on the journal, F = -int p n R dtheta dz:

    F = -K int_{V.n > 0} (V . n) n / (1 - (e/C) . n)^3 dtheta,   K = mu R L^3 / C^3    (M.94c)

For V = -(omega/2) e_z x e (a centre at rest) this is exactly the static Ocvirk force
(paper eq. 25); with the half film held at the static position it is Flores et al.'s form with
omega -> omega - 2 phi_dot and the squeeze term in eps_dot. Here the half film follows V,
so F is continuous everywhere and smooth except at V = 0 (half-speed whirl, F = 0).

The integrals have closed forms under Sommerfeld's substitution (1 - eps cos theta)
(1 + eps cos psi) = 1 - eps^2, which turns each into a trigonometric polynomial in psi
(M.94d). Because the integrand vanishes on the film's edges (V . n = 0), the edges carry no
derivative: dF/dV = -K int n n^T / h^3 and dF/de|_V = -(3K/C) int (V . n) n n^T / h^4 (M.94e).
"""

from __future__ import annotations

import math

import numba
import numpy as np

from .._speed.compile_policy import KERNEL

N_SQUEEZE_OUT = 10  # force (2), dF/de at fixed V (2x2 row-major), dF/dV (2x2 row-major)


@numba.njit(**KERNEL)
def sommerfeld_angle(theta, eps):
    """psi(theta) of Sommerfeld's substitution, continuous in theta (psi(theta + 2 pi) =
    psi(theta) + 2 pi): tan(psi/2) = sqrt((1 + eps)/(1 - eps)) tan(theta/2)."""
    k = math.sqrt((1.0 + eps) / (1.0 - eps))
    c = math.cos(theta)
    return theta + 2.0 * math.atan((k - 1.0) * math.sin(theta) / ((1.0 + c) + k * (1.0 - c)))


@numba.njit(**KERNEL)
def _second_moments(p, eps):
    """Antiderivatives in psi of (cos + eps)^2, sin (cos + eps), sin^2 (M.94d)."""
    s, c = math.sin(p), math.cos(p)
    return (0.5 * p + 0.5 * s * c + 2.0 * eps * s + eps * eps * p,
            0.5 * s * s - eps * c,
            0.5 * p - 0.5 * s * c)


@numba.njit(**KERNEL)
def _third_moments(p, eps):
    """Antiderivatives in psi of (cos + eps)^3, (cos + eps)^2 sin, (cos + eps) sin^2, sin^3."""
    s, c = math.sin(p), math.cos(p)
    ce = c + eps
    return ((s - s**3 / 3.0) + 3.0 * eps * (0.5 * p + 0.5 * s * c) + 3.0 * eps * eps * s + eps**3 * p,
            -ce**3 / 3.0,
            s**3 / 3.0 + eps * (0.5 * p - 0.5 * s * c),
            -c + c**3 / 3.0)


@numba.njit(**KERNEL)
def film_moments(eps, theta1, theta2):
    """Film integrals over [theta1, theta2] (theta from the direction of e, h/C = 1 - eps cos):
    (I_cc, I_cs, I_ss) = int (cos^2, cos sin, sin^2) / (1 - eps cos)^3 and
    (T_ccc, T_ccs, T_css, T_sss) = int (cos^3, cos^2 sin, cos sin^2, sin^3) / (1 - eps cos)^4.
    eps in [0, 1)."""
    q = 1.0 - eps * eps
    p1, p2 = sommerfeld_angle(theta1, eps), sommerfeld_angle(theta2, eps)
    a2, b2, c2 = _second_moments(p2, eps)
    a1, b1, c1 = _second_moments(p1, eps)
    sq = math.sqrt(q)
    i_cc = (a2 - a1) / (q * q * sq)
    i_cs = (b2 - b1) / (q * q)
    i_ss = (c2 - c1) / (q * sq)
    d2, e2, f2, g2 = _third_moments(p2, eps)
    d1, e1, f1, g1 = _third_moments(p1, eps)
    return (i_cc, i_cs, i_ss,
            (d2 - d1) / (q**3 * sq), (e2 - e1) / q**3, (f2 - f1) / (q * q * sq), (g2 - g1) / (q * q))


@numba.njit(**KERNEL)
def squeeze_film_force(ex, ey, vx, vy, omega, c_film, k_film, eps_clip, out):
    """Dynamic short-bearing film force on the journal (M.94b–M.94e), global x-y frame.

    ex, ey [m]: journal centre minus bearing centre; vx, vy [m/s]: its velocity; omega
    [rad/s]: journal + bearing speed (entrainment); c_film [m]: film clearance; k_film
    [N s/m]: K = mu R L^3 / C^3 summed over the lands; eps_clip: largest e/c_film the film
    is evaluated at (beyond it the film's eps-slope is frozen).
    out (N_SQUEEZE_OUT,): F (2) [N], dF/de at fixed V (2x2) [N/m], dF/dV (2x2) [N s/m],
    V = v - (omega/2) e_z x e. Chain rule for V is the caller's (see cage_race_journal).
    """
    e = math.hypot(ex, ey)
    erx, ery = (ex / e, ey / e) if e > 0.0 else (1.0, 0.0)
    etx, ety = -ery, erx
    eps = e / c_film
    frozen = eps > eps_clip
    if frozen:
        eps = eps_clip
    Vx = vx + 0.5 * omega * ey
    Vy = vy - 0.5 * omega * ex
    vr = Vx * erx + Vy * ery
    vt = Vx * etx + Vy * ety
    if vr == 0.0 and vt == 0.0:
        # V = 0: no film force; the slope is the mean of the two half films (full film / 2)
        i_cc, i_cs, i_ss, t_ccc, t_ccs, t_css, t_sss = film_moments(eps, -math.pi, math.pi)
        i_cc, i_cs, i_ss = 0.5 * i_cc, 0.5 * i_cs, 0.5 * i_ss
    else:
        beta = math.atan2(vt, vr)
        i_cc, i_cs, i_ss, t_ccc, t_ccs, t_css, t_sss = film_moments(
            eps, beta - 0.5 * math.pi, beta + 0.5 * math.pi)
    # local frame (e_r, e_t): F = -K A V, dF/dV = -K A, dF_i/de_k = -(3K/C) T_ijk V_j
    a_rr, a_rt, a_tt = i_cc, i_cs, i_ss
    f_r = -k_film * (a_rr * vr + a_rt * vt)
    f_t = -k_film * (a_rt * vr + a_tt * vt)
    g = 3.0 * k_film / c_film
    if frozen:
        g = 0.0
    # T_ijk V_j with T_rrr = ccc, T_rrt = ccs, T_rtt = css, T_ttt = sss
    d_rr = -g * (t_ccc * vr + t_ccs * vt)
    d_rt = -g * (t_ccs * vr + t_css * vt)
    d_tt = -g * (t_css * vr + t_sss * vt)
    # back to the global frame: out = R (.) R^T with R = [[erx, etx], [ery, ety]]
    out[0] = f_r * erx + f_t * etx
    out[1] = f_r * ery + f_t * ety
    # offsets typed int64, not Literal[int]: numba compiles a callee once per literal argument
    _rotate_sym(d_rr, d_rt, d_tt, erx, ery, out, np.int64(2))
    _rotate_sym(-k_film * a_rr, -k_film * a_rt, -k_film * a_tt, erx, ery, out, np.int64(6))


@numba.njit(**KERNEL)
def _rotate_sym(m_rr, m_rt, m_tt, erx, ery, out, at):
    """out[at:at+4] = R M R^T (row-major) for the symmetric local M, R = [e_r e_t]."""
    etx, ety = -ery, erx
    out[at] = erx * erx * m_rr + 2.0 * erx * etx * m_rt + etx * etx * m_tt
    out[at + 1] = erx * ery * m_rr + (erx * ety + etx * ery) * m_rt + etx * ety * m_tt
    out[at + 2] = out[at + 1]
    out[at + 3] = ery * ery * m_rr + 2.0 * ery * ety * m_rt + ety * ety * m_tt


def squeeze_film_reference(ex, ey, vx, vy, omega, c_film, k_film, nodes: int = 20000) -> np.ndarray:
    """Slow twin for the tests: M.94c by a fine midpoint rule over the full circle with the
    half film selected by V . n > 0."""
    theta = (np.arange(nodes) + 0.5) * 2.0 * np.pi / nodes
    n = np.stack([np.cos(theta), np.sin(theta)])
    V = np.array([vx + 0.5 * omega * ey, vy - 0.5 * omega * ex])
    vn = V @ n
    h = 1.0 - (np.array([ex, ey]) / c_film) @ n
    w = np.where(vn > 0.0, vn, 0.0) / h**3
    return -k_film * (n * w).sum(axis=1) * 2.0 * np.pi / nodes
