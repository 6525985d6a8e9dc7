"""Fast traction for the time loop: pole-centred quadrature, SIMD evaluation (docs/model.md §6.4).

The engine: it places the nodes, reads the viscosity table, sums the nodes' stresses and knows
about vector widths and precision; the law comes from `dynamics.traction.laws`, as the bundle
`TractionRule.law`, and numba compiles the engine for the law of that bundle's class. The Eyring
law, the default, has passes of its own (below) that call the law's node functions
(`laws.eyring.argument`, `stress_factor`, `stress_slope`) in float64 or float32; every other
film law runs through one float64 pass of its response (`laws.operations.response`) per node
(`_law_response`). Every law's node values then pass through the film's inlet elasticity
(`traction.inlet`, `_inlet_elasticity`) when the rule has a finite shear modulus and the contact a
mean speed u > 0.

Same physics and sign convention as `dynamics.traction.quadrature` (force and spin moment ON THE BALL,
Jacobian d(F_x, F_y, M_z)/d(du0, dv0, w_s)); the nodes come from `dynamics.traction.nodes`
(rules centred on the spin pole, 200-320 nodes). What makes it fast is how the nodes are
evaluated: in short passes over contiguous scratch arrays that LLVM vectorises (numba
`fastmath`, `error_model="numpy"` so that `/` carries no zero-division branch), with
asinh(x) = log(x + sqrt(1 + x^2)) and a branch-free log of our own (`_speed.simd_math`)
because numba's `math.log` is a scalar libm call that blocks vectorisation. The viscosity table
lookup is a gather that LLVM leaves scalar; the float32 passes split the table position into
row and fraction in the slip pass, pick the rows in a pass of loads (`_speed.table_lookup`)
and interpolate in the Eyring pass. g = asinh(x)/|s| has a float32 pass of its own, so the
float64 sums only multiply and add.

Square roots and divisions share one unit that neither wider vectors nor fast-math speed up;
they set the cost. Where their rounding is harmless they run in float32, which that unit
serves about three times faster. A rule built with `float32_residual` (what the time loop
uses) evaluates residual-only calls (`jacobian=False`, the loop's common call) with every
node value in float32 -- pressure index, sliding speed, viscosity (a float32 copy of the
table), Eyring argument, z = x + sqrt(1 + x^2) and its log -- and only the nodes' positions,
weights and the sums in float64. The force moves by less than 1e-6 of tau0 times the contact
area from the float64 path, far inside the quadrature's 2 %. One width throughout matters:
passes that convert between float64 and float32 vectorise half as wide. The Jacobian stays
float64 (its x/sqrt(1 + x^2) - asinh x cancels to -x^3/3 for small x), and so does every call
of a default rule: a force with rounding steps of 1e-7 is no input for finite differences
(scipy's solve_ivp, finite-difference tangents and their tests). docs/performance.md gives
the cost of both paths.

Viscosity comes from a table of eta on a uniform pressure grid (linear interpolation;
relative error ~1e-4 with 4096 points to 5 GPa), built once per lubricant and temperature
by `FastTraction.build`. Flags (bits, OR-ed): FLAG_PRESSURE_CLAMPED when p_h is above the
table (eta is held at its last value), FLAG_NO_CONTACT when a, b, p_h or h <= 0 (zero force),
FLAG_UNVALIDATED when the input lies outside the range where the 2 % accuracy was checked
(a/b or p_h outside VALIDATED_*; the result is still finite), FLAG_SLIP_CLAMPED when a
slip speed exceeds SLIP_MAX (clamped there). No input gives NaN.

Accuracy against the (128, 1024) quadrature of `dynamics.traction.quadrature`, default rule, two samples
of 240 random operating points of the reference scene (tests/test_traction_fast.py, -m slow):
|dF|/|F| <= 0.74 %, |dM_z|/max(|M_z|, |F| b) <= 0.76 %, max|dJ|/max|J| <= 1.4 %; edge cases
(slip 1e-5 and 0.3, pure spin, pure roll, 20 N, pole at 0.97 / 1.03 ellipse radii) <= 0.7 %.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any, NamedTuple

import numba
import numpy as np
from numba.extending import overload

from ..lubrication import rheology
from . import inlet
from .laws import LAWS, eyring, operations
from .._speed.aligned import CACHE_LINE, empty_aligned
from .._speed.compile_policy import KERNEL, NO_REFCOUNT, VEC, VEC_UNFUSED
from .._speed.simd_math import exp_array, log_array, log_array32
from .._speed.table_lookup import last_position32, lerp_picked32, pick_rows, split_position32
from .nodes import max_nodes, pack_rule, place_nodes

FLAG_OK = 0
FLAG_PRESSURE_CLAMPED = 1
FLAG_NO_CONTACT = 2
FLAG_UNVALIDATED = 4
FLAG_SLIP_CLAMPED = 8
SLIP_MAX = 1.0e4  # m/s: |du0|, |dv0|, |w_s| b beyond this are clamped (their squares must not overflow)
VALIDATED_ASPECT = (0.05, 0.25)  # a/b (a along entrainment) checked in tests
VALIDATED_P_H = (2.0e8, 3.0e9)  # Pa, maximum Hertz pressure checked in tests

_WORK_ROWS = 10
_WORK32_ROWS = 6  # the residual-only passes' float32 rows: f_index (then log exponents), r, k, x, z, asinh x


class TractionRule(NamedTuple):
    """What `traction_fast` needs besides the contact: one per lubricant and temperature
    (`FastTraction.traction_rule`), with a scratch workspace for one thread."""

    eta_table: np.ndarray  # (n, 2): eta [Pa.s] at p = i p_step, and eta_(i+1) - eta_i
    p_step: float          # [Pa]
    rule: np.ndarray       # packed quadrature rule, `traction_nodes.pack_rule`
    work: np.ndarray       # (9, n_max) float64 scratch
    iwork: np.ndarray      # (n_max,) int64 scratch
    work32: np.ndarray     # (_WORK32_ROWS, n_max) float32 scratch of the residual-only passes
    iwork32: np.ndarray    # (n_max,) int32 scratch of the residual-only passes
    eta_flat32: np.ndarray  # eta_table in float32, flattened (the residual-only passes' table)
    float32_residual: bool  # residual-only calls through the float32 passes (module docstring)
    law: Any                # the law's parameter bundle (`traction.laws`: its module's `Params`)
    shear_modulus: float    # the film's elastic shear modulus G [Pa] (`inlet_elasticity`); inf: viscous

    def with_float32_residual(self, on: bool = True) -> "TractionRule":
        """A copy whose residual-only calls take the float32 passes (`on`) or not."""
        return self._replace(float32_residual=bool(on))


def dry_traction_rule(law) -> TractionRule:
    """The rule of a law without film (`law`: its bundle): no table, no nodes, no scratch."""
    return TractionRule(np.zeros((2, 2)), 0.0, np.zeros(1), np.zeros((1, 1)), np.zeros(1, dtype=np.int64),
                        np.zeros((_WORK32_ROWS, 1), dtype=np.float32), np.zeros(1, dtype=np.int32),
                        np.zeros(4, dtype=np.float32), False, law, math.inf)


class _Nodes(NamedTuple):
    """Quadrature nodes in the scaled plane (X = x/a, Y = y/b) and area weights W [m^2]."""

    X: np.ndarray
    Y: np.ndarray
    W: np.ndarray


class _Contact(NamedTuple):
    """One contact as `traction_fast` takes it (units there)."""

    a: float
    b: float
    p_h: float
    h: float
    du0: float
    dv0: float
    w_s: float
    u: float  # mean surface speed along the entrainment [m/s] (0: not known, the film taken as viscous)


class _Slip(NamedTuple):
    """The sliding of the contact centre, (du0, dv0) [m/s] along and across the entrainment,
    and the spin w_s [rad/s] about the contact normal: the sliding speed of a node at (x, y)
    is (du0 - w_s y, dv0 + w_s x)."""

    du0: float
    dv0: float
    w_s: float


class _NodeValues(NamedTuple):
    """Per node: eta/(tau0 h) k [s/m], |s| r [m/s], Eyring argument x, z = x + sqrt(1 + x^2),
    asinh x = ln z (ash)."""

    k: np.ndarray
    r: np.ndarray
    x: np.ndarray
    z: np.ndarray
    ash: np.ndarray


@numba.njit(**VEC_UNFUSED)
def _slip_and_table_index(X, Y, n, a, b, p_h, du0, dv0, w_s, inv_p_step, f_index, r):
    """Per node: fractional index of p = p_h sqrt(1 - X^2 - Y^2) in the eta table, |s| [m/s].
    Without fused multiply-adds (`compile_policy.VEC_UNFUSED`), so that a run that compiled this
    pass and one that loaded it from the cache run the same bits (docs/model.md §9)."""
    for m in range(n):
        q = 1.0 - X[m] * X[m] - Y[m] * Y[m]
        f_index[m] = p_h * math.sqrt(max(q, 0.0)) * inv_p_step
        sx = du0 - w_s * b * Y[m]
        sy = dv0 + w_s * a * X[m]
        r[m] = math.sqrt(sx * sx + sy * sy)


@numba.njit(cache=True, inline="always")
def _node_index_and_speed32(Xm, Ym, scale, a32, b32, du32, dv32, ws32):
    """A node's table position p/p_step = scale sqrt(1 - X^2 - Y^2) and sliding speed |s|, in
    float32 (the float32 passes' shared node arithmetic; scale and the rest already float32)."""
    # 1 - X^2 - Y^2 cancels at the ellipse edge: formed in float64 (in float32 the index
    # moved there by up to 2e-3 of a table step)
    f = scale * math.sqrt(max(np.float32(1.0 - Xm * Xm - Ym * Ym), np.float32(0.0)))
    x = np.float32(Xm)
    y = np.float32(Ym)
    sx = du32 - ws32 * b32 * y
    sy = dv32 + ws32 * a32 * x
    return f, math.sqrt(sx * sx + sy * sy)


@numba.njit(**VEC)
def _viscosity_lookup(f_index, n, eta_table, inv_tau0_h, k):
    """k[m] = eta(p)/(tau0 h) [s/m] by linear interpolation (scalar: gathers do not vectorise).

    eta_table rows are (eta_i, eta_(i+1) - eta_i): one row is one 16-byte load rather than two
    reads from a plain table. The table is read as one flat array with an unsigned index
    (f >= 0): a signed index makes numba wrap negative values, a compare and add per node.
    """
    last = eta_table.shape[0] - 1.000001
    flat = eta_table.reshape(eta_table.size)  # a view: row i is flat[2i], flat[2i + 1]
    one = np.uint64(1)
    for m in range(n):
        f = min(f_index[m], last)
        i = np.uint64(f)
        j = i + i
        k[m] = (flat[j] + (f - float(i)) * flat[j + one]) * inv_tau0_h


@numba.njit(**VEC)
def _eyring_argument(k, r, n, x, z):
    """x = `eyring.argument(k, |s|)` and z = x + sqrt(1 + x^2) >= 1, so asinh x = ln z."""
    for m in range(n):
        xm = eyring.argument(k[m], r[m])
        x[m] = xm
        z[m] = xm + math.sqrt(1.0 + xm * xm)


@numba.njit(cache=True, inline="always")
def _eyring_node32(km, rm):
    """A node's Eyring argument x = `eyring.argument(k, |s|)` and z = x + sqrt(1 + x^2)
    (asinh x = ln z), in float32 (k, r float32; asinh x = ln z then to ~1e-7 absolute). Not for
    the Jacobian, whose (x/sqrt(1 + x^2) - asinh x) cancels to x^3/3 for small x."""
    xm = eyring.argument(km, rm)
    return xm, xm + math.sqrt(np.float32(1.0) + xm * xm)


@numba.njit(cache=True, inline="always")
def _node_slip(X, Y, m, a, b, du0, dv0, w_s):
    """Node m's position (x, y) [m] and sliding velocity (s_x, s_y) = (du0 - w_s y, dv0 + w_s x)."""
    xp = a * X[m]
    yp = b * Y[m]
    return xp, yp, du0 - w_s * yp, dv0 + w_s * xp


@numba.njit(cache=True, inline="always")
def _node_force(X, Y, W, m, g, a, b, du0, dv0, w_s):
    """Node m's share of (F_x, F_y, M_z) with the sign left to the sum: W g s and its moment
    (tau0 = 1; tau = g s, g = asinh(x)/|s|)."""
    xp, yp, sx, sy = _node_slip(X, Y, m, a, b, du0, dv0, w_s)
    wgt = W[m] * g
    return wgt * sx, wgt * sy, wgt * (xp * sy - yp * sx)


@numba.njit(cache=True, inline="always")
def _store_force(out, Fx, Fy, Mz):
    """out[0:3] = (F_x, F_y, M_z), out[3:12] = 0 (a residual-only evaluation has no Jacobian)."""
    out[0] = Fx
    out[1] = Fy
    out[2] = Mz
    for m in range(3, 12):
        out[m] = 0.0


@numba.njit(**VEC)
def _slip_and_table_row32(nodes, n, a, b, p_h, slip, inv_p_step, last, row, frac, r):
    """`_slip_and_table_index` in float32 (nodes: `_Nodes`, slip: `_Slip`), with the table
    position f = min(index, last) split at once into its row i = floor f (uint32) and the
    fraction f - i (float32) (`table_lookup.split_position32`); r float32. Done here, in a
    pass that vectorises, the split leaves the lookup only its loads (`table_lookup.pick_rows`).
    A float32 root costs about a third of a float64 one on the divider, and a pass in one width
    vectorises twice as wide as one that converts. Rounding: 6e-8 of p and of the terms of s (|du0| + |w_s| b), so near the
    spin pole, where they cancel, |s| is good to ~1e-7 (|du0| + |dv0| + |w_s| b) rather than
    relatively; the force still moves by < 1e-6 of tau0 pi a b (tests/test_traction_fast.py)."""
    X, Y = nodes.X, nodes.Y
    scale = np.float32(p_h * inv_p_step)
    a32, b32 = np.float32(a), np.float32(b)
    du32, dv32, ws32 = np.float32(slip.du0), np.float32(slip.dv0), np.float32(slip.w_s)
    for m in range(n):
        f, r[m] = _node_index_and_speed32(X[m], Y[m], scale, a32, b32, du32, dv32, ws32)
        row[m], frac[m] = split_position32(f, last)


@numba.njit(**VEC)
def _lerp_eyring_argument32(picked, frac, r, n, inv_tau0_h, k, x, z):
    """k = fma(f - i, eta_(i+1) - eta_i, eta_i) / (tau0 h) from the picked rows
    (`table_lookup.lerp_picked32`), then the Eyring argument x = k |s| and z
    (`_eyring_node32`), in one pass."""
    pair = picked.view(np.float32)  # (eta_i, eta_(i+1) - eta_i) per node
    scale = np.float32(inv_tau0_h)
    for m in range(n):
        km = lerp_picked32(pair, m, frac[m], scale)
        k[m] = km
        x[m], z[m] = _eyring_node32(km, r[m])


@numba.njit(**VEC)
def _stress_factor32(k, r, x, ash, n, g):
    """g = `eyring.stress_factor` per node in float32 (tau/tau0 = g s): the float32 part of
    the float64 path's `_eyring_response`, in a pass of its own, so that the sums' float64 loop carries no
    division, selection or conversions of four arrays."""
    for m in range(n):
        g[m] = eyring.stress_factor(k[m], r[m], x[m], ash[m])


@numba.njit(**VEC)
def _accumulate_force_g(nodes, g, n, a, b, du0, dv0, w_s, out):
    """The force from g per node (`_eyring_response`, `_stress_factor32`): out[0:3] = (F_x, F_y,
    M_z) (tau0 = 1), out[3:12] = 0 (a residual-only call needs no d tau/d s); the sums of
    `_accumulate_response` in the same order."""
    X, Y, W = nodes.X, nodes.Y, nodes.W
    Fx = Fy = Mz = 0.0
    for m in range(n):
        fx, fy, mz = _node_force(X, Y, W, m, g[m], a, b, du0, dv0, w_s)
        Fx -= fx
        Fy -= fy
        Mz -= mz
    _store_force(out, Fx, Fy, Mz)


@numba.njit(**VEC)
def _eyring_response(values, n, jacobian, g, c):
    """(g, c) of the Eyring law at every node from its values (`_NodeValues`): g =
    `eyring.stress_factor`, and c = `eyring.stress_slope` when jacobian (tau0 = 1; tau = g s,
    d tau/d s = g I + c s s^T)."""
    k, r, x, z, ash = values.k, values.r, values.x, values.z, values.ash
    for m in range(n):
        g[m] = eyring.stress_factor(k[m], r[m], x[m], ash[m])
    if jacobian:
        for m in range(n):
            c[m] = eyring.stress_slope(k[m], r[m], x[m], z[m] - x[m], ash[m])


@numba.njit(**VEC)
def _law_response(law, k, r, n, g, c):
    """(g, c) of film law `law` (its bundle) at every node (`laws.operations.response`):
    tau = g s, d tau/d s = g I + c s s^T."""
    for m in range(n):
        g[m], c[m] = operations.response(law, k[m], r[m])


@numba.njit(**VEC)
def _accumulate_response(nodes, g, c, n, a, b, du0, dv0, w_s, out):
    """Sum tau = g s over the nodes into out[0:3] and its Jacobian, from d tau/d s = g I + c s s^T,
    into out[3:12] (stress scale 1), for any film law."""
    X, Y, W = nodes.X, nodes.Y, nodes.W
    Fx = Fy = Mz = 0.0
    j00 = j01 = j02 = j11 = j12 = j20 = j21 = j22 = 0.0
    for m in range(n):
        xp, yp, sx, sy = _node_slip(X, Y, m, a, b, du0, dv0, w_s)
        gm, cm, wgt = g[m], c[m], W[m]
        tx, ty = gm * sx, gm * sy
        axx, axy, ayy = gm + cm * sx * sx, cm * sx * sy, gm + cm * sy * sy
        dtx_dw = -axx * yp + axy * xp
        dty_dw = -axy * yp + ayy * xp
        Fx -= wgt * tx
        Fy -= wgt * ty
        Mz -= wgt * (xp * ty - yp * tx)
        j00 -= wgt * axx
        j01 -= wgt * axy
        j02 -= wgt * dtx_dw
        j11 -= wgt * ayy
        j12 -= wgt * dty_dw
        j20 -= wgt * (xp * axy - yp * axx)
        j21 -= wgt * (xp * ayy - yp * axy)
        j22 -= wgt * (xp * dty_dw - yp * dtx_dw)
    out[0], out[1], out[2] = Fx, Fy, Mz
    out[3], out[4], out[5] = j00, j01, j02
    out[6], out[7], out[8] = j01, j11, j12
    out[9], out[10], out[11] = j20, j21, j22


@numba.njit(**NO_REFCOUNT)
def _inlet_elasticity(tr, nodes, n, contact, stress, jacobian, g, c, rows):
    """The film's inlet elasticity on the nodes' (g, c) in place (`traction.inlet`), when it acts
    (a finite shear modulus and a mean speed u > 0); stress: the law's stress scale [Pa]; rows:
    three free float64 scratch rows (-y, e^-y, exp's mantissa); tr.iwork must be free."""
    scale = inlet.inlet_scale(tr.shear_modulus, contact.a, contact.u, stress, contact.h)
    if scale < math.inf:
        minus_y, e, mantissa = rows
        inlet.exponents(nodes.X, nodes.Y, g, n, scale, minus_y)
        exp_array(minus_y, n, mantissa, tr.iwork, e)
        inlet.apply(minus_y, e, n, jacobian, g, c)


@numba.njit(**NO_REFCOUNT)
def traction_fast(a, b, p_h, h, du0, dv0, w_s, u, tr, out, jacobian=True):
    """Film traction on the ball by pole-centred quadrature (docs/model.md §6.4, M.72–M.74).

    a, b [m] Hertz semi-axes (x = entrainment), p_h [Pa], h [m] central film, du0, dv0 [m/s]
    sliding velocity ball - race at the centre, w_s [rad/s] spin (ball - race, along the
    normal), u [m/s] the mean surface speed along the entrainment (the film's transit, for its
    inlet elasticity, `traction.inlet`; 0: the viscous law alone); tr: the `TractionRule`
    (viscosity table, the law's bundle, the film's shear modulus, quadrature rule, scratch). Writes out[0:3] = (F_x [N], F_y [N], M_z [N.m]) and out[3:12] =
    d(F_x, F_y, M_z)/d(du0, dv0, w_s) row-major (zeros when jacobian is False: a
    residual-only evaluation, ~20 % cheaper); returns the flag bits (FLAG_*).
    """
    for m in range(12):
        out[m] = 0.0
    if not (a > 0.0 and b > 0.0 and p_h > 0.0 and h > 0.0):
        return FLAG_NO_CONTACT
    flag = FLAG_OK
    if p_h > tr.p_step * (tr.eta_table.shape[0] - 1):
        flag |= FLAG_PRESSURE_CLAMPED
    aspect = a / b
    if not (VALIDATED_ASPECT[0] <= aspect <= VALIDATED_ASPECT[1] and VALIDATED_P_H[0] <= p_h <= VALIDATED_P_H[1]):
        flag |= FLAG_UNVALIDATED
    if max(abs(du0), abs(dv0), abs(w_s) * b) > SLIP_MAX:
        flag |= FLAG_SLIP_CLAMPED
        du0 = min(max(du0, -SLIP_MAX), SLIP_MAX)
        dv0 = min(max(dv0, -SLIP_MAX), SLIP_MAX)
        w_s = min(max(w_s, -SLIP_MAX / b), SLIP_MAX / b)
    # scratch rows: X, Y, W; then 3..7 are place_nodes' own until it returns, and become
    # f_index (table position), r, k, x, z; 8 is asinh x
    work = tr.work
    nodes = _Nodes(work[0], work[1], work[2])
    n = place_nodes(a, b, du0, dv0, w_s, tr.rule, nodes.X, nodes.Y, nodes.W, work[3:8])
    _film_passes(tr.law, tr, nodes, n, _Contact(a, b, p_h, h, du0, dv0, w_s, u), out, jacobian)
    return flag


def _film_passes(law, tr, nodes, n, contact, out, jacobian):
    """The node passes of the law of bundle `law` (numba: `_eyring_passes` for the Eyring law,
    `_general_passes` for any other film law)."""


@overload(_film_passes, jit_options=NO_REFCOUNT, inline="always")
def _film_passes_of(law, tr, nodes, n, contact, out, jacobian):
    passes = _eyring_passes if law.instance_class is eyring.Eyring else _general_passes
    return lambda law, tr, nodes, n, contact, out, jacobian: passes(tr, nodes, n, contact, out, jacobian)


@numba.njit(**NO_REFCOUNT)
def _general_passes(tr, nodes, n, contact, out, jacobian):
    """Any film law: one float64 pass of its response (`operations.response`) per node."""
    a, b, p_h, h, du0, dv0, w_s, _ = contact  # u: read by `_inlet_elasticity`
    stress = operations.stress_scale(tr.law, p_h)
    work = tr.work
    f_index, r, k, g, c = work[3], work[4], work[5], work[6], work[7]
    _slip_and_table_index(nodes.X, nodes.Y, n, a, b, p_h, du0, dv0, w_s, 1.0 / tr.p_step, f_index, r)
    _viscosity_lookup(f_index, n, tr.eta_table, 1.0 / (stress * h), k)
    _law_response(tr.law, k, r, n, g, c)
    _inlet_elasticity(tr, nodes, n, contact, stress, True, g, c, (work[3], work[4], work[5]))
    _accumulate_response(nodes, g, c, n, a, b, du0, dv0, w_s, out)
    for m in range(12):
        out[m] = out[m] * stress if (jacobian or m < 3) else 0.0


@numba.njit(**NO_REFCOUNT)
def _eyring_passes(tr, nodes, n, contact, out, jacobian):
    """The Eyring law's passes: float32 node values for a residual-only call of a rule with
    `float32_residual` (module docstring), float64 otherwise."""
    a, b, p_h, h, du0, dv0, w_s, _ = contact  # u: read by `_inlet_elasticity`
    tau0 = eyring.stress_scale(tr.law, p_h)
    if tr.float32_residual and not jacobian:  # the node values in float32 (module docstring)
        w32 = tr.work32
        values32 = _NodeValues(k=w32[2], r=w32[1], x=w32[3], z=w32[4], ash=w32[5])
        # row and fraction at once, the rows picked in a pass of their own (`_speed.table_lookup`)
        row = tr.iwork32.view(np.uint32)
        _slip_and_table_row32(nodes, n, a, b, p_h, _Slip(du0, dv0, w_s), 1.0 / tr.p_step,
                              last_position32(tr.eta_flat32), row, w32[0], values32.r)
        picked = tr.iwork  # the float64 path's int64 scratch, free here
        pick_rows(row, n, tr.eta_flat32.view(np.int64), picked)
        _lerp_eyring_argument32(picked, w32[0], values32.r, n, 1.0 / (tau0 * h), values32.k, values32.x,
                                values32.z)
        log_array32(values32.z, n, w32[0], tr.iwork32, values32.ash)  # row 0 is spent: the exponents
        _stress_factor32(values32.k, values32.r, values32.x, values32.ash, n, w32[0])  # and now g
        work = tr.work  # its rows past the nodes are free here
        _inlet_elasticity(tr, nodes, n, contact, tau0, False, w32[0], w32[0], (work[3], work[4], work[5]))
        _accumulate_force_g(nodes, w32[0], n, a, b, du0, dv0, w_s, out)
        for m in range(3):
            out[m] *= tau0
        return
    work = tr.work
    f_index = work[3]
    values = _NodeValues(k=work[5], r=work[4], x=work[6], z=work[7], ash=work[8])
    _slip_and_table_index(nodes.X, nodes.Y, n, a, b, p_h, du0, dv0, w_s, 1.0 / tr.p_step, f_index, values.r)
    _viscosity_lookup(f_index, n, tr.eta_table, 1.0 / (tau0 * h), values.k)
    _eyring_argument(values.k, values.r, n, values.x, values.z)
    log_array(values.z, n, f_index, tr.iwork, values.ash)  # f_index is spent: reuse it for the exponents
    g, c = work[3], work[9]  # f_index spent again: g
    _eyring_response(values, n, jacobian, g, c)
    _inlet_elasticity(tr, nodes, n, contact, tau0, jacobian, g, c, (work[4], work[5], work[6]))  # r, k, x spent
    if jacobian:
        _accumulate_response(nodes, g, c, n, a, b, du0, dv0, w_s, out)
    else:
        _accumulate_force_g(nodes, g, n, a, b, du0, dv0, w_s, out)
    for m in range(12):
        out[m] *= tau0


@numba.njit(**KERNEL)
def traction_fast_batch(a, b, p_h, h, du0, dv0, w_s, u, tr, F, J, flags):
    """traction_fast over n contacts: inputs (n,) arrays (units as traction_fast), one rule.

    Writes F[i] = (F_x, F_y, M_z) [N, N, N.m], J[i] = d(F_x, F_y, M_z)/d(du0, dv0, w_s)
    (3 x 3) and flags[i].
    """
    out = np.empty(12)
    for i in range(a.shape[0]):
        flags[i] = traction_fast(a[i], b[i], p_h[i], h[i], du0[i], dv0[i], w_s[i], u[i], tr, out)
        for c in range(3):
            F[i, c] = out[c]
            for d in range(3):
                J[i, c, d] = out[3 + 3 * c + d]


@dataclass(frozen=True)
class FastTraction:
    """Viscosity table and quadrature rule for `traction_fast`: one per lubricant and temperature.

    Build with `FastTraction.build(lubricant)`. From Python call `evaluate(...)` (one contact)
    or `evaluate_batch(...)` (arrays of contacts); kernels take `traction_rule()`, the
    `TractionRule` bundle with a fresh workspace.
    """

    eta_table: np.ndarray  # (n, 2): eta [Pa.s] at p = i p_step, and eta_(i+1) - eta_i (0 in the last row)
    p_step: float  # [Pa]
    rule: np.ndarray  # packed quadrature rule, `traction_nodes.pack_rule`
    law: Any  # the film law's bundle (`traction.laws`); the lubricant's Eyring law unless `with_law`
    shear_modulus: float = math.inf  # the film's elastic shear modulus G [Pa] (`traction.inlet`)

    def with_law(self, law) -> "FastTraction":
        """The same table and rule for another film law, given by its bundle (`LAWS.pack`)."""
        entry = LAWS.law_of(type(law))
        if not entry.film:
            raise ValueError(f"traction law {entry.name!r} has no film: choose one of {', '.join(LAWS.film_laws())}")
        return replace(self, law=law)

    @classmethod
    def build(cls, lubricant, p_max: float = 5.0e9, n_table: int = 4096, n_radial: int = 10,
              n_angle: tuple[int, int, int] = (20, 24, 32), n_cone: tuple[int, int] = (16, 56),
              n_far: tuple[int, int] = (8, 12), far_ratio: float = 4.0,
              edge: tuple[float, float] = (0.85, 1.2), centre: float = 0.5) -> "FastTraction":
        """Tabulate eta(p) on [0, p_max] Pa and set up the node counts of the rules.

        Spin pole at |P| ellipse radii from the centre: n_radial x n_angle[0] nodes for
        |P| < centre, n_radial x n_angle[1] up to edge[0], n_radial x n_angle[2] up to 1
        (pole near the edge, inside), n_radial x n_cone[1] up to edge[1], n_radial x
        n_cone[0] up to far_ratio, n_far = (radial, angular) beyond. The defaults meet the
        2 % target with margin (tests/test_traction_fast.py); see benchmarks/traction.py
        for other settings. n_cone[1] = 56: with the pole a hair outside the edge near the end of
        the major axis, the contact fills a narrow wedge of a cone that opens to half a turn,
        and 24 chords were 35 % off there (docs/model.md §6.4, *The pole just outside the edge*);
        56 is the fewest that keep it within the rest of the rule's 0.76 %.
        """
        counts = (n_radial, *n_angle, *n_cone, *n_far)
        if len(n_angle) != 3 or min(counts) < 2 or not 1.0 < far_ratio \
                or not 0.0 < centre <= edge[0] <= 1.0 <= edge[1] <= far_ratio or p_max <= 0.0 or n_table < 2:
            raise ValueError(
                f"FastTraction.build: node counts {counts} must be >= 2 (three ray counts), 0 < centre <= "
                f"edge[0] <= 1 <= edge[1] <= far_ratio (got centre = {centre}, edge = {edge}, far_ratio = "
                f"{far_ratio}), p_max = {p_max} Pa > 0, n_table = {n_table} >= 2.")
        p = np.linspace(0.0, p_max, n_table)
        eta = rheology.viscosity_array(p, lubricant.model_code, lubricant.rheology_params())
        # the residual-only passes read a float32 copy: every law is held at eta_g = 1e12 Pa.s
        # (`lubrication.rheology`), so this holds unless a law breaks that promise
        if not np.all(np.isfinite(eta)) or eta.max() > rheology.GLASS_VISCOSITY or np.any(np.diff(eta) < 0.0):
            raise ValueError(
                f"lubricant '{lubricant.name}': its {lubricant.viscosity_model} viscosity is not finite, "
                f"non-decreasing and at most {rheology.GLASS_VISCOSITY:g} Pa.s over 0 .. {p_max:g} Pa; "
                "check lubricant.viscosity_model and its parameters (docs/model.md §6.4)")
        table = np.ascontiguousarray(np.stack([eta, np.append(np.diff(eta), 0.0)], axis=1))
        return cls(eta_table=table, p_step=float(p[1] - p[0]),
                   law=eyring.Eyring(float(lubricant.eyring_stress)),
                   shear_modulus=float(lubricant.elastic_shear_modulus),
                   rule=pack_rule(n_radial, tuple(n_angle), tuple(n_cone), tuple(n_far), float(far_ratio),
                                  tuple(edge), float(centre)))

    @property
    def max_nodes(self) -> int:
        """Largest node count of the three rules (workspace length)."""
        return max_nodes(self.rule)

    @property
    def _row_length(self) -> int:
        """max_nodes rounded up to whole cache lines of float32: every scratch row then starts on
        a line when the array does (`_speed.aligned`)."""
        lanes = CACHE_LINE // 4
        return -(-self.max_nodes // lanes) * lanes

    def workspace(self) -> tuple[np.ndarray, np.ndarray]:
        """Fresh scratch (work, iwork) for one thread, each row on a cache line (`_speed.aligned`)."""
        return empty_aligned((_WORK_ROWS, self._row_length)), empty_aligned(self._row_length, np.int64)

    def workspace32(self) -> tuple[np.ndarray, np.ndarray]:
        """Fresh float32 scratch (work32, iwork32) of the residual-only passes, one thread, each
        row on a cache line."""
        return empty_aligned((_WORK32_ROWS, self._row_length), np.float32), empty_aligned(self._row_length, np.int32)

    def traction_rule(self, float32_residual: bool = False) -> TractionRule:
        """The bundle `traction_fast` takes, with a fresh workspace (one per thread).

        float32_residual: residual-only calls through the float32 passes (module docstring):
        ~25 % cheaper, but the force then carries rounding steps of ~1e-7 that finite
        differences amplify, so only for callers with an analytic tangent (the time loop)
        (`TractionRule.with_float32_residual`)."""
        rule = TractionRule(self.eta_table, self.p_step, self.rule, *self.workspace(), *self.workspace32(),
                            self.eta_table.astype(np.float32).ravel(), False, self.law, self.shear_modulus)
        return rule.with_float32_residual(float32_residual)

    def evaluate(self, a, b, p_h, h, du0, dv0, w_s, u=0.0) -> tuple[np.ndarray, np.ndarray, int]:
        """(F = [F_x, F_y, M_z], J[3, 3], flag) on the ball; units as traction_fast (u = 0: the
        viscous law alone, without the film's inlet elasticity)."""
        out = np.empty(12)
        flag = traction_fast(float(a), float(b), float(p_h), float(h), float(du0), float(dv0), float(w_s),
                             float(u), self.traction_rule(), out)
        return out[:3].copy(), out[3:].reshape(3, 3).copy(), int(flag)

    def evaluate_batch(self, a, b, p_h, h, du0, dv0, w_s, u=0.0) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(F (n, 3), J (n, 3, 3), flags (n,)) for arrays of n contacts; units as traction_fast
        (u: one speed for all, or one per contact)."""
        u = np.broadcast_to(np.asarray(u, dtype=np.float64), np.shape(np.atleast_1d(a)))
        cols = [np.ascontiguousarray(np.atleast_1d(v), dtype=np.float64) for v in (a, b, p_h, h, du0, dv0, w_s, u)]
        n = cols[0].shape[0]
        if any(c.shape != (n,) for c in cols):
            raise ValueError(f"evaluate_batch: all inputs must be 1-D of one length; got shapes {[c.shape for c in cols]}.")
        F, J, flags = np.empty((n, 3)), np.empty((n, 3, 3)), np.empty(n, dtype=np.int64)
        traction_fast_batch(*cols, self.traction_rule(), F, J, flags)
        return F, J, flags
