"""Time loop: HHT-α steps, step-size control, sampling and the accepted-step hook (docs/model.md §9).

Control flow per attempt: Newton failure -> reject, h *= newton_failure_factor (never below
min_step; failing at min_step raises IntegrationError); error norm > 1 -> reject, shrink h by
the controller; error norm > 1 at min_step -> accept and count `min_step_accepts` (contact
impacts may need it; the count tells the user the tolerance was not met).
"""

from __future__ import annotations

import math
import time
from typing import Callable

import numpy as np

from .hht import HHTState, HHTStepper
from .linear_solvers import DenseSolver
from .problem import check_problem, checked_error_scales
from .results import IntegrationError, NewtonStallWatch, Result, Solution, SolverStats, damping_first
from .settings import HHTSettings
from .step_control import AT_MIN_STEP, LAST_STEP_STRETCH, next_step


def initial_acceleration(problem, solver, t0: float, q0, v0) -> tuple[np.ndarray, np.ndarray]:
    """Consistent a0 from M(q0) a0 = g(t0, q0, v0) (S with c_m = 1, c_v = c_q = 0); also g0."""
    n = problem.n_dof
    ma, g0, a0 = np.zeros(n), np.zeros(n), np.zeros(n)
    problem.evaluate(t0, q0, v0, a0, ma, g0)
    if not np.all(np.isfinite(g0)):
        bad = np.flatnonzero(~np.isfinite(g0))[:5]
        raise IntegrationError(t0, 0.0, f"initial forces are not finite at coordinates {bad}",
                               Result.NAN_RESIDUAL.hint)
    if not solver.factor(problem.jacobian(t0, q0, v0, a0, 1.0, 0.0, 0.0)):
        raise IntegrationError(t0, 0.0, "the mass matrix is singular",
                               Result.SINGULAR_MATRIX.hint + ", or pass a0 explicitly")
    solver.solve(g0 - ma, a0)
    return a0, g0


def integrate(problem, t0: float, t1: float, q0, v0, settings: HHTSettings | None = None, *,
              a0=None, linear_solver=None, sampler=None,
              on_step: Callable | None = None) -> Solution:
    """Integrate a `MultibodyProblem` from t0 to t1 [s] with HHT-α.

    q0, v0: initial configuration and velocity (n,). a0: initial acceleration (default:
    solved from M a0 = g). linear_solver: `DenseSolver()` (default) or `BlockArrowSolver`.
    sampler: e.g. `FixedIntervalSampler`. on_step(t, q, v, a): called after each accepted
    step (default: `problem.on_accepted_step` if the problem has one).
    With `settings.adaptive = False` the step is fixed at `first_step` and the last step
    lands on t1. Raises IntegrationError when Newton fails at the minimum step, or when it
    fails on so many steps in a row that the run would crawl (`results.NewtonStallWatch`).
    """
    settings = settings or HHTSettings()
    check_problem(problem)
    n = problem.n_dof
    solver = linear_solver if linear_solver is not None else DenseSolver()
    on_step = on_step if on_step is not None else getattr(problem, "on_accepted_step", None)
    stats = SolverStats()
    wall0 = time.perf_counter()
    stepper = HHTStepper(problem, settings, solver, stats)
    stall = NewtonStallWatch(settings.alpha, settings.max_newton_iter)
    if hasattr(problem, "error_scales"):
        stepper.set_error_scales(checked_error_scales(problem, t0, q0, v0))
    y = HHTState(n)
    y.q[:] = q0
    y.v[:] = v0
    if a0 is None:
        y.a[:], y.g[:] = initial_acceleration(problem, solver, t0, y.q, y.v)
        stats.factorizations += 1
        stats.residual_evaluations += 1
    else:
        y.a[:] = a0
        problem.evaluate(t0, y.q, y.v, y.a, np.zeros(n), y.g)
        stats.residual_evaluations += 1
    if sampler is not None:
        sampler.start(t0, y.q, y.v, y.a)
    t, h = t0, settings.first_step
    n_fixed = max(1, int(round((t1 - t0) / h))) if not settings.adaptive else 0
    while t < t1 and (settings.adaptive or stats.steps < n_fixed):
        if settings.adaptive:
            if t + LAST_STEP_STRETCH * h >= t1:  # land on t1 without leaving a sliver of a step
                h = t1 - t
        else:
            h = (t1 - t0) / n_fixed
        y1, err, result = stepper.step(t, h, y)
        if result is not Result.SUCCESSFUL:
            stats.rejected_steps += 1
            stats.newton_failures += 1
            if not settings.adaptive or h <= settings.min_step * AT_MIN_STEP:
                stats.wall_time = time.perf_counter() - wall0
                where = "at the minimum step" if settings.adaptive else "at the fixed step"
                raise IntegrationError(t, h, f"{result.value} {where}", damping_first(result.hint, settings.alpha))
            h = max(h * settings.newton_failure_factor, settings.min_step)
            continue
        if settings.adaptive and err > 1.0:
            if h > settings.min_step * AT_MIN_STEP:
                stats.rejected_steps += 1
                h = next_step(h, err, settings)
                continue
            stats.min_step_accepts += 1
        if sampler is not None:
            sampler.observe(t, h, y, y1, stepper.rotation_slots)
        t = t0 + (stats.steps + 1) * h if not settings.adaptive else t + h
        stepper.accepted(y, y1, h)
        y, stepper.y1 = y1, y  # swap buffers: no copies
        stats.steps += 1
        if stats.steps % NewtonStallWatch.WINDOW == 0:
            stall.check(t, h, stats.steps, stats.newton_failures)
        if on_step is not None:
            on_step(t, y.q, y.v, y.a)
        if settings.adaptive:
            h = next_step(h, err, settings)
    stats.wall_time = time.perf_counter() - wall0
    return Solution(t=t, q=y.q.copy(), v=y.v.copy(), a=y.a.copy(),
                    h_next=h if math.isfinite(h) else settings.first_step, stats=stats)
