"""Machinery of the work-precision study: finite-difference tangents, the
instrumented window runner, error metrics and the observed order of HHT-alpha."""

from __future__ import annotations

import math

import numpy as np
import pytest

from bearingsim.dynamics.multibody import HHTSettings
from bearingsim.dynamics.multibody.linear_solvers import BlockArrowMatrix, BlockArrowSolver
from bearingsim.dynamics.multibody.example_problems import ArrowSprings, Pendulum, RigidBody
from bearingsim.dynamics.multibody.hinge import HingeStiffness
from bearingsim.pipeline.studies import wp_metrics as wm
from bearingsim.pipeline.studies.instrumented import fd_tangent, run_window
from bearingsim.pipeline.studies.work_precision import markdown_table, method_grid


def _state(n, rng, scale=1e-3):
    return rng.normal(scale=scale, size=n), rng.normal(scale=0.1, size=n), rng.normal(size=n)


@pytest.mark.parametrize("structure", ["dense", "block"])
def test_fd_tangent_matches_the_exact_tangent_of_hardening_springs(structure):
    """ArrowSprings' analytic tangent is exact ((k + k3 |d|^2) I + 2 k3 d d^T, models.py):
    two independent methods must agree to the truncation error of central differences."""
    rng = np.random.default_rng(3)
    model = ArrowSprings(4, structure=structure)
    q, v, a = _state(model.n_dof, rng)
    c_m, c_v, c_q = 1.0, 1.1e-6, 3e-12
    exact = model.jacobian(0.0, q, v, a, c_m, c_v, c_q)
    exact = exact.to_dense() if isinstance(exact, BlockArrowMatrix) else exact.copy()
    template = model.jacobian(0.0, q, v, a, c_m, c_v, c_q)
    fd = fd_tangent(model, 0.0, q, v, a, c_m, c_v, c_q, template)
    fd = fd.to_dense() if isinstance(fd, BlockArrowMatrix) else fd
    assert np.abs(fd - exact).max() <= 1e-7 * np.abs(exact).max()


def test_fd_tangent_uses_material_rotation_increments_on_crv_slots():
    """A hinged rigid body (CRV orientation, gyroscopic terms): the FD tangent with
    multiplicative rotation increments matches the model's analytic K_t and C_t
    (dynamics/multibody/example_problems.py RigidBody; hinge M.19-M.20)."""
    rng = np.random.default_rng(5)
    model = RigidBody(2.0, np.diag([0.01, 0.012, 0.02]),
                      hinge=HingeStiffness(1e7 * np.eye(3), np.array([1e4, 1e4]), 1e-5))
    q, v, a = _state(6, rng, scale=1e-2)
    exact = model.jacobian(0.0, q, v, a, 1.0, 2e-6, 1e-12).copy()
    fd = fd_tangent(model, 0.0, q, v, a, 1.0, 2e-6, 1e-12, model.jacobian(0.0, q, v, a, 1.0, 2e-6, 1e-12))
    assert np.abs(fd - exact).max() <= 1e-5 * np.abs(exact).max()


def test_run_window_samples_counts_and_observed_order_two():
    """Small-amplitude pendulum, theta = theta0 cos(w t): HHT-alpha at fixed steps is second
    order (Hilber, Hughes & Taylor, Earthq. Eng. Struct. Dyn. 5 (1977) 283, §3)."""
    w, theta0, T = 2 * math.pi, 1e-3, 2.0
    hs, errs = [], []
    for n in (200, 400, 800):
        h = T / n
        s = HHTSettings(alpha=0.1, adaptive=False, first_step=h, min_step=h / 10, max_step=h)
        run, wrapped = run_window(Pendulum(w), np.array([theta0]), np.array([0.0]), s, T, 0.01)
        assert run.completed and run.stats["steps"] == n
        assert run.history.shape == (n, 4) and np.allclose(run.history[:, 1], h)
        assert wrapped.evaluations == run.stats["residual_evaluations"]
        exact = theta0 * np.cos(w * run.t)
        hs.append(h)
        errs.append(wm.rms_vector_error(run.q[:, :1], exact[:, None]))
    assert wm.observed_order(hs, errs) == pytest.approx(2.0, abs=0.15)


