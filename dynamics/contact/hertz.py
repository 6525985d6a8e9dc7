"""Hertz point contact of a ball in a groove (docs/model.md §6.2, M.24, M.34).

Kernels are pure numba functions of floats and float64 arrays, SI units:

- `elliptic_km` — complete elliptic integrals K(m), E(m) (parameter m) by the AGM.
- `ellipticity` — exact κ = a/b from the curvature difference F(ρ).
- `hertz_exact` — κ, δ*, k_h and the semi-axis coefficients for one curvature set.
- `hertz_hamrock_brewe` — the Hamrock–Brewe closed forms (comparison / fast path).
- `race_curvature` — Σρ and F(ρ) of the ball–race contact versus contact angle α.
- `build_hertz_table` / `hertz_table_eval` — the α-table the time loop interpolates.
- `normal_tangent` — the 3×3 tangent of the Hertz normal force (M.34).

Notation (Harris & Kotzalas, "Rolling Bearing Analysis", 5th ed., vol. 1, ch. 6):
x is the rolling direction, y the groove direction; a (along y) is the semi-major axis,
b (along x) the semi-minor one; κ = a/b ≥ 1; F_n = k_h δ^{3/2} (M.24);
a = c_a F_n^{1/3}, b = c_b F_n^{1/3}, p_max = 3 F_n / (2π a b).
"""

from __future__ import annotations

import math

import numba
import numpy as np

from .._speed.compile_policy import KERNEL, NO_REFCOUNT

# Columns of a Hertz table row (value, d/dα pairs for cubic Hermite interpolation).
TAB_KH, TAB_DKH, TAB_KAPPA, TAB_DKAPPA, TAB_CA, TAB_DCA, TAB_CB, TAB_DCB = range(8)
TABLE_COLUMNS = 8
DEFAULT_TABLE_NODES = 181  # 0.5° spacing on [0, 90°]: max relative error ~1e-9


@numba.njit(**KERNEL)
def elliptic_km(m):
    """Complete elliptic integrals (K(m), E(m)) of parameter m = k² ∈ [0, 1).

    Arithmetic–geometric mean: K = π / (2 AGM(1, √(1−m))), and
    E = K (1 − Σ_n 2^{n−1} c_n²) with c_0² = m, c_{n+1} = (a_n − b_n)/2
    (Abramowitz & Stegun 17.6). Used by the ellipticity equation of M.24's k_h.
    """
    a = 1.0
    b = math.sqrt(1.0 - m)
    c2_sum = 0.5 * m  # n = 0 term: 2^{-1} c_0²
    weight = 0.5
    for _ in range(40):
        c = 0.5 * (a - b)
        a, b = 0.5 * (a + b), math.sqrt(a * b)
        weight *= 2.0
        c2_sum += weight * c * c
        if abs(c) <= 1e-17 * a:
            break
    k = 0.5 * math.pi / a
    return k, k * (1.0 - c2_sum)


@numba.njit(**KERNEL)
def _ellipticity_residual(log_kappa, f_rho):
    kappa2 = math.exp(2.0 * log_kappa)
    k, e = elliptic_km(1.0 - 1.0 / kappa2)
    return ((kappa2 + 1.0) * e - 2.0 * k) / ((kappa2 - 1.0) * e) - f_rho


@numba.njit(**KERNEL)
def ellipticity(f_rho):
    """Ellipticity κ = a/b [-] solving F(ρ) = [(κ²+1)E(m) − 2K(m)] / [(κ²−1)E(m)].

    m = 1 − 1/κ² (docs/model.md §6.2). The right-hand side increases monotonically from 0
    (κ = 1) to 1 (κ → ∞), so bisection on ln κ is safe; 200 halvings of [0, ln 1e4]
    reach round-off. F(ρ) < 1e-12 returns κ = 1 (circular contact).
    """
    if f_rho < 1e-12:
        return 1.0
    lo, hi = 1e-9, math.log(1e4)
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if _ellipticity_residual(mid, f_rho) > 0.0:
            hi = mid
        else:
            lo = mid
        if hi - lo <= 4e-16 * hi:
            break
    return math.exp(0.5 * (lo + hi))


