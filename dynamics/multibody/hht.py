"""One HHT-α step with Newton iterations (docs/model.md §9; Hilber, Hughes & Taylor, Earthq. Eng.
Struct. Dyn. 5 (1977) 283–292, in the paper's sign convention alpha in [0, 1/3]).

    M(q_{n+1}) a_{n+1} - (1 - alpha) g(t_{n+1}, q_{n+1}, v_{n+1}) - alpha g_n = 0
    dq      = h v_n + h^2 (1/2 - beta) a_n + h^2 beta a_{n+1},   q_{n+1} = q_n (+) dq
    v_{n+1} = v_n + h (1 - gamma) a_n + h gamma a_{n+1}
    gamma = 1/2 + alpha,  beta = (1 + alpha)^2 / 4

`(+)` is additive except on CRV triples (multiplicative, `crv.update_configuration`).
g_n is the force of the previous accepted step (not re-evaluated). After the Newton
correction test passes, q and v are updated to the final a_{n+1}; g_{n+1} is kept from the
last evaluation (it differs by less than the Newton tolerance).
"""

from __future__ import annotations

import math

import numba
import numpy as np

from .._speed.compile_policy import KERNEL

from .crv import update_configuration
from .newton import IterationMatrix
from .results import Result, SolverStats
from .settings import HHTSettings, JacobianReuse
from .step_control import MACHINE_EPSILON, NEWTON_FLOOR, scaled_difference_norm


@numba.njit(**KERNEL)
def newmark_kinematics(q_n, v_n, a_n, a1, h, beta, gamma, rotation_slots, dq, q1, v1):
    """Newmark increment dq, q_{n+1} = q_n (+) dq and v_{n+1} (module docstring), in place."""
    c_a = h * h * (0.5 - beta)
    c_b = h * h * beta
    c_v0 = h * (1.0 - gamma)
    c_v1 = h * gamma
    for i in range(q_n.shape[0]):
        dq[i] = h * v_n[i] + c_a * a_n[i] + c_b * a1[i]
        v1[i] = v_n[i] + c_v0 * a_n[i] + c_v1 * a1[i]
    update_configuration(q_n, dq, rotation_slots, q1)


@numba.njit(**KERNEL)
def hht_residual(ma, g1, g_n, alpha, r):
    """r = M a_{n+1} - (1 - alpha) g_{n+1} - alpha g_n [N, N m]; returns max |r| (inf if NaN)."""
    big = 0.0
    for i in range(ma.shape[0]):
        r[i] = ma[i] - (1.0 - alpha) * g1[i] - alpha * g_n[i]
        ar = abs(r[i])
        if not ar <= big:  # also catches NaN
            big = ar if math.isfinite(ar) else math.inf
        if big == math.inf:
            return big
    return big


@numba.njit(**KERNEL)
def predict_acceleration(a_n, da_prev, ratio, linear, out):
    """Newton's start for a_{n+1}: a_n, or (linear) a_n + (h / h_prev)(a_n - a_{n-1}), the
    extrapolation of the last step's change; it starts Newton O(h) closer on smooth motion."""
    c = ratio if linear else 0.0
    for i in range(a_n.shape[0]):
        out[i] = a_n[i] + c * da_prev[i]


@numba.njit(**KERNEL)
def subtract_inplace(x, dx):
    for i in range(x.shape[0]):
        x[i] -= dx[i]


NEWTON_CONTINUE, NEWTON_CONVERGED, NEWTON_DIVERGED = 0, 1, 2


@numba.njit(**KERNEL)
def newton_verdict(k, corr, corr_prev, eta, estimate_test, newton_tol, floor, fresh, full_newton, refactor_rate):
    """Decision after Newton correction k (0-based) of scaled size corr (the previous one
    corr_prev, inf at k = 0): returns (NEWTON_*, updated contraction estimate eta, rebuild the
    matrix before the next iteration). docs/model.md M.102."""
    rate = corr / corr_prev
    if k > 0 and rate < 1.0:
        eta = rate / (1.0 - rate)
    remaining = corr
    if estimate_test:
        # remaining error of a contracting iteration, eta |da_k| (Hairer & Wanner, Solving
        # ODE II, §IV.8, eq. 8.10); the first iteration borrows the last step's rate
        # (raised to 0.8, as there), and only for a correction already within tolerance
        if k > 0:
            remaining = corr * eta if rate < 1.0 else corr
        elif corr <= 1.0:
            remaining = corr * max(eta, 1e-16) ** 0.8
    if remaining <= newton_tol or corr <= floor:
        return NEWTON_CONVERGED, eta, False
    # Divergence: a fresh matrix that does not contract a correction larger than the error
    # tolerance. Below it, a non-contracting iterate is already as accurate as the step
    # is allowed to be; it gets its remaining iterations (a correction of the prescribed
    # spin row can make the second correction larger than the first, then Newton converges
    # quadratically: case b at t = 0.313 s, h = 1e-8 s, corrections 0.005, 0.012, 7e-8).
    if rate >= 1.0 and fresh and not full_newton and corr > 1.0:
        return NEWTON_DIVERGED, eta, False
    # An old matrix that converges slowly (or diverges) is rebuilt at the next iterate.
    return NEWTON_CONTINUE, eta, full_newton or (not fresh and rate > refactor_rate)


class HHTState:
    """State at one time: q (config), v, a, g = g(t, q, v) and the increment dq that led here."""

    __slots__ = ("q", "v", "a", "g", "dq")

    def __init__(self, n: int) -> None:
        self.q, self.v, self.a = np.zeros(n), np.zeros(n), np.zeros(n)
        self.g, self.dq = np.zeros(n), np.zeros(n)

    def copy_from(self, other: "HHTState") -> None:
        for name in self.__slots__:
            getattr(self, name)[:] = getattr(other, name)


