"""Newton iteration matrix of HHT-α and the policy for reusing its factorisation (docs/model.md §9).

Unknown of a step: a_{n+1}. With the Newmark updates, dq/da = beta h^2 and dv/da = gamma h,
so the exact Jacobian of r = M a - (1 - alpha) g_{n+1} - alpha g_n is

    S = M + (1 - alpha) (gamma h C_t + beta h^2 K_t)       (paper eq. 9)

(for a q-dependent M its derivative is folded into K_t by the model, also scaled by
(1 - alpha): an approximation that only slows Newton). Rotation increments are composed
multiplicatively; the tangent operator of that composition is taken as the identity, an
O(|dTheta|) approximation of the Jacobian (dTheta ~ 3e-4 rad per step for the cage).
"""

from __future__ import annotations

import numba

from .._speed.compile_policy import KERNEL

from .results import SolverStats
from .settings import HHTSettings, JacobianReuse


@numba.njit(**KERNEL)
def needs_refactor(stale, h_factored, h, keep_across_steps, refactor_step_ratio):
    """Whether a step of size h starts with a fresh matrix: none is factored (or it is stale),
    the policy rebuilds every step (`keep_across_steps` false), or the step changed by more
    than `refactor_step_ratio` since the factorisation."""
    if stale or h_factored == 0.0 or not keep_across_steps:
        return True
    ratio = h / h_factored
    return not (1.0 / refactor_step_ratio <= ratio <= refactor_step_ratio)


class IterationMatrix:
    """Builds S through the model, factors it with the linear solver, decides on reuse."""

    def __init__(self, problem, solver, settings: HHTSettings, stats: SolverStats) -> None:
        self.problem, self.solver, self.settings, self.stats = problem, solver, settings, stats
        self.h_factored = 0.0  # step the current factorisation was built with; 0 = none
        self.stale = True      # force a rebuild at the next opportunity

    def coefficients(self, h: float) -> tuple[float, float, float]:
        """(c_m, c_v, c_q) of S = c_m M + c_v C_t + c_q K_t for step h [s]."""
        s = self.settings
        return 1.0, (1.0 - s.alpha) * s.gamma * h, (1.0 - s.alpha) * s.beta * h * h

    def needs_factor_at_step_start(self, h: float) -> bool:
        s = self.settings
        return needs_refactor(self.stale, self.h_factored, h, s.reuse_jacobian is JacobianReuse.ADAPTIVE,
                              s.refactor_step_ratio)

    def factor(self, t: float, q, v, a, h: float) -> bool:
        """Rebuild S at (t, q, v, a) and factor it; False if it is singular."""
        c_m, c_v, c_q = self.coefficients(h)
        matrix = self.problem.jacobian(t, q, v, a, c_m, c_v, c_q)
        self.stats.factorizations += 1
        ok = self.solver.factor(matrix)
        self.h_factored = h if ok else 0.0
        self.stale = not ok
        return ok

    def solve(self, rhs, out) -> None:
        self.solver.solve(rhs, out)