@numba.njit(**KERNEL)
def hertz_from_kappa(kappa, k_el, e_el, sum_rho, e_eff):
    """(δ*, k_h, c_a, c_b) from κ and K, E at m = 1 − 1/κ² (Harris ch. 6; docs/model.md §6.2).

    δ* = (2K/π)(π/(2κ²E))^{1/3} [-]; k_h = (2√2/3) E' Σρ^{−1/2} δ*^{−3/2} [N/m^1.5];
    a = (2κ²E/π)^{1/3} X^{1/3}, b = (2E/(πκ))^{1/3} X^{1/3}, X = 3F/(2Σρ)·(2/E'), so
    c_a = a/F^{1/3}, c_b = b/F^{1/3} [m/N^{1/3}]. Σρ [1/m], E' effective modulus [Pa].
    """
    delta_star = (2.0 * k_el / math.pi) * (math.pi / (2.0 * kappa * kappa * e_el)) ** (1.0 / 3.0)
    k_h = (2.0 * math.sqrt(2.0) / 3.0) * e_eff / math.sqrt(sum_rho) * delta_star**-1.5
    x_per_f = (3.0 / (2.0 * sum_rho)) * (2.0 / e_eff)
    c_a = (2.0 * kappa * kappa * e_el / math.pi * x_per_f) ** (1.0 / 3.0)
    c_b = (2.0 * e_el / (math.pi * kappa) * x_per_f) ** (1.0 / 3.0)
    return delta_star, k_h, c_a, c_b


@numba.njit(**KERNEL)
def hertz_exact(sum_rho, f_rho, e_eff):
    """Exact Hertz constants (κ, δ*, k_h, c_a, c_b) for curvature sum Σρ [1/m] and F(ρ).

    M.24 with κ from the exact ellipticity equation. e_eff = E' [Pa].
    """
    kappa = ellipticity(f_rho)
    k_el, e_el = elliptic_km(1.0 - 1.0 / (kappa * kappa))
    delta_star, k_h, c_a, c_b = hertz_from_kappa(kappa, k_el, e_el, sum_rho, e_eff)
    return kappa, delta_star, k_h, c_a, c_b


@numba.njit(**KERNEL)
def hertz_hamrock_brewe(sum_rho, f_rho, e_eff):
    """Hamrock–Brewe closed forms (ASME J. Lubr. Technol. 105, 1983), same outputs as
    `hertz_exact`: κ ≈ 1.0339 (R_y/R_x)^0.636, E ≈ 1.0003 + 0.5968 R_x/R_y,
    K ≈ 1.5277 + 0.6023 ln(R_y/R_x). With 1/R_x + 1/R_y = Σρ and
    (1/R_x − 1/R_y)/Σρ = F(ρ), R_y/R_x = (1+F)/(1−F). About 3 % off at tight conformity.
    """
    ratio = (1.0 + f_rho) / (1.0 - f_rho)  # R_y / R_x >= 1
    kappa = 1.0339 * ratio**0.636
    e_el = 1.0003 + 0.5968 / ratio
    k_el = 1.5277 + 0.6023 * math.log(ratio)
    delta_star, k_h, c_a, c_b = hertz_from_kappa(kappa, k_el, e_el, sum_rho, e_eff)
    return kappa, delta_star, k_h, c_a, c_b


