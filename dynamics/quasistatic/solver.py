"""Quasi-static equilibrium of a ball bearing (docs/model.md §10): the solver.

Unknowns: inner-race displacement and tilt q = (u_x, u_y, u_z, θ_x, θ_y) and each ball's
centre (r, z) in its azimuth plane. Balls are equilibrated one by one (2×2 Newton, see
`dynamics.quasistatic.kernels`), the inner race by Newton on the five loads with the
exact condensed tangent; the condensed tangent at the solution is the bearing stiffness.
Start: a one-dimensional search along the load direction (rigid-ring estimate that takes
up the clearance), then Newton with a line search on the potential energy (M.119), then,
if needed, load continuation from the axial load alone, radial load and moment ramped up.
Ball orbital speed, centrifugal force and gyroscopic friction use pure-rolling
kinematics with race control, updated by fixed-point passes until they settle.

Example::

    from ..geometry import BearingGeometry, Material
    from ..operating_point import OperatingPoint
    from .solver import solve_quasistatic
    res = solve_quasistatic(geometry, steel, steel,
                            OperatingPoint(axial=34000.0, moment=430.0, inner_speed=320.4))
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..geometry import BearingGeometry, Material, contact_side, effective_modulus
from ..contact.hertz import (DEFAULT_TABLE_NODES, TAB_DKH, TAB_KH, hertz_table_eval, max_pressure,
                            race_hertz_table)
from .kernels import (BALL_COLUMNS, B_AI, B_AO, B_DI, B_DO, B_FR, B_FZ, B_QI, B_QO,
                                          B_STATUS, STATUS_FAILED, BallLoads, Grooves, ball_kinematics,
                                          bearing_equilibrium)
from ..operating_point import OperatingPoint
from .options import QuasiStaticOptions
from .result import QuasiStaticResult, tilt_rotation_matrix


class QuasiStaticError(RuntimeError):
    """The quasi-static equilibrium could not be found; the message says why and what to try."""


@dataclass
class _Problem:
    """Arrays packed once for the kernels (SI)."""

    psi: np.ndarray
    R_ci: float
    R_co: float
    gap_i: float
    gap_o: float
    tab_i: np.ndarray
    tab_o: np.ndarray
    m_om2: np.ndarray
    g_i: np.ndarray
    g_o: np.ndarray
    xb: np.ndarray
    linear_kinematics: bool = False
    # angle at which the groove meets its land [rad] for a contact angle >= 0 and < 0 (the land
    # on the side that contact presses on, dynamics.geometry.contact_side); NaN: no land
    land_i: tuple[float, float] = (math.nan, math.nan)
    land_o: tuple[float, float] = (math.nan, math.nan)

    def land_limit(self, ring: str, angles: np.ndarray) -> np.ndarray:
        """The land angle [rad] each contact of `ring` at `angles` [rad] may reach before its
        centre rides over the land (pi/2, the groove's edge, where there is no land)."""
        positive, negative = self.land_i if ring == "inner" else self.land_o
        limit = np.where(np.asarray(angles) >= 0.0, positive, negative)
        return np.where(np.isfinite(limit), limit, 0.5 * math.pi)

    @property
    def lever(self) -> float:
        """Length that turns tilts into displacements and moments into forces [m]."""
        return self.R_ci

    def inner_centres(self, q: np.ndarray):
        """Inner curvature centres C_i = u + R(θ) (d_i/2) e_r(ψ) in each ball's azimuth plane.

        Exact rigid rotation (rotation vector (θ_x, θ_y, 0)) rather than the small-angle
        (Jones) form, so moment arms include the tilt-induced axial offset of C_i.
        Returns ((Z, 2) centres (r, z), (Z, 2, 5) G = ∂C_i/∂q, (Z, 3) rotated R C0).
        """
        c, s = np.cos(self.psi), np.sin(self.psi)
        if self.linear_kinematics:  # Jones / ISO/TS 16281: C_i = C0 + u + θ × C0, moment arm d_i/2
            ci = np.column_stack([self.R_ci + q[0] * c + q[1] * s, q[2] + self.R_ci * (q[3] * s - q[4] * c)])
            g = np.zeros((self.psi.size, 2, 5))
            g[:, 0, 0], g[:, 0, 1], g[:, 1, 2], g[:, 1, 3], g[:, 1, 4] = c, s, 1.0, self.R_ci * s, -self.R_ci * c
            return ci, g, np.zeros((self.psi.size, 3))
        c0 = self.R_ci * np.column_stack([c, s, np.zeros_like(c)])
        v = c0 @ tilt_rotation_matrix(q[3:]).T
        centre = v + q[:3]
        ci = np.column_stack([c * centre[:, 0] + s * centre[:, 1], centre[:, 2]])
        # δ(R c0) = (J_l δθ) × (R c0): columns for δθ_x, δθ_y
        jl = _left_jacobian(np.array([q[3], q[4], 0.0]))
        dv = np.stack([np.cross(jl[:, a], v) for a in range(2)], axis=2)  # (Z, 3, 2)
        g = np.zeros((self.psi.size, 2, 5))
        g[:, 0, 0], g[:, 0, 1], g[:, 1, 2] = c, s, 1.0
        g[:, 0, 3:] = c[:, None] * dv[:, 0, :] + s[:, None] * dv[:, 1, :]
        g[:, 1, 3:] = dv[:, 2, :]
        return ci, g, v

    def contact(self, q: np.ndarray, warm: bool = True):
        """(generalised contact force on the inner race (5), stiffness (5×5), ball table, failures).

        Stiffness = Σ Gᵀ K_c G (balls re-equilibrated) − Σ f·∂²C_i/∂θ² (geometric term of the
        rotation, small-angle form), i.e. the Hessian of the contact energy: symmetric when
        k_h is constant.
        """
        ci, g, v = self.inner_centres(q)
        force, stiff = np.zeros(5), np.zeros((5, 5))
        balls = np.zeros((self.psi.size, BALL_COLUMNS))
        failed = bearing_equilibrium(ci, g, self.R_co, Grooves(self.tab_i, self.tab_o, self.gap_i, self.gap_o),
                                     BallLoads(self.m_om2, self.g_i, self.g_o), self.xb, warm, force, stiff, balls)
        e_r = np.column_stack([np.cos(self.psi), np.sin(self.psi)])
        for a in range(2):
            for b in range(2):
                # ∂²(R v)/∂θ_a∂θ_b at θ = 0: ½[e_b (e_a·v) + e_a (e_b·v)] − v δ_ab
                sv = -v * (a == b)
                sv[:, b] += 0.5 * v[:, a]
                sv[:, a] += 0.5 * v[:, b]
                proj_r = np.sum(e_r * sv[:, :2], axis=1)
                stiff[3 + a, 3 + b] -= np.sum(balls[:, B_FR] * proj_r + balls[:, B_FZ] * sv[:, 2])
        return force, stiff, balls, failed


def _left_jacobian(theta: np.ndarray) -> np.ndarray:
    """SO(3) left Jacobian J_l(θ): δ(R(θ)) = (J_l δθ)~ R (rotation-vector parameters)."""
    phi = float(np.linalg.norm(theta))
    t = np.array([[0.0, -theta[2], theta[1]], [theta[2], 0.0, -theta[0]], [-theta[1], theta[0], 0.0]])
    if phi < 1e-8:
        return np.eye(3) + 0.5 * t
    return np.eye(3) + (1.0 - math.cos(phi)) / phi**2 * t + (phi - math.sin(phi)) / phi**3 * t @ t


def _scale(problem: _Problem) -> np.ndarray:
    """q̂ = q / scale has metres everywhere; residual·scale has newtons everywhere."""
    return np.array([1.0, 1.0, 1.0, 1.0 / problem.lever, 1.0 / problem.lever])


def _initial_guess(problem: _Problem, load: np.ndarray) -> np.ndarray:
    """Move the inner race along the (scaled) load direction until the contact load's
    component along it balances the applied one: takes up the clearance and gives a
    rigid-ring-like start that is in contact (Newton needs a non-zero tangent)."""
    sc = _scale(problem)
    load_hat = load * sc
    norm = np.linalg.norm(load_hat)
    if norm == 0.0:
        return np.zeros(5)
    d_hat = load_hat / norm

    def balance(s: float) -> float:
        force, _, _, _ = problem.contact(s * d_hat * sc, warm=False)
        return norm + d_hat @ (force * sc)

    lo, hi = 0.0, 1e-6
    while balance(hi) > 0.0:
        lo, hi = hi, 2.0 * hi
        if hi > 1.0:
            raise QuasiStaticError(
                "the contacts cannot balance the applied load even after a 1 m displacement of "
                "the inner race: check the geometry (groove radii, diameters) and the load units (N, N·m)")
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if balance(mid) > 0.0:
            lo = mid
        else:
            hi = mid
    return hi * d_hat * sc


def _newton(problem: _Problem, load: np.ndarray, q0: np.ndarray, tol: float, max_iter: int):
    """Newton on the inner-race equilibrium, globalised on the potential energy (docs/model.md
    §10, M.119). Returns (q, iters, ok, res).

    The equilibrium is the minimum of Π(q) = Σ contact energies − load·q. Each step is a
    descent direction of Π and the line search looks for the minimum of Π along it. A
    backtracking on |residual| instead stalls where the tangent is singular and the
    out-of-balance load lies in its null space (e.g. a race pivoting about a loaded zone
    with all other balls loose): a stationary point of |residual|², not an equilibrium.
    """
    sc = _scale(problem)
    cap = 0.5 * (problem.gap_i + problem.gap_o)  # largest step [m]: half the groove play
    q = q0.copy()
    force, stiff, balls, failed = problem.contact(q)
    res = (load + force) * sc
    for it in range(1, max_iter + 1):
        # residual scale: applied load, or the internal (preload) ball loads, or 1 N
        ref = max(np.max(np.abs(load * sc)), np.sum(balls[:, B_QI]), 1.0)
        if failed == 0 and np.max(np.abs(res)) <= tol * ref:
            return q, it - 1, True, float(np.max(np.abs(res)))
        step_hat = _descent_step(stiff * sc[:, None] * sc[None, :], res)
        step_len = np.max(np.abs(step_hat))
        if step_len > cap:
            step_hat *= cap / step_len
        found = _energy_line_search(problem, load, q, step_hat, res)
        if found is None:
            return q, it, False, float(np.max(np.abs(res)))
        q, (force, stiff, balls, failed), res = found
    ref = max(np.max(np.abs(load * sc)), np.sum(balls[:, B_QI]), 1.0)
    ok = failed == 0 and np.max(np.abs(res)) <= tol * ref
    return q, max_iter, ok, float(np.max(np.abs(res)))


def _descent_step(k_hat: np.ndarray, res: np.ndarray) -> np.ndarray:
    """Scaled Newton step K̂⁻¹ r̂, or — when that is no descent direction of Π (r̂·step ≤ 0:
    K̂ indefinite, from the rotation's geometric term or the centrifugal force) — the step
    of the symmetric part shifted to be positive definite (a Levenberg–Marquardt step)."""
    k_hat = k_hat + np.eye(5) * 1e-12 * max(np.trace(k_hat), 1.0)  # directions without load
    try:
        step = np.linalg.solve(k_hat, res)
        if res @ step > 0.0 and np.all(np.isfinite(step)):
            return step
    except np.linalg.LinAlgError:
        pass
    k_sym = 0.5 * (k_hat + k_hat.T)
    eig = np.linalg.eigvalsh(k_sym)
    shift = max(0.0, -eig[0]) + 1e-6 * max(eig[-1], 1.0)
    return np.linalg.solve(k_sym + shift * np.eye(5), res)


def _energy_line_search(problem: _Problem, load: np.ndarray, q: np.ndarray, step_hat: np.ndarray,
                        res: np.ndarray):
    """Step length λ along the scaled step towards the minimum of Π; None if none is found.

    Π itself is not evaluated (k_h(α) makes the contact force slightly non-conservative);
    its slope along the step is: dΠ/dλ = −φ(λ), φ(λ) = r̂(q + λ s)·ŝ (the work rate of the
    out-of-balance load). φ(0) > 0 (descent). λ = 1 is taken unless it overshoots the
    minimum by more than half the initial slope (φ(1) < −φ(0)/2, where Π may have risen);
    then the secant of φ moves λ towards its zero. A ball that fails to converge halves λ.
    """
    sc = _scale(problem)
    step = step_hat * sc
    slope0 = res @ step_hat
    lam = 1.0
    for _ in range(40):
        trial = problem.contact(q + lam * step)
        res_new = (load + trial[0]) * sc
        slope = res_new @ step_hat
        if trial[3] == 0 and slope >= -0.5 * slope0:
            return q + lam * step, trial, res_new
        if trial[3] != 0 or not np.isfinite(slope):
            lam *= 0.5
        else:  # overshoot: secant towards φ = 0, kept within [0.1 λ, 0.9 λ]
            lam *= min(0.9, max(0.1, slope0 / (slope0 - slope)))
        if lam < 1e-12:
            break
    return None


def _solve_load(problem: _Problem, load: np.ndarray, q0, tol: float, max_iter: int):
    """Newton from q0 (or from the rigid-ring start), then load continuation if needed."""
    start = _initial_guess(problem, load) if q0 is None else q0
    q, its, ok, res = _newton(problem, load, start, tol, max_iter)
    if ok:
        return q, its, res
    return _continuation(problem, load, tol, max_iter, its)


def _load_path(load: np.ndarray):
    """Continuation path t ∈ [0, 1] → loads: the axial load alone at t = 0 (every ball takes
    an equal share: a well-posed start, unlike the zero load where all contacts open), then
    the radial load and the moment ramped up with t."""
    def path(t: float) -> np.ndarray:
        out = t * load
        out[2] = load[2]
        return out
    return path


def _continuation(problem: _Problem, load: np.ndarray, tol: float, max_iter: int, total: int):
    """Follow `_load_path` with adaptive steps, each Newton from the previous equilibrium."""
    path = _load_path(load)
    q_prev, its, ok, res = _newton(problem, path(0.0), _initial_guess(problem, path(0.0)), tol, max_iter)
    total += its
    frac, step = (0.0, 0.25) if ok else (None, 0.0)
    while ok and frac < 1.0:
        trial = min(1.0, frac + step)
        # an equilibrium that carries nothing (no axial load) gives Newton no tangent: rigid-ring start
        start = q_prev if np.any(problem.contact(q_prev)[2][:, B_QI] > 0.0) else _initial_guess(problem, path(trial))
        q_new, its, converged, res = _newton(problem, path(trial), start, tol, max_iter)
        total += its
        if converged:
            frac, q_prev, step = trial, q_new, min(2.0 * step, 0.5)
        else:
            step *= 0.5
            ok = step >= 1e-4
    if ok:
        return q_prev, total, res
    raise _no_equilibrium(problem, q_prev if frac is not None else None, frac, res)


def _no_equilibrium(problem: _Problem, q_last, frac, res: float) -> QuasiStaticError:
    """Why the continuation stopped: past a land (the ball rides over the shoulder: no
    equilibrium inside the groove model, a limit of the load) or a solver failure."""
    if q_last is not None:
        hit = _past_land(problem, problem.contact(q_last)[2])
        if hit is not None:
            k, side, angle, limit = hit
            has_land = limit < 0.5 * math.pi
            edge = f"the {side} land at {math.degrees(limit):.2f}°" if has_land else "90°, the edge of the groove"
            return QuasiStaticError(
                f"with {100 * frac:.1f} % of the radial load and moment on top of the axial load, ball {k}: "
                f"the {side} contact angle {math.degrees(angle):.2f}° already reaches {edge}: the ball rides "
                f"over the shoulder on the way to the full load, which the groove model cannot follow. Reduce "
                f"the radial load or the moment.")
    where = ("under the axial load alone" if frac is None
             else f"beyond {100 * frac:.2f} % of the radial load and moment")
    return QuasiStaticError(
        f"Newton diverged {where} (residual {res:.3g} N): the bearing probably cannot carry it (contact "
        "angles near the groove limit). Try a smaller load, check the clearance and groove radii, or loosen `tol`.")


def _past_land(problem: _Problem, balls: np.ndarray):
    """(ball, side, |α|, limit) of the first loaded contact at or past its land — 90°, the
    edge of the groove, where there is none — else None."""
    for side, col_q, col_a in (("inner", B_QI, B_AI), ("outer", B_QO, B_AO)):
        limit = problem.land_limit(side, balls[:, col_a])
        over = np.flatnonzero((balls[:, col_q] > 0.0) & (np.abs(balls[:, col_a]) >= limit))
        if over.size:
            k = int(over[0])
            return k, side, float(abs(balls[k, col_a])), float(limit[k])
    return None


def _kinematics(problem, balls, D, inner_speed, outer_speed, inner_control):
    """Per-ball pure-rolling (ω_m, ω_r, ω_z) [rad/s] at the current contact angles."""
    out = np.zeros((problem.psi.size, 3))
    for k in range(problem.psi.size):
        alpha_i, alpha_o = balls[k, B_AI], balls[k, B_AO]
        if 1.0 + math.cos(alpha_i - alpha_o) < 1e-9:
            # the normals point the same way (only for a ball the race has pushed through the groove,
            # far outside the model): pure rolling is singular there; roll as if collinear
            alpha_i = alpha_o
        out[k] = ball_kinematics(alpha_i, alpha_o, problem.xb[k, 0], D, inner_speed, outer_speed, inner_control)
    return out


def _check_geometry(geometry):
    if geometry.curvature_center_distance <= 0.0:
        raise ValueError(
            f"groove radii too small: r_i + r_o − D = {geometry.curvature_center_distance:.3e} m must be > 0")


def _hertz_tables(geometry, e_eff, contact_constants, nodes):
    tab_i = race_hertz_table(geometry, e_eff, outer=False, n_nodes=nodes)
    tab_o = race_hertz_table(geometry, e_eff, outer=True, n_nodes=nodes)
    if contact_constants is not None:
        # fixed k_h (e.g. to reproduce a textbook that used one value); ellipse data stays exact
        for tab, k in zip((tab_i, tab_o), contact_constants):
            tab[:, TAB_KH], tab[:, TAB_DKH] = float(k), 0.0
    return tab_i, tab_o


def _make_problem(geometry: BearingGeometry, ball_material: Material, race_material: Material,
                  contact_constants=None, kinematics: str = "exact",
                  table_nodes: int = DEFAULT_TABLE_NODES) -> _Problem:
    """The kernels' arrays for `geometry`, balls at rest (no centrifugal force, no friction)."""
    e_eff = effective_modulus(ball_material, race_material)
    tab_i, tab_o = _hertz_tables(geometry, e_eff, contact_constants, table_nodes)
    Z, D = geometry.ball_count, geometry.ball_diameter
    R_ci, R_co = 0.5 * geometry.inner_groove_center_diameter, 0.5 * geometry.outer_groove_center_diameter
    return _Problem(
        psi=2.0 * np.pi * np.arange(Z) / Z, R_ci=R_ci, R_co=R_co, gap_i=geometry.inner_groove_radius - 0.5 * D,
        gap_o=geometry.outer_groove_radius - 0.5 * D, tab_i=tab_i, tab_o=tab_o, m_om2=np.zeros(Z),
        g_i=np.zeros(Z), g_o=np.zeros(Z), xb=np.full((Z, 2), np.nan), linear_kinematics=kinematics == "linear",
        land_i=_land_angles(geometry, "inner", R_ci, geometry.inner_groove_radius),
        land_o=_land_angles(geometry, "outer", R_co, geometry.outer_groove_radius))


def solve_quasistatic(
    geometry: BearingGeometry,
    ball_material: Material,
    race_material: Material,
    loads: OperatingPoint = OperatingPoint(),
    options: QuasiStaticOptions = QuasiStaticOptions(),
    *,
    tol: float = 1e-10,
    max_iter: int = 50,
    table_nodes: int = DEFAULT_TABLE_NODES,
) -> QuasiStaticResult:
    """Quasi-static equilibrium of the bearing under loads on the inner race (docs/model.md §10).

    loads: the axial, radial and moment loads on the inner race and the race speeds
    (`OperatingPoint`); options: centrifugal force, gyroscopic friction and its controlling
    race, kinematics, fixed contact constants (`QuasiStaticOptions`). tol: relative residual
    of the five loads (moments divided by d_i/2); max_iter: Newton iterations of one solve;
    table_nodes: nodes of the Hertz tables in the contact angle.
    Raises QuasiStaticError when no equilibrium is found or a contact rides over a land.
    """
    _check_geometry(geometry)
    problem = _make_problem(geometry, ball_material, race_material, options.contact_constants, options.kinematics,
                            table_nodes)
    centrifugal, gyroscopic = options.centrifugal, options.gyroscopic
    inner_speed, outer_speed = loads.inner_speed, loads.outer_speed
    Z, D = geometry.ball_count, geometry.ball_diameter
    load = np.array([loads.radial, 0.0, loads.axial, 0.0, loads.moment], dtype=float)
    mass, inertia = geometry.ball_mass(ball_material), geometry.ball_inertia(ball_material)
    inner_control = options.race_control == "inner"
    moving = inner_speed != 0.0 or outer_speed != 0.0

    q, iterations, residual = _solve_load(problem, load, None, tol, max_iter)
    for _ in range(30):  # kinematic fixed point: ω_c, centrifugal force, gyroscopic friction
        _, _, balls, _ = problem.contact(q)
        kin = _kinematics(problem, balls, D, inner_speed, outer_speed, inner_control)
        if not moving or not (centrifugal or gyroscopic):
            break
        w_c = float(np.mean(kin[:, 0]))
        m_om2 = np.full(Z, mass * w_c**2 if centrifugal else 0.0)
        friction = 2.0 * inertia * w_c * kin[:, 1] / D if gyroscopic else np.zeros(Z)
        g_i, g_o = (friction, np.zeros(Z)) if inner_control else (np.zeros(Z), friction)
        change = max(np.max(np.abs(m_om2 - problem.m_om2)) * D, np.max(np.abs(g_i - problem.g_i)),
                     np.max(np.abs(g_o - problem.g_o)))
        if change <= 1e-9 * max(1.0, np.max(np.abs(load))):
            break
        problem.m_om2, problem.g_i, problem.g_o = m_om2, g_i, g_o
        q, its, residual = _solve_load(problem, load, q, tol, max_iter)
        iterations += max(its, 1)
    return _build_result(geometry, problem, q, load, kin, iterations, residual, inner_speed, outer_speed)


def _land_angles(geometry: BearingGeometry, ring: str, center_radius: float, groove_radius: float):
    """(land angle for a contact angle >= 0, for one < 0) [rad] of `ring`: each the land on the
    side that contact presses on (NaN: no land)."""
    return tuple(_shoulder_angle(geometry.shoulder(ring, contact_side(ring, sign)), center_radius, groove_radius,
                                 outer=ring == "outer") for sign in (1.0, -1.0))


def _shoulder_angle(land_diameter, center_radius, groove_radius, outer: bool) -> float:
    """Angle from the radial plane at which the groove meets the land [rad] (NaN: no land)."""
    if land_diameter is None:
        return math.nan
    depth = (0.5 * land_diameter - center_radius) if outer else (center_radius - 0.5 * land_diameter)
    return math.acos(max(-1.0, min(1.0, depth / groove_radius)))


def _ellipse(tab, loads, angles):
    """(p_max [Pa], semi-major a [m]) per ball from the Hertz table."""
    p, a = np.zeros(loads.size), np.zeros(loads.size)
    for k in range(loads.size):
        _, _, _, c_a, c_b = hertz_table_eval(tab, angles[k])
        p[k] = max_pressure(loads[k], c_a, c_b)
        a[k] = c_a * max(loads[k], 0.0) ** (1.0 / 3.0)
    return p, a


def _land_error(geometry, problem: _Problem, balls: np.ndarray, k: int, side: str, land_angle: float):
    """QuasiStaticError: ball k's loaded `side` contact has reached the land at land_angle [rad].
    Its azimuth and load say where (e.g. a light contact opposite a radial load)."""
    col_q, col_a = (B_QI, B_AI) if side == "inner" else (B_QO, B_AO)
    land_side = contact_side(side, balls[k, col_a])
    land = geometry.shoulder(side, land_side)
    pair = geometry.shoulders(side)
    which = "" if pair is None or pair[0] == pair[1] else f", its side toward {'+z' if land_side > 0 else '-z'}"
    where = f"ball {k} (azimuth {math.degrees(problem.psi[k]):.1f}°, {balls[k, col_q]:.4g} N)"
    return QuasiStaticError(
        f"{where}: the {side} contact angle {math.degrees(balls[k, col_a]):.2f}° reaches the "
        f"{side} land at {math.degrees(land_angle):.2f}° ({side}_shoulder_diameter = {land} m{which}): the ball "
        f"rides over the shoulder and the contact ellipse is cut off by the land, so the groove "
        f"cannot carry this load. Reduce the axial load or moment, or check the shoulder diameter.")


def _truncation(geometry, problem, balls, a_i, a_o):
    """Margins r(θ_land − |α|) − a [m]; raise if a loaded contact centre passes a land."""
    margins, notes = [], []
    for side, r, col_q, col_a, a in (
            ("inner", geometry.inner_groove_radius, B_QI, B_AI, a_i),
            ("outer", geometry.outer_groove_radius, B_QO, B_AO, a_o)):
        land = problem.land_i if side == "inner" else problem.land_o
        theta = np.where(balls[:, col_a] >= 0.0, land[0], land[1])  # NaN without a land
        margin = r * (theta - np.abs(balls[:, col_a])) - a
        loaded = balls[:, col_q] > 0.0
        over = np.flatnonzero(loaded & (np.abs(balls[:, col_a]) >= theta))
        if over.size:
            k = int(over[0])
            raise _land_error(geometry, problem, balls, k, side, float(theta[k]))
        pair = geometry.shoulders(side)
        for k in np.flatnonzero(loaded & (margin < 0.0)):
            which = ("" if pair is None or pair[0] == pair[1]
                     else f" on its side toward {'+z' if contact_side(side, balls[k, col_a]) > 0 else '-z'}")
            notes.append(f"ball {int(k)}: {side} contact ellipse truncated by the land{which} by "
                         f"{-margin[k] * 1e3:.3f} mm (semi-axis a = {a[k] * 1e3:.3f} mm)")
        margins.append(np.where(loaded, margin, r * (theta - np.abs(balls[:, col_a]))))
    return margins[0], margins[1], tuple(notes)


def _build_result(geometry, problem, q, load, kin, iterations, residual, inner_speed, outer_speed):
    force, stiffness, balls, failed = problem.contact(q)
    if failed or np.any(balls[:, B_STATUS] == STATUS_FAILED):
        raise QuasiStaticError("a ball's equilibrium did not converge at the final inner-race position; "
                               "try a smaller load or check the geometry")
    p_i, a_i = _ellipse(problem.tab_i, balls[:, B_QI], balls[:, B_AI])
    p_o, a_o = _ellipse(problem.tab_o, balls[:, B_QO], balls[:, B_AO])
    margin_i, margin_o, notes = _truncation(geometry, problem, balls, a_i, a_o)
    psi = problem.psi
    xb = problem.xb
    positions = np.column_stack([xb[:, 0] * np.cos(psi), xb[:, 0] * np.sin(psi), xb[:, 1]])
    spin = np.column_stack([kin[:, 1] * np.cos(psi), kin[:, 1] * np.sin(psi), kin[:, 2]])
    norm = np.linalg.norm(stiffness)
    return QuasiStaticResult(
        converged=True, iterations=int(iterations), inner_displacement=q[:3].copy(),
        inner_tilt=q[3:].copy(), azimuth=psi.copy(), inner_load=balls[:, B_QI].copy(),
        outer_load=balls[:, B_QO].copy(), inner_contact_angle=balls[:, B_AI].copy(),
        outer_contact_angle=balls[:, B_AO].copy(), inner_deflection=balls[:, B_DI].copy(),
        outer_deflection=balls[:, B_DO].copy(), max_pressure_inner=p_i, max_pressure_outer=p_o,
        semi_major_inner=a_i, semi_major_outer=a_o, truncation_margin_inner=margin_i,
        truncation_margin_outer=margin_o, stiffness=stiffness, ball_positions=positions,
        ball_angular_velocity=spin, ball_orbital_speed=kin[:, 0].copy(), cage_speed=float(np.mean(kin[:, 0])),
        inner_speed=float(inner_speed), outer_speed=float(outer_speed), applied_load=load.copy(),
        residual=float(residual),
        stiffness_asymmetry=float(np.linalg.norm(stiffness - stiffness.T) / norm) if norm > 0 else 0.0,
        warnings=notes)
