"""Fast Eyring traction for the time loop: a spin-pole-centred quadrature (MODEL.md §6.4).

Same physics and sign convention as `dynamics.traction` (force and spin moment on the ball,
Jacobian d(F_x, F_y, M_z)/d(du0, dv0, w_s)), different node placement. Why not the plain
ellipse-centred rule with few nodes: with spin, the sliding field
s = (du0 - w_s y, dv0 + w_s x) = w_s e_z x (r - r_p) rotates about the spin pole
r_p = (-dv0/w_s, du0/w_s); where the pole lies in or near the ellipse the Eyring stress
turns through 360 deg around it and its tangent grows like 1/|r - r_p|, and a coarse
ellipse-centred grid is off by tens of percent (measured: 37 % with 8 x 16 nodes).

In polar coordinates centred on the pole (in the scaled plane X = x/a, Y = y/b, where the
ellipse is the unit disc) the sliding speed is |w_s| t q(psi) and its direction depends on
psi alone, so the integrand is smooth in both variables; the remaining square-root edges of
the Hertz pressure are removed by the substitutions below. Three cases:

- pole inside the disc: rays psi in [0, 2 pi) (periodic trapezoid), radius t = R(psi) S(v)
  with the smooth step S(v) = 3v^2 - 2v^3 (flattens both the pole and the sqrt edge);
- pole outside, |P| <= far_ratio: the cone of chords through the disc, psi = beta sin(xi)
  and t = t_mid - half cos(zeta) (both sqrt ends become smooth);
- pole far away (|P| > far_ratio or w_s = 0): the field is smooth on the disc and the
  ellipse-centred rule of `dynamics.traction` is used with the same node counts.

Viscosity comes from a table of eta on a uniform pressure grid (linear interpolation;
relative error in eta ~ 1e-4 for 4096 points to 5 GPa), built once per lubricant and
temperature by `FastTraction`. Outside the table (p > p_max) eta is held at its last
value and `flag` is set; inputs that are not a contact (a, b, p_h or h <= 0) give zero
force and flag 2. No input gives NaN.

Accuracy against the converged quadrature over the reference-scene range (slide-to-roll
1e-5..0.3, 100..6000 N, 0.1..2x speed, spin-to-roll 0.01..0.1), default 12 x 48 nodes:
max 0.13 % in |F|, 0.6 % in M_z, 0.24 % in the Jacobian (200-point sample, bench). 8 x 32
nodes is ~2x cheaper with 1 % in |F| and J but up to 4 % in M_z where M_z is itself small
(a few % of |F| b, cancellation). Cost ~10-30 us per call on the 2-core dev box: far above
the 0.5 us target -- see tests/test_traction.py and `python -m pipeline.bench.traction`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numba
import numpy as np

from dynamics import rheology

ANISOTROPY_SPLIT = 0.5
FLAG_OK = 0
FLAG_PRESSURE_CLAMPED = 1
FLAG_NO_CONTACT = 2


@numba.njit(cache=True, inline="always")
def _eta(p, eta_table, p_step):
    """Linear interpolation of eta(p) on the uniform table; clamps above the last point.

    Interpolating eta itself (not ln eta) saves an exp per node; with p_step ~ 1 MPa and
    d ln eta/dp <~ 3e-8 1/Pa the relative interpolation error is <~ (0.03)^2/8 ~ 1e-4.
    """
    f = p / p_step
    n = eta_table.shape[0] - 1
    if f >= n:
        return eta_table[n]
    i = int(f)
    w = f - i
    return (1.0 - w) * eta_table[i] + w * eta_table[i + 1]


@numba.njit(cache=True, inline="always")
def _eyring_response_fast(k, r):
    """eyring_response with asinh written as log(x + sqrt(1 + x^2)) sharing the sqrt."""
    x = k * r
    if x < 1e-4:
        x2 = x * x
        return k * (1.0 - x2 / 6.0), k * k * k * (-1.0 / 3.0 + 0.3 * x2)
    root = math.sqrt(1.0 + x * x)
    ash = math.log(x + root)
    inv_r = 1.0 / r
    return ash * inv_r, (x / root - ash) * inv_r * inv_r * inv_r


@numba.njit(cache=True, fastmath=True)
def _accumulate(nodes, n, a, b, p_h, inv_tau0_h, du0, dv0, w_s, eta_table, p_step, out):
    """Sum the Eyring integrand over nodes[:n] = (X, Y, weight) (scaled coords) into out[12].

    Kept as one tight loop with scalar accumulators: interleaving it with the node
    generation was 2.5x slower (the accumulators then live in memory).
    """
    Fx = Fy = Mz = 0.0
    j00 = j01 = j02 = j11 = j12 = j20 = j21 = j22 = 0.0
    for m in range(n):
        X = nodes[m, 0]
        Y = nodes[m, 1]
        wgt = nodes[m, 2]
        q = 1.0 - X * X - Y * Y
        p = p_h * math.sqrt(q) if q > 0.0 else 0.0
        k = _eta(p, eta_table, p_step) * inv_tau0_h
        x = a * X
        y = b * Y
        sx = du0 - w_s * y
        sy = dv0 + w_s * x
        g, c = _eyring_response_fast(k, math.sqrt(sx * sx + sy * sy))
        tx = g * sx
        ty = g * sy
        axx = g + c * sx * sx
        axy = c * sx * sy
        ayy = g + c * sy * sy
        dtx_dw = -axx * y + axy * x
        dty_dw = -axy * y + ayy * x
        Fx -= wgt * tx
        Fy -= wgt * ty
        Mz -= wgt * (x * ty - y * tx)
        j00 -= wgt * axx
        j01 -= wgt * axy
        j02 -= wgt * dtx_dw
        j11 -= wgt * ayy
        j12 -= wgt * dty_dw
        j20 -= wgt * (x * axy - y * axx)
        j21 -= wgt * (x * ayy - y * axy)
        j22 -= wgt * (x * dty_dw - y * dtx_dw)
    out[0] = Fx
    out[1] = Fy
    out[2] = Mz
    out[3] = j00
    out[4] = j01
    out[5] = j02
    out[6] = j01  # d F_y / d du0 = d F_x / d dv0: A is symmetric
    out[7] = j11
    out[8] = j12
    out[9] = j20
    out[10] = j21
    out[11] = j22


@numba.njit(cache=True)
def traction_fast(a, b, p_h, h, tau0, du0, dv0, w_s, eta_table, p_step, gl_x, gl_w, ga_x, ga_w, far_ratio, nodes, out):
    """Eyring traction on the ball, pole-centred quadrature (MODEL.md §6.4).

    a, b [m] semi-axes (x = entrainment), p_h [Pa], h [m] central film, tau0 [Pa],
    du0, dv0 [m/s] sliding velocity ball - race at the centre, w_s [rad/s] spin.
    eta_table: eta [Pa.s] at p = i p_step [Pa]; gl_x, gl_w: Gauss-Legendre nodes and
    weights on [0, 1] for the radial/chord direction, ga_x, ga_w: the same for the angular
    direction of the chord cone (n_angle = len(ga_x) also sets the periodic rule); far_ratio: |pole|/radius beyond which the
    ellipse-centred rule is used; nodes: scratch array of shape (>= n_r n_angle, 3).
    Writes out[0:3] = (F_x [N], F_y [N], M_z [N.m]) and
    out[3:12] = d(F_x, F_y, M_z)/d(du0, dv0, w_s) row-major; returns a flag (FLAG_*).
    """
    for m in range(12):
        out[m] = 0.0
    if a <= 0.0 or b <= 0.0 or p_h <= 0.0 or h <= 0.0:
        return FLAG_NO_CONTACT
    flag = FLAG_PRESSURE_CLAMPED if p_h > p_step * (eta_table.shape[0] - 1) else FLAG_OK
    inv_tau0_h = 1.0 / (tau0 * h)
    scale = a * b * tau0
    n_r = gl_x.shape[0]
    n_angle = ga_x.shape[0]
    n = 0
    gl_cos = np.empty(n_r)
    gl_sin = np.empty(n_r)
    for i in range(n_r):
        gl_cos[i] = math.cos(math.pi * gl_x[i])
        gl_sin[i] = math.sin(math.pi * gl_x[i])
    # Working plane (U, V) = (x/sqrt(a b), y/b): the ellipse has semi-axes (A, 1) with
    # A = sqrt(a/b), and the sliding direction turns at a rate within sqrt(b/a) of uniform
    # in the polar angle there -- the compromise between the ellipse's elongation (which
    # wants the scaled plane) and the rotation of the slip (which wants the physical one).
    A = (a / b) ** ANISOTROPY_SPLIT
    sig_x = a / A
    wscale = scale * sig_x / a  # dA = sig_x b dU dV; scale already holds a b tau0
    if w_s != 0.0:
        PU = -dv0 / (w_s * sig_x)
        PV = du0 / (w_s * b)
        P_scaled = math.sqrt((PU / A) ** 2 + PV * PV)  # |pole| in ellipse radii
    else:
        PU = PV = 0.0
        P_scaled = math.inf
    inv_A2 = 1.0 / (A * A)
    if P_scaled < 1.0:
        dpsi = 2.0 * math.pi / n_angle
        c0 = PU * PU * inv_A2 + PV * PV - 1.0
        for j in range(n_angle):
            psi = (j + 0.5) * dpsi
            dx = math.cos(psi)
            dy = math.sin(psi)
            qa = dx * dx * inv_A2 + dy * dy
            qb = PU * dx * inv_A2 + PV * dy
            R = (-qb + math.sqrt(qb * qb - qa * c0)) / qa
            for i in range(n_r):
                v = gl_x[i]
                t = R * v * v * (3.0 - 2.0 * v)
                wgt = wscale * gl_w[i] * 6.0 * R * v * (1.0 - v) * t * dpsi
                nodes[n, 0] = (PU + t * dx) / A
                nodes[n, 1] = PV + t * dy
                nodes[n, 2] = wgt
                n += 1
    elif P_scaled <= far_ratio:
        # cone of directions through the ellipse: edges found in the scaled plane (unit
        # disc, half-angle asin(1/|P|) about -P) and mapped to the working plane
        PX = PU / A
        beta = math.asin(1.0 / P_scaled)
        centre = math.atan2(-PV, -PX)
        e1 = math.atan2(math.sin(centre - beta), A * math.cos(centre - beta))
        e2 = math.atan2(math.sin(centre + beta), A * math.cos(centre + beta))
        half = 0.5 * (e2 - e1)
        if half < 0.0:
            half += math.pi
        mid = e1 + half
        c0 = PU * PU * inv_A2 + PV * PV - 1.0
        # Gauss-Legendre in xi (the cone integrand is smooth but not periodic in xi)
        for j in range(n_angle):
            xi = math.pi * (ga_x[j] - 0.5)
            dxi = math.pi * ga_w[j]
            psi = mid + half * math.sin(xi)
            dpsi_dxi = half * math.cos(xi)
            dx = math.cos(psi)
            dy = math.sin(psi)
            qa = dx * dx * inv_A2 + dy * dy
            qb = PU * dx * inv_A2 + PV * dy
            disc = math.sqrt(max(qb * qb - qa * c0, 0.0)) / qa
            t_mid = -qb / qa
            for i in range(n_r):
                # zeta = pi gl_x[i]: chord parameter clustering nodes at both sqrt ends
                t = t_mid - disc * gl_cos[i]
                wgt = wscale * gl_w[i] * math.pi * disc * gl_sin[i] * t * dpsi_dxi * dxi
                nodes[n, 0] = (PU + t * dx) / A
                nodes[n, 1] = PV + t * dy
                nodes[n, 2] = wgt
                n += 1
    else:
        dth = 2.0 * math.pi / n_angle
        for i in range(n_r):
            u = gl_x[i]
            rho = math.sqrt(1.0 - u * u)
            for j in range(n_angle):
                th = (j + 0.5) * dth
                wgt = scale * gl_w[i] * u * dth
                nodes[n, 0] = rho * math.cos(th)
                nodes[n, 1] = rho * math.sin(th)
                nodes[n, 2] = wgt
                n += 1
    _accumulate(nodes, n, a, b, p_h, inv_tau0_h, du0, dv0, w_s, eta_table, p_step, out)
    return flag


@dataclass(frozen=True)
class FastTraction:
    """Packed tables for `traction_fast`: one per lubricant and operating temperature.

    Build with `FastTraction.build(lubricant)`; call `evaluate(...)` from Python or pass
    the arrays (`args()`) to the njit kernel from other kernels.
    """

    eta_table: np.ndarray
    p_step: float
    gl_x: np.ndarray
    gl_w: np.ndarray
    ga_x: np.ndarray
    ga_w: np.ndarray
    far_ratio: float
    tau0: float

    @classmethod
    def build(cls, lubricant, p_max: float = 5.0e9, n_table: int = 4096,
              n_radial: int = 12, n_angle: int = 48, far_ratio: float = 4.0) -> "FastTraction":
        """Tabulate eta(p) on [0, p_max] Pa and set up the node counts of the rule."""
        p = np.linspace(0.0, p_max, n_table)
        eta = rheology.viscosity_array(p, lubricant.model_code, lubricant.rheology_params())
        xg, wg = np.polynomial.legendre.leggauss(n_radial)
        xa, wa = np.polynomial.legendre.leggauss(n_angle)
        return cls(
            eta_table=np.ascontiguousarray(eta), p_step=float(p[1] - p[0]),
            gl_x=np.ascontiguousarray(0.5 * (xg + 1.0)), gl_w=np.ascontiguousarray(0.5 * wg),
            ga_x=np.ascontiguousarray(0.5 * (xa + 1.0)), ga_w=np.ascontiguousarray(0.5 * wa), far_ratio=float(far_ratio), tau0=float(lubricant.eyring_stress),
        )

    def args(self) -> tuple:
        """Trailing arguments of traction_fast after (a, b, p_h, h, tau0, du0, dv0, w_s), incl. a fresh scratch."""
        nodes = np.empty((self.gl_x.shape[0] * self.ga_x.shape[0], 3))
        return (self.eta_table, self.p_step, self.gl_x, self.gl_w, self.ga_x, self.ga_w, self.far_ratio, nodes)

    def evaluate(self, a, b, p_h, h, du0, dv0, w_s) -> tuple[np.ndarray, np.ndarray, int]:
        """(F = [F_x, F_y, M_z], J[3, 3], flag) on the ball; units as traction_fast."""
        out = np.empty(12)
        flag = traction_fast(a, b, p_h, h, self.tau0, du0, dv0, w_s, *self.args(), out)
        return out[:3].copy(), out[3:].reshape(3, 3).copy(), flag
