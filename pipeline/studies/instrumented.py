"""Instrumented runs of a multibody problem over a fixed window, for the studies.

Three pieces, none of them bearing-specific except `bearing_window` at the end:

* `Instrumented` wraps any `dynamics.multibody` problem: counts residual evaluations and
  matrix builds per accepted step (the Newton statistics of the step-size history), stops a
  run past a wall-clock deadline (raises `WallClockExceeded`, so a case can never hang), and
  optionally replaces the model's (approximate) tangent by a finite-difference one.
* `fd_tangent` builds S = c_m M + c_v C_t + c_q K_t by central differences of the residual
  r = M a - g (docs/model.md §9, paper eq. 9), with material rotation increments on CRV slots —
  the "exact tangent" the approximate analytic one is compared with.
* `run_window` integrates with HHT-α and samples with the integrator's Hermite dense output
  at fixed times, so two runs with different steps are compared at the same instants.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

from ...dynamics.multibody.crv import update_configuration
from ...dynamics.multibody.linear_solvers import BlockArrowMatrix


class WallClockExceeded(RuntimeError):
    """A run took longer than its wall-clock budget (a case must never hang)."""

    def __init__(self, t: float, budget: float) -> None:
        self.t, self.budget = t, budget
        super().__init__(f"stopped at t = {t:.6g} s after the wall-clock budget of {budget:.0f} s; "
                         "the step size collapsed or the run is far too long for this window. "
                         "Try a shorter window, a larger solver.min_step, or a looser tolerance")


def fd_tangent(problem, t, q, v, a, c_m, c_v, c_q, template, dq_scale=1e-9, dv_scale=1e-6):
    """S = c_m M + c_v C_t + c_q K_t by central differences of r = M a - g (docs/model.md §9).

    q is perturbed by +-dq_scale [m, or rad on CRV slots, composed multiplicatively], v by
    +-dv_scale [m/s, rad/s]. M is read from one evaluation at a = 1 (diagonal mass; a row the
    model replaces by a constraint reads 0 there). `template` is the matrix the model's own
    `jacobian` returns (dense array or BlockArrowMatrix): the result has its structure, and
    entries outside a block-arrow pattern are dropped. 4 n + 1 evaluations.
    """
    n = problem.n_dof
    slots = np.ascontiguousarray(problem.rotation_slots, dtype=np.int64)
    ma, g_p, g_m = np.zeros(n), np.zeros(n), np.zeros(n)
    r_p, r_m = np.zeros(n), np.zeros(n)
    dense = np.zeros((n, n))
    dq, qp = np.zeros(n), np.zeros(n)
    for j in range(n):
        for sign, r in ((1.0, r_p), (-1.0, r_m)):
            dq[:] = 0.0
            dq[j] = sign * dq_scale
            update_configuration(q, dq, slots, qp)
            problem.evaluate(t, qp, v, a, ma, g_p)
            r[:] = ma - g_p
        dense[:, j] += c_q * (r_p - r_m) / (2.0 * dq_scale)
        for sign, r in ((1.0, r_p), (-1.0, r_m)):
            vp = v.copy()
            vp[j] += sign * dv_scale
            problem.evaluate(t, q, vp, a, ma, g_m)
            r[:] = ma - g_m
        dense[:, j] += c_v * (r_p - r_m) / (2.0 * dv_scale)
    problem.evaluate(t, q, v, np.ones(n), ma, g_p)
    dense[np.diag_indices(n)] += c_m * ma
    problem.evaluate(t, q, v, a, ma, g_p)  # leave the model's diagnostics at (q, v, a)
    if isinstance(template, BlockArrowMatrix):
        return block_arrow_from_dense(dense, template)
    return dense


def block_arrow_from_dense(dense: np.ndarray, out: BlockArrowMatrix) -> BlockArrowMatrix:
    """Copy the block-arrow pattern of a dense matrix into `out` (linear_solvers.py order)."""
    Z, m, nb = out.E.shape
    s = Z * m
    for k in range(Z):
        rows = slice(k * m, (k + 1) * m)
        out.D[k] = dense[rows, rows]
        out.E[k] = dense[rows, s:]
        out.F[k] = dense[s:, rows]
    out.B[:] = dense[s:, s:]
    return out


class Instrumented:
    """A problem wrapper with counters, a deadline and an optional finite-difference tangent.

    Follows `dynamics.multibody.problem.MultibodyProblem`. After each accepted step it
    appends (t [s], h [s], residual evaluations, matrix builds) since the previous accepted
    step to `history` (rejected attempts included), then calls the model's own hook.
    """

    def __init__(self, model, *, exact_tangent: bool = False, wall_budget: float = math.inf):
        self.model = model
        self.n_dof, self.rotation_slots = model.n_dof, model.rotation_slots
        self.error_weights = model.error_weights
        if hasattr(model, "error_scales"):
            self.error_scales = model.error_scales
        self.exact_tangent = exact_tangent
        self.wall_budget = wall_budget
        self.deadline = time.perf_counter() + wall_budget
        self.evaluations = self.builds = 0
        self._last = (0.0, 0, 0)
        self.history: list[tuple[float, float, int, int]] = []
        self._t = 0.0

    def evaluate(self, t, q, v, a, ma_out, g_out) -> None:
        self.evaluations += 1
        self._t = t
        if self.evaluations % 64 == 0 and time.perf_counter() > self.deadline:
            raise WallClockExceeded(t, self.wall_budget)
        self.model.evaluate(t, q, v, a, ma_out, g_out)

    def jacobian(self, t, q, v, a, c_m, c_v, c_q):
        self.builds += 1
        template = self.model.jacobian(t, q, v, a, c_m, c_v, c_q)
        if not self.exact_tangent or (c_v == 0.0 and c_q == 0.0):
            return template
        return fd_tangent(self.model, t, q, v, a, c_m, c_v, c_q, template)

    def on_accepted_step(self, t, q, v, a) -> None:
        t0, e0, b0 = self._last
        self.history.append((t, t - t0, self.evaluations - e0, self.builds - b0))
        self._last = (t, self.evaluations, self.builds)
        hook = getattr(self.model, "on_accepted_step", None)
        if hook is not None:
            hook(t, q, v, a)


@dataclass
class WindowRun:
    """A run over [0, window]: Hermite samples at `t`, step history, counters, outcome.

    `error` is None for a completed run, else the message of the exception that stopped it
    (samples after the stop are NaN). history columns: t, h, evaluations, matrix builds.
    """

    t: np.ndarray
    q: np.ndarray
    v: np.ndarray
    wall: float
    stats: dict
    history: np.ndarray
    error: str | None = None
    error_kind: str | None = None
    extra: dict = field(default_factory=dict)

    @property
    def completed(self) -> bool:
        return self.error is None


def run_window(problem, q0, v0, settings, window: float, sample_interval: float, *,
               linear_solver=None, exact_tangent: bool = False,
               wall_budget: float = math.inf) -> tuple[WindowRun, Instrumented]:
    """Integrate `problem` from t = 0 to `window` [s] with HHT-α (`settings`); sample q and
    v every `sample_interval` [s] on [0, window). Never raises for a solver failure: the
    outcome is in `WindowRun.error` (IntegrationError, WallClockExceeded, a ValueError).

    A problem with a compiled side runs in the compiled loop (`multibody.compiled`), as in a
    user's run, unless `exact_tangent` asks for the Python loop's finite-difference tangent."""
    from ...dynamics.multibody import FixedIntervalSampler, IntegrationError, integrate
    from ...dynamics.multibody.compiled import RunTrace, integrate_compiled

    wrapped = Instrumented(problem, exact_tangent=exact_tangent, wall_budget=wall_budget)
    # samples on [0, window): a sample exactly at the window's end can be lost to rounding
    # of the accumulated fixed-step time (the last step ends ~1e-18 s short of it)
    sampler = FixedIntervalSampler(0.0, window - 0.5 * sample_interval, sample_interval, problem.n_dof)
    compiled = hasattr(problem, "compiled") and not exact_tangent

    def check_budget(t: float, h: float) -> None:
        if time.perf_counter() > wrapped.deadline:
            raise WallClockExceeded(t, wall_budget)

    t0 = time.perf_counter()
    error = kind = None
    stats: dict = {}
    trace = RunTrace()
    try:
        if compiled:
            sol, _ = integrate_compiled(problem, 0.0, window, q0, v0, settings, sampler=sampler, log_every=1,
                                        on_chunk=check_budget, trace=trace)
        else:
            sol = integrate(wrapped, 0.0, window, q0, v0, settings, linear_solver=linear_solver,
                            sampler=sampler)
        stats = sol.stats.as_dict()
    except (IntegrationError, WallClockExceeded, ValueError, FloatingPointError) as exc:
        error, kind = str(exc), type(exc).__name__
    wall = time.perf_counter() - t0
    if compiled:  # cumulative counts per accepted step -> per step, as the Python loop's history
        stats = stats or trace.stats.as_dict()
        log = np.concatenate(trace.log) if trace.log else np.zeros((0, 4))
        hist = log.copy()
        hist[:, 2:] = np.diff(log[:, 2:], axis=0, prepend=0.0)
    else:
        stats.setdefault("residual_evaluations", wrapped.evaluations)
        stats.setdefault("factorizations", wrapped.builds)
        stats.setdefault("steps", len(wrapped.history))
        hist = np.array(wrapped.history, dtype=float).reshape(-1, 4)
    return WindowRun(t=sampler.t, q=sampler.q, v=sampler.v, wall=wall, stats=stats,
                     history=hist, error=error, error_kind=kind), wrapped


def bearing_window(params, start, settings, window: float, sample_interval: float, *,
                   exact_tangent: bool = False, wall_budget: float = math.inf,
                   q0=None, v0=None, float32_residual: bool | None = None) -> tuple[WindowRun, object]:
    """`run_window` for the bearing model from its quasi-static start (or given q0, v0);
    returns the run and the model (impact log, energy balance, diagnostics).

    float32_residual: the float32 traction passes of a user's run (`simulate_bearing`); by
    default on unless `exact_tangent` (finite differences need the smooth float64 residual)."""
    from ...dynamics.bearing import BearingModel
    from ...dynamics.bearing.run import initial_coordinates
    from ...dynamics.multibody.linear_solvers import BlockArrowSolver

    params = params.with_float32_residual(not exact_tangent if float32_residual is None else float32_residual)
    model = BearingModel(params)
    q_start, v_start = initial_coordinates(params, start)
    q0 = q_start if q0 is None else q0
    v0 = v_start if v0 is None else v0
    solver = BlockArrowSolver(params.ball_count, 6, model.nb)
    run, _ = run_window(model, q0, v0, settings, window, sample_interval, linear_solver=solver,
                        exact_tangent=exact_tangent, wall_budget=wall_budget)
    run.extra["impacts"] = model.impact_log()
    run.extra["energy"] = dict(model.energy)
    return run, model