class HHTStepper:
    """Attempts steps of HHT-α on a problem following `problem.MultibodyProblem`."""

    def __init__(self, problem, settings: HHTSettings, solver, stats: SolverStats) -> None:
        n = problem.n_dof
        self.problem, self.settings, self.stats = problem, settings, stats
        self.matrix = IterationMatrix(problem, solver, settings, stats)
        self.rotation_slots = np.ascontiguousarray(problem.rotation_slots, dtype=np.int64)
        self.weights = np.ascontiguousarray(problem.error_weights, dtype=float)
        self.scales = np.zeros(0)  # physical error scales (set_error_scales); empty: scale by |q|
        self._use_max = settings.error_norm == "max"
        self.y1 = HHTState(n)
        self._ma, self._r, self._da = np.zeros(n), np.zeros(n), np.zeros(n)
        self._zeros = np.zeros(n)
        # last accepted step's acceleration change (a_n - a_{n-1}) and size: the linear predictor
        self._da_prev = np.zeros(n)
        self._h_prev = 0.0
        # Newton contraction rate of the last converged step (Hairer & Wanner's eta test)
        self._eta = 1.0

    def set_error_scales(self, scales) -> None:
        """Scale each coordinate's error by its physical scale L_i (step_control, M.99)."""
        self.scales = np.ascontiguousarray(scales, dtype=float)

    def _norm(self, x, y, coef, q_a, q_b) -> float:
        s = self.settings
        return scaled_difference_norm(x, y, coef, q_a, q_b, self.weights, self.scales, s.atol, s.rtol,
                                      self._use_max)

    def accepted(self, y_old: HHTState, y_new: HHTState, h: float) -> None:
        """Called by the time loop after a step from y_old to y_new of size h is accepted."""
        np.subtract(y_new.a, y_old.a, out=self._da_prev)
        self._h_prev = h

    def step(self, t: float, h: float, y: HHTState) -> tuple[HHTState, float, Result]:
        """Try a step from (t, y) of size h: returns (y1, error norm, result).

        y1 is a workspace reused by the next call: copy it or swap it in before stepping
        again. The error norm is `step_control.scaled_difference_norm` of the error estimate e (M.99).
        """
        s, y1 = self.settings, self.y1
        beta, gamma = s.beta, s.gamma
        t1 = t + h
        predict_acceleration(y.a, self._da_prev, h / self._h_prev if self._h_prev > 0.0 else 0.0,
                             s.predictor == "linear", y1.a)
        fresh = False
        if self.matrix.needs_factor_at_step_start(h):
            newmark_kinematics(y.q, y.v, y.a, y1.a, h, beta, gamma, self.rotation_slots,
                               y1.dq, y1.q, y1.v)
            if not self.matrix.factor(t1, y1.q, y1.v, y1.a, h):
                return y1, math.inf, Result.SINGULAR_MATRIX
            fresh = True
        result = self._newton(t1, h, y, fresh)
        if result is not Result.SUCCESSFUL:
            self.matrix.stale = True
            return y1, math.inf, result
        err = self._norm(y1.a, y.a, (beta - 1.0 / 6.0) * h * h, y.q, y1.q)
        return y1, err, Result.SUCCESSFUL

    def _newton(self, t1: float, h: float, y: HHTState, fresh: bool) -> Result:
        """Newton on a_{n+1}; `fresh` says the factored matrix was built in this step."""
        s, y1, st = self.settings, self.y1, self.stats
        ma, r, da = self._ma, self._r, self._da
        alpha, beta, gamma = s.alpha, s.beta, s.gamma
        full_newton = s.reuse_jacobian is JacobianReuse.NEWTON
        estimate_test = s.newton_test == "estimate"
        rebuild = False
        corr_prev = math.inf
        # Corrections below the round-off of q cannot shrink further: count them as converged.
        floor = NEWTON_FLOOR * self._norm(y.q, self._zeros, MACHINE_EPSILON, y.q, y.q)
        for k in range(s.max_newton_iter):
            newmark_kinematics(y.q, y.v, y.a, y1.a, h, beta, gamma, self.rotation_slots,
                               y1.dq, y1.q, y1.v)
            self.problem.evaluate(t1, y1.q, y1.v, y1.a, ma, y1.g)
            st.residual_evaluations += 1
            r_max = hht_residual(ma, y1.g, y.g, alpha, r)
            if r_max == math.inf:
                return Result.NAN_RESIDUAL
            if k > 0 and r_max <= s.residual_tol:
                return Result.SUCCESSFUL
            if rebuild:
                if not self.matrix.factor(t1, y1.q, y1.v, y1.a, h):
                    return Result.SINGULAR_MATRIX
                fresh, rebuild = True, False
            self.matrix.solve(r, da)
            subtract_inplace(y1.a, da)
            st.newton_iterations += 1
            corr = self._norm(da, self._zeros, beta * h * h, y.q, y1.q)
            verdict, self._eta, rebuild = newton_verdict(k, corr, corr_prev, self._eta, estimate_test, s.newton_tol,
                                                         floor, fresh, full_newton, s.refactor_rate)
            if verdict == NEWTON_CONVERGED:
                newmark_kinematics(y.q, y.v, y.a, y1.a, h, beta, gamma, self.rotation_slots,
                                   y1.dq, y1.q, y1.v)
                return Result.SUCCESSFUL
            if verdict == NEWTON_DIVERGED:
                return Result.NEWTON_DIVERGED
            corr_prev = corr
        return Result.NEWTON_MAX_ITER
