"""Quadrature nodes for the fast Eyring traction: rules centred on the spin pole (docs/model.md §6.4).

Why not the ellipse-centred rule of `dynamics.traction.quadrature` with few nodes: with spin the
sliding field s = (du0 - w_s y, dv0 + w_s x) = w_s e_z x (r - r_p) rotates about the spin
pole r_p = (-dv0/w_s, du0/w_s); where the pole lies in or near the ellipse the Eyring stress
turns through 360 deg around it, and a coarse ellipse-centred grid is off by tens of percent.
In polar coordinates centred on the pole the slip direction depends on the ray angle alone
and the integrand is smooth along each ray. Three rules, chosen by |P|, the pole distance
from the centre in ellipse radii:

- inside (|P| < 1): rays psi over [0, 2 pi) (periodic trapezoid in xi, psi = xi -
  (beta/4) sin 4 xi), radius t = R(psi) S(v), S(v) = 3v^2 - 2v^3 (t ~ v^2 at the pole
  makes the area element t dt smooth; R - t ~ (1 - v)^2 makes p ~ sqrt(R - t) smooth);
- cone (1 <= |P| <= far_ratio): the chords through the ellipse, psi = mid + half sin(xi),
  t = t_mid - half_chord cos(zeta), Gauss-Legendre in xi and zeta (both sqrt ends smooth);
- far (|P| > far_ratio, or w_s = 0): the slip field is nearly uniform; the ellipse-centred
  rule (Gauss-Legendre in u = sqrt(1 - rho^2) x uniform angle) of `dynamics.traction.quadrature`.

Rays live in the working plane (U, V) = (x/sqrt(a b), y/b), where the ellipse has semi-axes
(sqrt(a/b), 1): the slip direction (physical plane) and the ray length R (scaled plane) then
have their complex singularities at the same distance atanh(sqrt(a/b)) from the real psi axis,
at psi = 0, pi/2, pi, 3pi/2 -- the map psi(xi) with beta = 0.3 stretches the rule there.
Measured on 240 random points of the reference scene, the trapezoid error falls ~10x per 8
extra rays, the step S(v) ~ 7x per 2 extra radial nodes (the limit is the Eyring knee where
eta(p)|s| ~ tau0 h, a feature of width ~0.06 in u at p_h ~ 2 GPa).

Every rule writes nodes (X, Y) in the scaled plane (X = x/a, Y = y/b; the unit disc) and the
area weight W [m^2] (sum of W = pi a b up to the rule's error). Kernels use no libm
trigonometry per ray (angles of the inside rule are fixed and precomputed; the cone rule
rotates one direction by a Taylor-series sin/cos): a libm call per ray cost more than the rest
of the rule.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from .._speed.compile_policy import VEC

ANGLE_MAP_BETA = 0.3  # strength of the 4-fold angular stretch of the inside rule


@numba.njit(**VEC)
def pole_position(a, b, du0, dv0, w_s):
    """Spin pole in working-plane units (PU, PV) and |P| in ellipse radii; |P| = inf if w_s = 0."""
    if w_s == 0.0:
        return 0.0, 0.0, math.inf
    PX = -dv0 / (w_s * a)  # pole in the scaled plane (X = x/a, Y = y/b)
    PV = du0 / (w_s * b)
    P_scaled = math.sqrt(PX * PX + PV * PV)
    PU = PX * math.sqrt(a / b)
    if not P_scaled < math.inf:  # overflow or NaN from an extreme slip/spin ratio: pole at infinity
        return 0.0, 0.0, math.inf
    return PU, PV, P_scaled


# Packed rule: one contiguous float64 array, a header of counts and offsets, then blocks.
# (A tuple of 13 arrays costs more per call to unbox, and indexing one array at runtime offsets
# does not vectorise; sliced views of the blocks do.)
H_N_RADIAL, H_FAR_RATIO, H_EDGE_IN, H_EDGE_OUT = 0, 1, 2, 3
H_N_IN, H_O_IN, H_N_IN_EDGE, H_O_IN_EDGE, H_O_RADIAL = 4, 5, 6, 7, 8
H_N_CONE, H_O_CONE, H_N_CONE_EDGE, H_O_CONE_EDGE, H_N_FAR, H_O_FAR = 9, 10, 11, 12, 13, 14
H_CENTRE, H_N_IN_CENTRE, H_O_IN_CENTRE = 15, 16, 17
_HEADER = 18


def _gauss01(n: int) -> tuple[np.ndarray, np.ndarray]:
    x, w = np.polynomial.legendre.leggauss(n)
    return 0.5 * (x + 1.0), 0.5 * w


def _ray_angles(n_angle: int) -> list[np.ndarray]:
    """cos psi_j, sin psi_j, dpsi_j of the inside rays: psi = xi - (beta/4) sin 4xi, xi_j = 2 pi (j + 1/2)/n."""
    xi = 2.0 * np.pi * (np.arange(n_angle) + 0.5) / n_angle
    psi = xi - 0.25 * ANGLE_MAP_BETA * np.sin(4.0 * xi)
    dpsi = (1.0 - ANGLE_MAP_BETA * np.cos(4.0 * xi)) * 2.0 * np.pi / n_angle
    return [np.cos(psi), np.sin(psi), dpsi]


def pack_rule(n_radial: int, n_angle: tuple[int, int, int], n_cone: tuple[int, int], n_far: tuple[int, int],
              far_ratio: float, edge: tuple[float, float], centre: float) -> np.ndarray:
    """The three rules' call-independent data as one contiguous float64 array.

    n_angle = (rays when |P| < centre, rays, rays when |P| >= edge[0]) of the inside rule,
    n_cone = (chords, chords when |P| < edge[1]) of the cone rule: the nearer the pole to
    the ellipse edge, the more the ray length varies with the angle (a near-kink at the
    edge), so the more rays it needs. Blocks: ray angles (`_ray_angles`) per count;
    radial S(v_i) = 3v^2 - 2v^3, C_i = w_i S'(v_i) S(v_i) (inside weight per R^2), w_i,
    cos(pi v_i), sin(pi v_i) (cone chords); cone-angle Gauss nodes and weights per count;
    far grid X, Y and weight per unit a b.
    """
    v, v_w = _gauss01(n_radial)
    S = v * v * (3.0 - 2.0 * v)
    radial = [S, v_w * 6.0 * v * (1.0 - v) * S, v_w, np.cos(np.pi * v), np.sin(np.pi * v)]
    u, u_w = _gauss01(n_far[0])
    theta = 2.0 * np.pi * (np.arange(n_far[1]) + 0.5) / n_far[1]
    rho = np.sqrt(1.0 - u * u)
    far = [np.outer(rho, np.cos(theta)).ravel(), np.outer(rho, np.sin(theta)).ravel(),
           np.repeat(u_w * u * 2.0 * np.pi / n_far[1], n_far[1])]
    groups = [_ray_angles(n_angle[1]), _ray_angles(n_angle[2]), radial,
              list(_gauss01(n_cone[0])), list(_gauss01(n_cone[1])), far, _ray_angles(n_angle[0])]
    offsets, o = [], _HEADER
    for g in groups:
        offsets.append(o)
        o += sum(len(b) for b in g)
    header = np.zeros(_HEADER)
    header[[H_N_RADIAL, H_FAR_RATIO, H_EDGE_IN, H_EDGE_OUT]] = n_radial, far_ratio, edge[0], edge[1]
    header[[H_N_IN, H_O_IN, H_N_IN_EDGE, H_O_IN_EDGE, H_O_RADIAL]] = n_angle[1], offsets[0], n_angle[2], offsets[1], offsets[2]
    header[[H_CENTRE, H_N_IN_CENTRE, H_O_IN_CENTRE]] = centre, n_angle[0], offsets[6]
    header[[H_N_CONE, H_O_CONE, H_N_CONE_EDGE, H_O_CONE_EDGE]] = n_cone[0], offsets[3], n_cone[1], offsets[4]
    header[[H_N_FAR, H_O_FAR]] = n_far[0] * n_far[1], offsets[5]
    return np.ascontiguousarray(np.concatenate([header, *(b for g in groups for b in g)]))


def max_nodes(rule: np.ndarray) -> int:
    """Largest node count of the rules of a packed rule (workspace length)."""
    n_r = int(rule[H_N_RADIAL])
    n_ang = max(rule[H_N_IN_CENTRE], rule[H_N_IN], rule[H_N_IN_EDGE], rule[H_N_CONE], rule[H_N_CONE_EDGE])
    return int(max(n_r * n_ang, rule[H_N_FAR]))


@numba.njit(cache=True, inline="always")
def _block(rule, start, length):
    """View of one block of the packed rule (sliced views let LLVM vectorise; offset indexing did not).

    Inlined, not called: as a function of its own it would inherit its callers' compiling without
    reference counting, under which numba returns an argument array itself but no view of it."""
    return rule[start:start + length]


@numba.njit(**VEC)
def nodes_inside(a, b, PU, PV, rule, n_angle, o_angle, X, Y, W, ray):
    """Pole inside the ellipse: n_angle rays x n_radial nodes from the pole; returns the count.

    rule from `pack_rule`, its ray block of n_angle rays at offset o_angle; (PU, PV) from
    `pole_position`; ray: scratch (>= 3, >= n_angle). Node m = i n_angle + j (radial i,
    ray j) so that the inner loop runs over rays and vectorises.
    """
    n_r = int(rule[H_N_RADIAL])
    o_r = int(rule[H_O_RADIAL])
    cos_psi = _block(rule, o_angle, n_angle)
    sin_psi = _block(rule, o_angle + n_angle, n_angle)
    dpsi = _block(rule, o_angle + 2 * n_angle, n_angle)
    S = _block(rule, o_r, n_r)
    C = _block(rule, o_r + n_r, n_r)
    RX, RY, RW = ray[0], ray[1], ray[2]
    inv_A = math.sqrt(b / a)
    inv_A2 = inv_A * inv_A
    wscale = math.sqrt(a * b) * b  # dA = sqrt(a b) b dU dV
    c0 = PU * PU * inv_A2 + PV * PV - 1.0
    for j in range(n_angle):
        dx = cos_psi[j]
        dy = sin_psi[j]
        qa = dx * dx * inv_A2 + dy * dy
        qb = PU * dx * inv_A2 + PV * dy
        R = (-qb + math.sqrt(max(qb * qb - qa * c0, 0.0))) / qa  # ray length to the ellipse
        RX[j] = R * dx * inv_A
        RY[j] = R * dy
        RW[j] = wscale * R * R * dpsi[j]
    X0 = PU * inv_A
    # one output array per loop nest, indexed flat: LLVM vectorises each with one store stream
    # (one loop writing X, Y and W through row slices was slower; docs/performance.md)
    for i in range(n_r):
        o = i * n_angle
        Si = S[i]
        for j in range(n_angle):
            X[o + j] = X0 + RX[j] * Si
    for i in range(n_r):
        o = i * n_angle
        Si = S[i]
        for j in range(n_angle):
            Y[o + j] = PV + RY[j] * Si
    for i in range(n_r):
        o = i * n_angle
        Ci = C[i]
        for j in range(n_angle):
            W[o + j] = RW[j] * Ci
    return n_r * n_angle


@numba.njit(cache=True, inline="always")
def _cos_sin_small(phi):
    """(cos phi, sin phi) for |phi| <= pi/2 by Taylor series (error < 3e-12); no libm call."""
    p2 = phi * phi
    c = 1.0 + p2 * (-1.0 / 2 + p2 * (1.0 / 24 + p2 * (-1.0 / 720 + p2 * (1.0 / 40320 + p2 * (
        -1.0 / 3628800 + p2 * (1.0 / 479001600 + p2 * (-1.0 / 87178291200 + p2 / 20922789888000)))))))
    s = phi * (1.0 + p2 * (-1.0 / 6 + p2 * (1.0 / 120 + p2 * (-1.0 / 5040 + p2 * (1.0 / 362880 + p2 * (
        -1.0 / 39916800 + p2 * (1.0 / 6227020800 + p2 * (-1.0 / 1307674368000 + p2 / 355687428096000))))))))
    return c, s


@numba.njit(**VEC)
def _cone_edges(A, PU, PV, P_scaled):
    """(cos mid, sin mid, half): central direction and half-angle [rad] of the cone of rays
    from the pole that cross the ellipse, in the working plane.

    In the scaled plane (the unit disc) the two tangents from P make the angle
    beta = asin(1/|P|) with -P; each edge's direction (c, s) there is (A c, s) in the working
    plane, normalised. mid lies half-way from the first edge to the second, counter-clockwise:
    perpendicular to their difference, which stays well conditioned when the edges are almost
    opposite (|P| -> 1). Rotations instead of angles: one libm call (atan2) where angles took
    six (asin, three atan2, cos, sin)."""
    inv_P = 1.0 / P_scaled
    sb = min(inv_P, 1.0)
    cb = math.sqrt(max(1.0 - sb * sb, 0.0))
    ux = -PU / A * inv_P  # -P/|P| in the scaled plane
    uy = -PV * inv_P
    d1x, d1y = A * (ux * cb + uy * sb), uy * cb - ux * sb  # -P turned by -beta, mapped
    d2x, d2y = A * (ux * cb - uy * sb), uy * cb + ux * sb  # and by +beta
    n1 = 1.0 / math.sqrt(d1x * d1x + d1y * d1y)
    n2 = 1.0 / math.sqrt(d2x * d2x + d2y * d2y)
    d1x, d1y, d2x, d2y = d1x * n1, d1y * n1, d2x * n2, d2y * n2
    dx, dy = d2x - d1x, d2y - d1y  # 2 sin(half) (-sin mid, cos mid)
    sx, sy = d2x + d1x, d2y + d1y  # 2 cos(half) (cos mid, sin mid)
    chord = math.sqrt(dx * dx + dy * dy)
    half = math.atan2(chord, math.sqrt(sx * sx + sy * sy))
    return dy / chord, -dx / chord, half


@numba.njit(**VEC)
def nodes_cone(a, b, PU, PV, P_scaled, rule, n_cone, o_cone, X, Y, W, ray):
    """Pole outside: the cone of chords through the ellipse; returns the node count.

    Radial: zeta = pi v (Gauss v on [0, 1]), t = t_mid - chord cos(zeta); angular:
    Gauss-Legendre in xi (n_cone nodes, block at o_cone), psi = mid + half sin(xi). rule from
    `pack_rule`; ray: scratch (>= 5, >= n_cone). One libm call per contact (atan2), none per
    ray. Node m = i n_cone + j.
    """
    n_r = int(rule[H_N_RADIAL])
    o = int(rule[H_O_RADIAL]) + 2 * n_r
    v_w = _block(rule, o, n_r)
    z_cos = _block(rule, o + n_r, n_r)
    z_sin = _block(rule, o + 2 * n_r, n_r)
    g = _block(rule, o_cone, n_cone)
    g_w = _block(rule, o_cone + n_cone, n_cone)
    A = math.sqrt(a / b)
    inv_A = 1.0 / A
    inv_A2 = inv_A * inv_A
    wscale = math.sqrt(a * b) * b
    cos_mid, sin_mid, half = _cone_edges(A, PU, PV, P_scaled)
    c0 = PU * PU * inv_A2 + PV * PV - 1.0
    DX, DY, CH, TM, DW = ray[0], ray[1], ray[2], ray[3], ray[4]
    for j in range(n_cone):
        xi = math.pi * (g[j] - 0.5)
        cos_xi, sin_xi = _cos_sin_small(xi)
        cphi, sphi = _cos_sin_small(half * sin_xi)  # psi = mid + phi, |phi| < pi/2
        dx = cos_mid * cphi - sin_mid * sphi
        dy = sin_mid * cphi + cos_mid * sphi
        qa = dx * dx * inv_A2 + dy * dy
        qb = PU * dx * inv_A2 + PV * dy
        chord = math.sqrt(max(qb * qb - qa * c0, 0.0)) / qa
        DX[j] = dx
        DY[j] = dy
        CH[j] = chord
        TM[j] = -qb / qa
        DW[j] = wscale * math.pi * chord * half * cos_xi * math.pi * g_w[j]
    for i in range(n_r):
        zc = z_cos[i]
        wz = v_w[i] * z_sin[i]
        Xi = X[i * n_cone:(i + 1) * n_cone]
        Yi = Y[i * n_cone:(i + 1) * n_cone]
        Wi = W[i * n_cone:(i + 1) * n_cone]
        for j in range(n_cone):
            t = TM[j] - CH[j] * zc
            Xi[j] = (PU + t * DX[j]) * inv_A
            Yi[j] = PV + t * DY[j]
            Wi[j] = DW[j] * wz * t
    return n_r * n_cone


@numba.njit(**VEC)
def nodes_far(a, b, rule, X, Y, W):
    """Pole far away: the fixed ellipse-centred grid of the packed rule; returns the count."""
    n_far = int(rule[H_N_FAR])
    o = int(rule[H_O_FAR])
    far_X = _block(rule, o, n_far)
    far_Y = _block(rule, o + n_far, n_far)
    far_W = _block(rule, o + 2 * n_far, n_far)
    ab = a * b
    for m in range(n_far):
        X[m] = far_X[m]
        Y[m] = far_Y[m]
        W[m] = ab * far_W[m]
    return n_far


@numba.njit(**VEC)
def place_nodes(a, b, du0, dv0, w_s, rule, X, Y, W, ray):
    """Fill X, Y, W with the rule the spin-pole position calls for; returns the node count.

    ray: scratch (>= 5 rows, >= max(n_angle, n_cone) columns).
    """
    PU, PV, P_scaled = pole_position(a, b, du0, dv0, w_s)
    if P_scaled < 1.0:
        h = H_N_IN_CENTRE if P_scaled < rule[H_CENTRE] else (H_N_IN if P_scaled < rule[H_EDGE_IN] else H_N_IN_EDGE)
        return nodes_inside(a, b, PU, PV, rule, int(rule[h]), int(rule[h + 1]), X, Y, W, ray)
    if P_scaled <= rule[H_FAR_RATIO]:
        h = H_N_CONE_EDGE if P_scaled < rule[H_EDGE_OUT] else H_N_CONE
        return nodes_cone(a, b, PU, PV, P_scaled, rule, int(rule[h]), int(rule[h + 1]), X, Y, W, ray)
    return nodes_far(a, b, rule, X, Y, W)