@numba.njit(**KERNEL)
def race_curvature(alpha, ball_diameter, pitch_diameter, groove_radius, is_outer):
    """Curvature sum Σρ [1/m] and difference F(ρ) [-] of a ball–race contact at angle α.

    docs/model.md §6.2 table (Harris sign convention, convex +): ρ_I1 = ρ_I2 = 2/D;
    inner: ρ_II1 = 2cosα/(d_m − D cosα), ρ_II2 = −1/r_i;
    outer: ρ_II1 = −2cosα/(d_m + D cosα), ρ_II2 = −1/r_o.
    """
    c = math.cos(alpha)
    D = ball_diameter
    if is_outer:
        rho_ii1 = -2.0 * c / (pitch_diameter + D * c)
    else:
        rho_ii1 = 2.0 * c / (pitch_diameter - D * c)
    rho_ii2 = -1.0 / groove_radius
    sum_rho = 4.0 / D + rho_ii1 + rho_ii2
    return sum_rho, (rho_ii1 - rho_ii2) / sum_rho


@numba.njit(**KERNEL)
def _race_row(alpha, D, d_m, r, is_outer, e_eff):
    sum_rho, f_rho = race_curvature(alpha, D, d_m, r, is_outer)
    kappa, _, k_h, c_a, c_b = hertz_exact(sum_rho, f_rho, e_eff)
    return k_h, kappa, c_a, c_b


@numba.njit(**KERNEL)
def build_hertz_table(ball_diameter, pitch_diameter, groove_radius, is_outer, e_eff, n_nodes):
    """Exact Hertz constants on n_nodes equally spaced α ∈ [0, π/2] for one race.

    Returns an (n_nodes, 8) array: k_h [N/m^1.5], κ [-], c_a, c_b [m/N^{1/3}], each
    followed by its derivative in α (central difference of the exact solve, h = 1e-4
    rad, one-sided at the ends) for C¹ cubic Hermite interpolation by `hertz_table_eval`.
    """
    table = np.empty((n_nodes, TABLE_COLUMNS))
    step = 0.5 * math.pi / (n_nodes - 1)
    h = 1e-4
    for j in range(n_nodes):
        alpha = j * step
        v = _race_row(alpha, ball_diameter, pitch_diameter, groove_radius, is_outer, e_eff)
        a_lo, a_hi = max(alpha - h, 0.0), min(alpha + h, 0.5 * math.pi)
        lo = _race_row(a_lo, ball_diameter, pitch_diameter, groove_radius, is_outer, e_eff)
        hi = _race_row(a_hi, ball_diameter, pitch_diameter, groove_radius, is_outer, e_eff)
        for c in range(4):
            table[j, 2 * c] = v[c]
            table[j, 2 * c + 1] = (hi[c] - lo[c]) / (a_hi - a_lo)
    return table


@numba.njit(**NO_REFCOUNT)
def hermite(table, j, col, t, step):
    """Cubic Hermite interpolation of column col (value) with col + 1 (slope per rad) of a
    contact-angle table between rows j and j + 1 at fraction t; returns (value, slope)."""
    y0, y1 = table[j, col], table[j + 1, col]
    m0, m1 = table[j, col + 1] * step, table[j + 1, col + 1] * step
    t2 = t * t
    t3 = t2 * t
    value = (2 * t3 - 3 * t2 + 1) * y0 + (t3 - 2 * t2 + t) * m0 + (-2 * t3 + 3 * t2) * y1 + (t3 - t2) * m1
    slope = ((6 * t2 - 6 * t) * y0 + (3 * t2 - 4 * t + 1) * m0 + (-6 * t2 + 6 * t) * y1 + (3 * t2 - 2 * t) * m1) / step
    return value, slope


@numba.njit(**NO_REFCOUNT)
def table_position(table, alpha):
    """(row j, fraction t, step [rad]) of |alpha| on a table's uniform grid over [0, pi/2]
    (|alpha| > pi/2 is clamped)."""
    n = table.shape[0]
    step = 0.5 * math.pi / (n - 1)
    x = min(abs(alpha), 0.5 * math.pi) / step
    j = min(int(x), n - 2)
    return j, x - j, step


