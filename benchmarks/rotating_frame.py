"""Experiment: the balls' centres in a frame turning with the cage (docs/model.md §9, *Frame of the scales*).

    taskset -c 1 python -m benchmarks.rotating_frame [SCENE] [--out DIR]

What holds the step in the settled motion of case b is a ball's local error along its orbit,
mostly the truncation error of a circular orbit in fixed axes, (β − 1/6) h³ ω³ r. In a frame
turning at a constant rate Ω about the bearing axis (here the quasi-static cage speed), a ball
that rolls with the cage stands still and that error vanishes:

    x = T(t) ξ,  T = R_z(Ω t),  v = T (ξ' + W ξ),  W = Ω e_z~
    m ξ'' = Tᵀ F(x, v) − m (2 W ξ' + W W ξ)           (Coriolis and centrifugal terms)

The tangents follow by the chain rule (ball rows and columns turned by T, the velocity
dependence of the forces adds C T W to the stiffness, the fictitious forces add m W W and
2 m W). This script wraps `BearingModel` so (Python loop; nothing else changes: same
contacts, same error scales as at the start, where T = I) and compares it with the model as
it is, on the work-precision window (15 ms from the quasi-static start) and on 10 ms of
settled motion from t = 0.2 s, each against a fixed-step reference (h = 1e-7 s, float64
residual) on the quantities of the work-precision study. A third variant ("turning,
isotropic") measures each ball's in-plane error on its radial scale in both directions, which
the turning frame makes affordable. It first checks the wrapper's tangent against central
differences at a state 3.1 ms into the turning frame.

Writes DIR/rotating_frame.json (default runs/bench) and prints one line per run.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import os
import time
from pathlib import Path

import numpy as np

from bearingsim.dynamics.bearing import BearingModel, layout
from bearingsim.dynamics.bearing.run import initial_coordinates
from bearingsim.dynamics.multibody.joints import prescribe_velocity_blocks
from bearingsim.dynamics.multibody.linear_solvers import (
    BlockArrowMatrix, BlockArrowSolver, assemble_iteration_blocks,
)
from bearingsim.pipeline.studies import wp_metrics as wm
from bearingsim.pipeline.studies.instrumented import bearing_window, fd_tangent, run_window
from bearingsim.pipeline.studies.work_precision import ADAPTIVE_DEFAULT as ADAPTIVE

REFERENCE_STEP = 1e-7  # s, as the work-precision study
SAMPLE = 5e-6  # s


def rot_z(phi: float) -> np.ndarray:
    c, s = np.cos(phi), np.sin(phi)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


class TurningBalls:
    """`BearingModel` with the balls' centres in a frame turning at `omega` [rad/s] about z
    (a `MultibodyProblem`, Python loop only); every other coordinate is unchanged."""

    def __init__(self, model: BearingModel, omega: float, isotropic: bool = False):
        self.model, self.omega, self.isotropic = model, float(omega), isotropic
        self.Z = model.params.ball_count
        self.n_dof, self.rotation_slots, self.error_weights = model.n_dof, model.rotation_slots, model.error_weights
        self.W = self.omega * np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 0.0]])
        self.m_ball = model.mass[0]
        self.S = BlockArrowMatrix.zeros(self.Z, layout.BALL_DOF, model.nb)
        self._q, self._v = np.zeros(self.n_dof), np.zeros(self.n_dof)

    def to_inertial(self, t, q, v, q_out, v_out) -> np.ndarray:
        """Fixed-axis state of the turning-frame state (q, v) at t; returns T(t)."""
        T = rot_z(self.omega * t)
        q_out[:], v_out[:] = q, v
        xi, dxi = layout.ball_states(q, self.Z)[:, :3], layout.ball_states(v, self.Z)[:, :3]
        layout.ball_states(q_out, self.Z)[:, :3] = xi @ T.T
        layout.ball_states(v_out, self.Z)[:, :3] = (dxi + xi @ self.W.T) @ T.T
        return T

    def from_inertial(self, t, q, v) -> tuple[np.ndarray, np.ndarray]:
        T = rot_z(self.omega * t)
        qo, vo = q.copy(), v.copy()
        xi = layout.ball_states(q, self.Z)[:, :3] @ T
        layout.ball_states(qo, self.Z)[:, :3] = xi
        layout.ball_states(vo, self.Z)[:, :3] = layout.ball_states(v, self.Z)[:, :3] @ T - xi @ self.W.T
        return qo, vo

    def evaluate(self, t, q, v, a, ma_out, g_out) -> None:
        T = self.to_inertial(t, q, v, self._q, self._v)
        self.model.evaluate(t, self._q, self._v, a, ma_out, g_out)
        gb = layout.ball_states(g_out, self.Z)
        gb[:, :3] = gb[:, :3] @ T  # T^T F, ball by ball
        xi, dxi = layout.ball_states(q, self.Z)[:, :3], layout.ball_states(v, self.Z)[:, :3]
        gb[:, :3] -= self.m_ball * (2.0 * dxi @ self.W.T + xi @ (self.W @ self.W).T)

    def jacobian(self, t, q, v, a, c_m, c_v, c_q):
        T = self.to_inertial(t, q, v, self._q, self._v)
        m = self.model
        m._kernel(t, self._q, self._v, a, m._ma, m._g, True)
        K, C = m._blocks
        P, Q = np.eye(6), np.zeros((6, 6))
        P[:3, :3], Q[:3, :3] = T, T @ self.W
        KD = np.einsum("ji,kjl,lm->kim", P, K.D, P) + np.einsum("ji,kjl,lm->kim", P, C.D, Q)
        CD = np.einsum("ji,kjl,lm->kim", P, C.D, P)
        KD[:, :3, :3] += self.m_ball * (self.W @ self.W)
        CD[:, :3, :3] += 2.0 * self.m_ball * self.W
        Kt = BlockArrowMatrix(KD, np.einsum("ji,kjl->kil", P, K.E),
                              np.einsum("kil,lm->kim", K.F, P) + np.einsum("kil,lm->kim", C.F, Q), K.B.copy())
        Ct = BlockArrowMatrix(CD, np.einsum("ji,kjl->kil", P, C.E), np.einsum("kil,lm->kim", C.F, P), C.B.copy())
        S = self.S.blocks()
        assemble_iteration_blocks(Kt.blocks(), Ct.blocks(), m.mass, c_m, c_v, c_q, S)
        prescribe_velocity_blocks(S, layout.spin_row(self.Z), c_m, c_v, 1.0)
        return self.S

    def error_scales(self, t0, q0, v0):
        qi, vi = np.zeros(self.n_dof), np.zeros(self.n_dof)
        self.to_inertial(t0, q0, v0, qi, vi)
        scales = self.model.error_scales(t0, qi, vi)
        if self.isotropic:  # each ball's in-plane error on its radial (tighter) scale, both directions
            balls = layout.ball_states(scales, self.Z)
            balls[:, :2] = np.min(balls[:, :2], axis=1)[:, None]
        return scales

    def on_accepted_step(self, t, q, v, a) -> None:
        self.model.on_accepted_step(t, q, v, a)


class _PythonLoop:
    """The model as it is, without its compiled side: both variants step in the same loop."""

    def __init__(self, model):
        for k in ("n_dof", "rotation_slots", "error_weights", "evaluate", "jacobian", "error_scales",
                  "on_accepted_step"):
            setattr(self, k, getattr(model, k))


def tangent_check(params, start, omega: float, t: float = 3.1e-3) -> dict:
    """Largest entry of |analytic − central difference| per block over the largest entry of the
    difference tangent, stiffness (c_q = 1) and damping (c_v = 1), fixed axes and turning frame,
    at the start state seen at time t (the turning frame's T(t) is then a 26° turn)."""
    model = BearingModel(params)
    turning = TurningBalls(model, omega)
    q0, v0 = initial_coordinates(params, start)
    xi, dxi = turning.from_inertial(t, q0, v0)
    a = np.zeros(model.n_dof)
    out = {}
    for label, problem, q, v in (("fixed axes", model, q0, v0), ("turning", turning, xi, dxi)):
        for name, c in (("K", (0.0, 0.0, 1.0)), ("C", (0.0, 1.0, 0.0))):
            S = problem.jacobian(t, q, v, a, *c)
            analytic = [x.copy() for x in (S.D, S.E, S.F, S.B)]
            fd = fd_tangent(problem, t, q, v, a, *c, template=BlockArrowMatrix.zeros(params.ball_count, 6, model.nb))
            out[f"{label} {name}"] = max(float(np.max(np.abs(x - y)) / np.max(np.abs(y)))
                                         for x, y in zip(analytic, (fd.D, fd.E, fd.F, fd.B)))
    return out


def compare(params, start, base, omega, q0, v0, window, rtols, fixed_steps=()) -> list[dict]:
    """Both variants from (q0, v0) over `window` against a fixed-step reference."""
    ref_settings = dataclasses.replace(base, adaptive=False, first_step=REFERENCE_STEP, max_step=REFERENCE_STEP,
                                       min_step=min(REFERENCE_STEP, base.min_step))
    ref_run, _ = bearing_window(params, start, ref_settings, window, SAMPLE, float32_residual=False, q0=q0, v0=v0)
    ref = wm.reference_data(params, ref_run.t, ref_run.q, ref_run.v)
    p32 = params.with_float32_residual(True)
    cases = [("rtol", r) for r in rtols] + [("fixed h", h) for h in fixed_steps]
    rows = []
    for kind, x in cases:
        if kind == "rtol":
            settings = dataclasses.replace(base, **{**ADAPTIVE, "rtol": x})
        else:
            settings = dataclasses.replace(base, **{**ADAPTIVE, "adaptive": False, "first_step": x,
                                                    "max_step": x, "min_step": min(x, 1e-8)})
        for frame in ("fixed axes", "turning", "turning, isotropic"):
            model = BearingModel(p32)
            solver = BlockArrowSolver(params.ball_count, 6, model.nb)
            t0 = time.perf_counter()
            if frame == "fixed axes":
                run, _ = run_window(_PythonLoop(model), q0, v0, settings, window, SAMPLE, linear_solver=solver)
                q, v = run.q, run.v
            else:
                turning = TurningBalls(model, omega, isotropic=frame.endswith("isotropic"))
                xi, dxi = turning.from_inertial(0.0, q0, v0)
                run, _ = run_window(turning, xi, dxi, settings, window, SAMPLE, linear_solver=solver)
                q, v = np.full_like(run.q, np.nan), np.full_like(run.v, np.nan)
                for j, t in enumerate(run.t):
                    if np.all(np.isfinite(run.q[j])):
                        turning.to_inertial(t, run.q[j], run.v[j], q[j], v[j])
            wall = time.perf_counter() - t0
            errors = wm.run_errors(params, run.t, q, v, ref) if run.error is None else {}
            s = run.stats
            row = {"frame": frame, kind: x, "wall": wall, "error_text": run.error, "steps": s.get("steps"),
                   "newton_iterations": s.get("newton_iterations"), "rejected": s.get("rejected_steps"),
                   **{k: errors.get(k) for k in wm.QUANTITIES}}
            rows.append(row)
            print(json.dumps(row), flush=True)
    return rows


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("scene", nargs="?", default="helicopter-b-given-hinge")
    ap.add_argument("--out", type=Path, default=Path("runs/bench"))
    args = ap.parse_args(argv)
    from bearingsim.pipeline.scene import load_scene
    from bearingsim.pipeline.stages.simulate import build_model

    scene = load_scene(args.scene, [])
    params, start = build_model(scene, None)
    base = scene.solver
    omega = float(start["cage_angular_speed"])
    print(f"{args.scene}: turning frame at the quasi-static cage speed {omega:.2f} rad/s", flush=True)
    check = tangent_check(params, start, omega)
    print("tangent vs central differences (largest block error / largest entry):", json.dumps(check), flush=True)
    q0, v0 = initial_coordinates(params, start)
    print("start-up window, 15 ms from the quasi-static start", flush=True)
    startup = compare(params, start, base, omega, q0, v0, 0.015, (1e-6, 3e-7, 1e-7), (1e-6, 2e-6))
    pre, _ = bearing_window(params, start, dataclasses.replace(base, **ADAPTIVE), 0.2005, 1e-3)
    i = int(np.argmin(np.abs(pre.t - 0.2)))
    print(f"settled motion, 10 ms from t = {pre.t[i]:.4f} s (the scene default's state there)", flush=True)
    settled = compare(params, start, base, omega, pre.q[i].copy(), pre.v[i].copy(), 0.01, (1e-6, 3e-7))
    args.out.mkdir(parents=True, exist_ok=True)
    out = {"scene": args.scene, "omega": omega, "tangent_check": check, "startup_15ms": startup,
           "settled_10ms_from_0.2s": settled, "load_average": os.getloadavg()[0]}
    (args.out / "rotating_frame.json").write_text(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
