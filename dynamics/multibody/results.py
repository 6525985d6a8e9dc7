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
        "lower solver.min_step, or check the model's tangents (K_t = dr/dq, C_t = dr/dv) "
        "against finite differences; use reuse_jacobian='newton' to rule out a stale matrix"),
    Result.NEWTON_MAX_ITER: (
        "raise solver.max_newton_iter or solver.newton_tol, lower solver.min_step, or "
        "improve the tangents"),
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