def test_wall_clock_budget_stops_a_run_with_a_clear_message():
    s = HHTSettings(adaptive=False, first_step=1e-4, min_step=1e-5, max_step=1e-4)
    run, _ = run_window(Pendulum(1.0), np.array([0.1]), np.array([0.0]), s, 100.0, 1.0, wall_budget=0.0)
    assert not run.completed and run.error_kind == "WallClockExceeded"
    assert "wall-clock budget" in run.error and "Try" in run.error
    assert np.isnan(run.q[-1, 0])  # nothing after the stop is reported as a result


def test_impact_error_matches_by_ball_and_time():
    # rows: time, ball, orbital position, peak force, impact speed, duration
    ref = np.array([[1e-3, 3, 0.0, 100.0, 0, 0], [2e-3, 5, 0.0, 200.0, 0, 0]])
    assert wm.impact_error(ref.copy(), ref) == (0.0, 2)
    off = ref.copy()
    off[:, 3] *= 1.1  # every peak 10 % high
    assert wm.impact_error(off, ref)[0] == pytest.approx(0.1)
    wrong_ball = ref.copy()
    wrong_ball[1, 1] = 6  # second impact on another ball: unmatched, counts 100 %
    err, matched = wm.impact_error(wrong_ball, ref)
    assert matched == 1 and err == pytest.approx(math.sqrt(0.5))
    late = ref.copy()
    late[0, 0] += 1e-3  # outside the match window
    assert wm.impact_error(late, ref, match_window=2e-4)[1] == 1


def test_rms_error_of_a_stopped_run_is_infinite():
    x = np.zeros((5, 2))
    y = x.copy()
    y[3, 1] = np.nan
    assert wm.rms_vector_error(y, x) == math.inf
    y = x + np.array([3.0, 4.0])
    assert wm.rms_vector_error(y, x) == pytest.approx(5.0)


def test_method_grid_and_table_report_failures():
    quick = method_grid(True)
    curves = {m.curve for m in quick}
    assert any(m.exact_tangent for m in quick) and any(m.ivp for m in quick)
    assert {"HHT a=0.1 fixed h", "HHT a=0.1 adaptive"} <= curves
    full = method_grid(False)
    assert {"solve_ivp Radau", "solve_ivp BDF", "HHT a=0 adaptive", "HHT a=0.3 adaptive"} <= {m.curve for m in full}
    row = {"curve": "solve_ivp BDF", "setting": "rtol = 0.001", "wall": 3.0, "error_text": "stopped at t = 1 s",
           "steps": None, "newton_iterations": None, "factorizations": None, "rejected": None,
           **{q: math.inf for q in wm.QUANTITIES}, "impacts_matched": None}
    study = {"rows": [row], "config": {"window": 0.01, "sample_interval": 1e-5, "reference_step": 1e-7},
             "reference": {"wall": 1.0, "impacts": 3, "alpha": 0.1}, "observed_order_fixed_h": 2.0,
             "load_average": 1.0}
    table = markdown_table(study)
    assert "failed: stopped at t = 1 s" in table and "2.00 (2 expected)" in table
    assert "cage centre moves" not in table  # a study saved without the excursion
    # the quick window ends about when the cage starts to move: the table says what that means
    study["reference"]["cage_excursion_max"], study["quick"] = 2e-6, True
    quick_table = markdown_table(study)
    assert "cage centre moves at most 2 µm from its start in the window: the quick window ends" in quick_table
    study["quick"] = False
    assert markdown_table(study).endswith("cage centre moves at most 2 µm from its start in the window.")


