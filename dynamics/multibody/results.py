"""Step results, solver counters and the error raised when the integrator gives up."""

from __future__ import annotations

import enum
from dataclasses import asdict, dataclass, field

import numpy as np


class Result(enum.Enum):
    """Outcome of one attempted step; `.hint` says what to try when it is a failure."""

    SUCCESSFUL = "successful"
    NEWTON_DIVERGED = "Newton iteration diverged"
    NEWTON_MAX_ITER = "Newton did not converge within max_newton_iter iterations"
    NAN_RESIDUAL = "residual is NaN or infinite"
    SINGULAR_MATRIX = "iteration matrix is singular"

    @property
    def hint(self) -> str:
        return _HINTS[self]


_HINTS = {
    Result.SUCCESSFUL: "",
    Result.NEWTON_DIVERGED: (
        "lower solver.first_step and solver.min_step, or check the model's tangents (K_t = dr/dq, C_t = dr/dv) "
        "against finite differences; use reuse_jacobian='newton' to rule out a stale matrix"),
    Result.NEWTON_MAX_ITER: (
        "raise solver.max_newton_iter or solver.newton_tol, lower solver.first_step and "
        "solver.min_step, or improve the tangents"),
    Result.NAN_RESIDUAL: (
        "a force produced NaN/inf: check the initial state (penetrations, zero film "
        "thickness, division by a zero speed) and lower solver.first_step"),
    Result.SINGULAR_MATRIX: (
        "a coordinate has no mass and no stiffness (a free dummy coordinate?) or the "
        "tangent has NaN; give every coordinate a mass or a prescribed row"),
}


class IntegrationError(RuntimeError):
    """The integrator gave up: names the time, the reason and what to try."""

    def __init__(self, t: float, h: float, reason: str, hint: str) -> None:
        self.t, self.h, self.reason, self.hint = t, h, reason, hint
        super().__init__(f"integration stopped at t = {t:.9g} s (step {h:.3g} s): {reason}. "
                         f"Try: {hint}.")


def _more_damping(alpha: float) -> str:
    """The advice both failures of an undamped run lead with (`damping_first`, `NewtonStallWatch`)."""
    return f"solver.alpha between 0.05 and 0.333333 (it is {alpha:g}"


def damping_first(hint: str, alpha: float) -> str:
    """What to try after Newton failed at the smallest step: with alpha = 0 (HHT-α as the
    trapezoidal rule) a stiff contact's highest frequencies are not damped at all, and more
    numerical damping comes before the rest of `hint`."""
    if alpha > 0.0:
        return hint
    return f"more numerical damping first: {_more_damping(alpha)}); then {hint}"


class NewtonStallWatch:
    """Stops a run whose step control has locked into a cycle of Newton failures.

    With too little numerical damping for a stiff contact (HHT-α with `alpha` = 0 in case b while
    the cage rubs its land in the start-up; docs/performance.md), Newton fails at a
    step h, succeeds at h/4, the controller grows the step back to h, and so on: one failure
    every other accepted step (steps of 12–47 ns in one run: 0.8 s would take hours). `check` is
    called with the running counters every WINDOW accepted steps or more; when the failures
    were at least RATIO of the accepted steps in each of WINDOWS windows in a row, it raises
    IntegrationError naming the time, the step and what to try. Runs that converge have far
    fewer: ≤ 0.1 failures per accepted step even in the worst 1000-step bursts measured
    (docs/model.md §9), against 0.5 in the cycle.
    """

    WINDOW, RATIO, WINDOWS = 1000, 0.4, 5

    def __init__(self, alpha: float, max_newton_iter: int | None = None) -> None:
        self.alpha, self.max_newton_iter = alpha, max_newton_iter
        self.steps = self.failures = self.in_a_row = 0

    def hint(self) -> str:
        """What to try: damping where there is too little (below the 0.05 that takes case b
        through its start-up), else more Newton iterations before a step is rejected, then damping."""
        if self.alpha < 0.05:
            return (f"more numerical damping: {_more_damping(self.alpha)}); 0.05 and the default 0.1 take "
                    f"case b through the start-up, where alpha = 0 cycles")
        iterations = f" (it is {self.max_newton_iter})" if self.max_newton_iter is not None else ""
        return (f"more Newton iterations before a step is rejected: a larger solver.max_newton_iter{iterations}; "
                f"or more numerical damping: {_more_damping(self.alpha)})")

    def check(self, t: float, h: float, steps: int, failures: int) -> None:
        if steps - self.steps < self.WINDOW:
            return
        ratio = (failures - self.failures) / (steps - self.steps)
        self.steps, self.failures = steps, failures
        self.in_a_row = self.in_a_row + 1 if ratio >= self.RATIO else 0
        if self.in_a_row >= self.WINDOWS:
            raise IntegrationError(
                t, h, f"Newton failed on {ratio:.0%} of the last {self.WINDOW} accepted steps, and on at least "
                      f"{self.RATIO:.0%} for {self.WINDOWS * self.WINDOW} steps: the step control is cycling between "
                      f"a failing step and a quarter of it",
                self.hint())


@dataclass
class SolverStats:
    """Counters of one integration (docs/model.md §9 asks for all of them)."""

    steps: int = 0
    rejected_steps: int = 0
    newton_failures: int = 0
    newton_iterations: int = 0
    factorizations: int = 0
    residual_evaluations: int = 0
    min_step_accepts: int = 0  # steps accepted at min_step although the error test failed
    wall_time: float = 0.0

    def as_dict(self) -> dict:
        return asdict(self)


@dataclass
class Solution:
    """Final state and counters; sampled series live in the sampler passed to integrate."""

    t: float
    q: np.ndarray
    v: np.ndarray
    a: np.ndarray
    h_next: float
    stats: SolverStats = field(default_factory=SolverStats)