@numba.njit(**NO_REFCOUNT)
def hertz_table_eval(table, alpha):
    """Interpolate a Hertz table at contact angle α [rad] (any sign; constants are even in α).

    Returns (k_h [N/m^1.5], dk_h/dα [N/m^1.5/rad], κ [-], c_a, c_b [m/N^{1/3}]).
    |α| > π/2 is clamped (no physical ball–race contact lies there).
    """
    sign = 1.0 if alpha >= 0.0 else -1.0
    j, t, step = table_position(table, alpha)
    # columns typed int64, not Literal[int]: numba compiles a callee once per literal argument
    k_h, dk = hermite(table, j, np.int64(TAB_KH), t, step)
    kappa, _ = hermite(table, j, np.int64(TAB_KAPPA), t, step)
    c_a, _ = hermite(table, j, np.int64(TAB_CA), t, step)
    c_b, _ = hermite(table, j, np.int64(TAB_CB), t, step)
    return k_h, sign * dk, kappa, c_a, c_b


@numba.njit(**KERNEL)
def semi_axis_coefficients(table, alpha):
    """c_a, c_b [m/N^{1/3}] (a = c_a F^{1/3}, b = c_b F^{1/3}) of a Hertz table at every contact
    angle of the array `alpha` [rad]: `hertz_table_eval` for many angles at once."""
    c_a = np.empty(alpha.size)
    c_b = np.empty(alpha.size)
    flat = alpha.ravel()
    for i in range(flat.size):
        _, _, _, c_a[i], c_b[i] = hertz_table_eval(table, flat[i])
    return c_a.reshape(alpha.shape), c_b.reshape(alpha.shape)


@numba.njit(**KERNEL)
def max_pressure(force, c_a, c_b):
    """p_max = 3F/(2π a b) [Pa] with a = c_a F^{1/3}, b = c_b F^{1/3} (docs/model.md §6.2)."""
    if force <= 0.0:
        return 0.0
    return 3.0 * force ** (1.0 / 3.0) / (2.0 * math.pi * c_a * c_b)


@numba.njit(**KERNEL)
def normal_tangent(k_h, delta, n, lever, out):
    """Tangent of the Hertz normal force, M.34, written into out (3×3) [N/m].

    ΔF ≈ (3/2) k_h δ^{1/2} Δδ n + F_n Δn with Δδ = n·Δu and Δn = (I − nnᵀ) Δu / ℓ,
    where Δu [m] is the change of the vector whose length grows with δ (for ball–race:
    groove curvature centre minus ball centre, ℓ = its length) and n its unit vector.
    So ΔF = out @ Δu with out = (3/2) k_h δ^{1/2} nnᵀ + (F_n/ℓ)(I − nnᵀ). The change of
    k_h with α is neglected, as M.34 says. lever = inf drops the rotation term.
    """
    for i in range(3):
        for j in range(3):
            out[i, j] = 0.0
    if delta <= 0.0:
        return
    f_n = k_h * delta**1.5
    k_n = 1.5 * k_h * math.sqrt(delta)
    k_t = f_n / lever if math.isfinite(lever) else 0.0
    for i in range(3):
        for j in range(3):
            nn = n[i] * n[j]
            out[i, j] = k_n * nn + k_t * ((1.0 if i == j else 0.0) - nn)


def race_hertz_table(geometry, e_eff: float, outer: bool, n_nodes: int = DEFAULT_TABLE_NODES) -> np.ndarray:
    """Exact Hertz table (see `build_hertz_table`) for the inner or outer race of a bearing.

    geometry: `dynamics.geometry.BearingGeometry`; e_eff: E' [Pa] from
    `dynamics.geometry.effective_modulus(ball, race)`.
    """
    r = geometry.outer_groove_radius if outer else geometry.inner_groove_radius
    return build_hertz_table(geometry.ball_diameter, geometry.pitch_diameter, r, outer, e_eff, n_nodes)