def test_the_scipy_baseline_sparsity_pattern_covers_the_jacobian():
    """Every non-zero of a finite-difference Jacobian of the first-order bearing ODE lies in
    the pattern passed to Radau/BDF as jac_sparsity (a wrong pattern would make the baseline
    solve another problem), and the pattern is sparse (block-arrow)."""
    from bearingsim.dynamics.bearing import BearingModel, layout
    from bearingsim.dynamics.bearing.run import initial_coordinates
    from bearingsim.pipeline.scene.load import load_scene
    from bearingsim.pipeline.stages.simulate import build_model
    from bearingsim.pipeline.studies.scipy_baseline import jac_sparsity, ode_rhs

    params, start = build_model(load_scene("helicopter-b-given-hinge"))
    model = BearingModel(params)
    q0, v0 = initial_coordinates(params, start)
    rhs, _ = ode_rhs(model, model.rotation_slots, layout.spin_row(params.ball_count))
    y0 = np.concatenate([q0, v0 + 1e-3])  # off pure rolling: every traction term slides
    f0 = rhs(0.0, y0)
    n2 = y0.size
    pattern = jac_sparsity(params.ball_count, params.has_cage, model.rotation_slots).toarray()
    assert pattern.shape == (n2, n2) and pattern.mean() < 0.25
    for j in range(n2):
        dy = np.zeros(n2)
        dy[j] = 1e-9 * max(1.0, abs(y0[j]))
        column = rhs(0.0, y0 + dy) - f0
        outside = np.nonzero((np.abs(column) > 0.0) & ~pattern[:, j])[0]
        assert outside.size == 0, (j, outside[:5])


def test_speedup_at_equal_error_interpolates_in_log_log():
    """Two HHT points (1e-3, 1 s) and (1e-4, 10 s) are the line wall = 1e-3/err s in log-log: at
    err = 10^-3.5 HHT needs 10^0.5 s, so a solve_ivp run of 10^1.5 s there is 10x slower; a run
    outside the curve's error range is not extrapolated."""
    from bearingsim.pipeline.studies.work_precision import speedup_at_equal_error

    def row(curve, setting, wall, err):
        return {"curve": curve, "setting": setting, "wall": wall, "cage_centre": err, "error_text": None}

    rows = [row("HHT a=0.1 adaptive", "a", 1.0, 1e-3), row("HHT a=0.1 adaptive", "b", 10.0, 1e-4),
            row("solve_ivp BDF", "in", 10 ** 1.5, 10 ** -3.5), row("solve_ivp BDF", "out", 5.0, 1e-2)]
    s = speedup_at_equal_error(rows)
    assert s["solve_ivp BDF, in"] == pytest.approx(10.0, rel=1e-12)
    assert s["solve_ivp BDF, out"] is None


def test_scipy_at_default_error_reads_the_lower_envelope():
    """The default row (err 1e-3.5, 1 s) against a solve_ivp curve with points (1e-3, 10 s),
    (1e-4, 100 s) and a dominated point (1e-3.8, 200 s: more time than the 1e-4 point for more
    error). The envelope is wall = 1e-2/err s, so at 10^-3.5 scipy needs 10^1.5 s: 31.6x. A
    curve never as accurate as the default gives None; one whose points are all more accurate gives
    the loosest one's time as an upper bound."""
    from bearingsim.pipeline.studies.work_precision import DEFAULT_CURVE, DEFAULT_SETTING, scipy_at_default_error

    def row(curve, setting, wall, err):
        return {"curve": curve, "setting": setting, "wall": wall, "cage_centre": err, "error_text": None}

    rows = [row(DEFAULT_CURVE, DEFAULT_SETTING, 1.0, 10 ** -3.5), row(DEFAULT_CURVE, "rtol = 1e-07", 3.0, 1e-4),
            row("solve_ivp Radau", "rtol = 0.001", 10.0, 1e-3), row("solve_ivp Radau", "rtol = 0.0001", 100.0, 1e-4),
            row("solve_ivp Radau", "rtol = 1e-05", 200.0, 10 ** -3.8),
            row("solve_ivp BDF", "rtol = 0.001", 5.0, 1e-2), row("solve_ivp BDF", "rtol = 0.0001", 9.0, 1e-3)]
    rows += [row("solve_ivp Radau, jac_sparsity", "rtol = 0.0001", 12.0, 1e-4),
             row("solve_ivp Radau, jac_sparsity", "rtol = 0.001", 13.0, 2e-4)]
    s = scipy_at_default_error(rows)
    assert s["solve_ivp Radau"] == {"speedup": pytest.approx(10 ** 1.5, rel=1e-12), "bound": False}
    assert s["solve_ivp BDF"] is None  # never below 1e-3
    # (2e-4, 13 s) is dominated by (1e-4, 12 s): the envelope stops at 1e-4, an upper bound of 12 s
    assert s["solve_ivp Radau, jac_sparsity"] == {"speedup": pytest.approx(12.0, rel=1e-12), "bound": True}
    assert scipy_at_default_error(rows[1:]) == {}
