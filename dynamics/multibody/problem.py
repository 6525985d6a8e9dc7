"""The residual protocol between a model and the integrator (docs/contributing.md rule 1).

A model (pendulum, rigid body, bearing) is any object with these members; the integrator
knows nothing else about it.

Coordinates. Three arrays of the same length n = `n_dof`: configuration q, velocity v and
acceleration a. Every coordinate is additive (v = dq/dt) except the CRV triples whose first
index is listed in `rotation_slots`: there q holds a CRV c (M.4a, |c| <= 4), v the material
angular velocity Omega [rad/s] and a its rate; the integrator updates them multiplicatively,
R(c_{n+1}) = R(c_n) R(crv(dTheta)), dTheta = Newmark increment (crv.update_configuration).
A coordinate whose configuration never enters a force (a ball's rotation) is an ordinary
additive slot carrying the integral of its velocity; give it error weight 0.

Members:

    n_dof: int
    rotation_slots: int64 array (k,)  start index of each CRV triple (may be empty)
    error_weights: float array (n,)  >= 0; converts coordinate i into the unit of atol
        (1 for m; a radius in m/rad for a rotation); 0 excludes it from error control
    evaluate(t, q, v, a, ma_out, g_out) -> None
        fills ma_out = M(q) a and g_out = g(t, q, v) (external, internal, complementary
        inertia forces, paper eq. 8) [N, N m]; for rotation slots, moments are material.
    jacobian(t, q, v, a, c_m, c_v, c_q) -> matrix
        returns S = c_m M + c_v C_t + c_q K_t, K_t = d(M a - g)/dq (material rotation
        perturbations), C_t = -dg/dv, in the structure the linear solver accepts (a dense
        (n, n) array for DenseSolver, a BlockArrowMatrix for BlockArrowSolver). The model
        may return the same buffers every call (the solver copies what it keeps).
        Approximate tangents are allowed: they only cost Newton iterations.

Optional:

    on_accepted_step(t, q, v, a) -> None   called after every accepted step (impact logs)
    error_scales(t0, q0, v0) -> float array (n,)  > 0 where w_i > 0: the physical scale of each
        weighted coordinate in the unit of atol, from the initial state; the step controller
        then holds each local error below atol + rtol L_i (step_control.py). Without it the
        relative part scales with |q|, which is meaningless for coordinates far from 0.

Residual of one HHT step: r = M a_{n+1} - (1 - alpha) g_{n+1} - alpha g_n (hht.py).
"""

from __future__ import annotations

from typing import Any, Protocol, runtime_checkable

import numpy as np


@runtime_checkable
class MultibodyProblem(Protocol):
    n_dof: int
    rotation_slots: np.ndarray
    error_weights: np.ndarray

    def evaluate(self, t: float, q: np.ndarray, v: np.ndarray, a: np.ndarray,
                 ma_out: np.ndarray, g_out: np.ndarray) -> None: ...

    def jacobian(self, t: float, q: np.ndarray, v: np.ndarray, a: np.ndarray,
                 c_m: float, c_v: float, c_q: float) -> Any: ...


def check_problem(problem: Any) -> None:
    """Raise a clear error when a model does not follow the protocol."""
    missing = [m for m in ("n_dof", "rotation_slots", "error_weights", "evaluate", "jacobian")
               if not hasattr(problem, m)]
    if missing:
        raise TypeError(f"{type(problem).__name__} is not a MultibodyProblem: it lacks "
                        f"{', '.join(missing)} (see dynamics/multibody/problem.py)")
    n = int(problem.n_dof)
    w = np.asarray(problem.error_weights)
    if w.shape != (n,) or np.any(~np.isfinite(w)) or np.any(w < 0.0):
        raise ValueError(f"{type(problem).__name__}.error_weights must be {n} finite values "
                         f">= 0, got shape {w.shape}")
    if not np.any(w > 0.0):
        raise ValueError(f"{type(problem).__name__}.error_weights are all zero: the step "
                         "controller would see no error; weight at least the positions")
    slots = np.asarray(problem.rotation_slots)
    if slots.ndim != 1 or np.any(slots < 0) or np.any(slots + 3 > n):
        raise ValueError(f"{type(problem).__name__}.rotation_slots {slots!r} must be start "
                         f"indices of CRV triples inside 0..{n - 1}")


def checked_error_scales(problem: Any, t0: float, q0, v0) -> np.ndarray:
    """problem.error_scales(t0, q0, v0), checked: finite and > 0 on every weighted coordinate."""
    n = int(problem.n_dof)
    scales = np.asarray(problem.error_scales(t0, np.asarray(q0, dtype=float), np.asarray(v0, dtype=float)),
                        dtype=float)
    w = np.asarray(problem.error_weights)
    if scales.shape != (n,) or np.any(~np.isfinite(scales[w > 0])) or np.any(scales[w > 0] <= 0.0):
        raise ValueError(f"{type(problem).__name__}.error_scales must return {n} finite values > 0 on "
                         f"the weighted coordinates, got shape {scales.shape}")
    return scales
