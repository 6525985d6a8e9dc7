"""The compiled time loop (dynamics/multibody/compiled.py, docs/model.md M.103) against the
Python loop (time_loop.integrate): the same method and decisions, so the same steps.

The reference is the Python loop itself, an independent implementation of the control flow
that the error-control tests (test_mb_error_control.py) check against closed forms. Both run
the reference bearing over a window with pocket impacts, step rejections and matrix rebuilds,
so that every branch of the control flow is taken."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from bearingsim.dynamics.bearing import BearingModel, ModelOptions
from bearingsim.dynamics.bearing.run import initial_coordinates
from bearingsim.dynamics.lubrication.lubricant import load_builtin_lubricant
from bearingsim.dynamics.multibody import FixedIntervalSampler, IntegrationError, integrate
from bearingsim.dynamics.multibody.compiled import integrate_compiled
from bearingsim.dynamics.multibody.linear_solvers import BlockArrowSolver
from bearingsim.dynamics.multibody.settings import HHTSettings

from .bearing_fixtures import reference_model

# the shipped solver defaults (rtol 1e-6 on the physical scales, max_step 1e-4 s)
DEFAULTS = HHTSettings()


@pytest.fixture(scope="module")
def bearing():
    params, start = reference_model(moment=430.0, lubricant=load_builtin_lubricant("nato-o156"), options=ModelOptions())
    q0, v0 = initial_coordinates(params, start)
    return params, q0, v0


def _python(params, q0, v0, settings, window, sampler=None):
    model = BearingModel(params)
    sol = integrate(model, 0.0, window, q0, v0, settings, sampler=sampler,
                    linear_solver=BlockArrowSolver(params.ball_count, 6, model.nb))
    return model, sol


def test_compiled_loop_takes_the_python_loops_steps(bearing):
    """6 ms from the quasi-static start: the first pocket impacts come at ~5 ms. Counters must be
    identical; the final state, Hermite samples, impact log and energy balance agree to round-off.
    Both loops run the same machine code of the force kernel (the compiled loop calls it as a
    first-class function value) and were bit for bit equal here, cold cache or warm; the loop's own arithmetic is
    compiled inside the loop, where another LLVM may fuse operations differently, so the test
    allows the last bits (a kernel linked into the loop and optimised again gave 2e-11)."""
    params, q0, v0 = bearing
    window, dt = 6e-3, 1e-4
    s_py, s_c = (FixedIntervalSampler(0.0, window, dt, params.n_dof) for _ in range(2))
    m_py, sol_py = _python(params, q0, v0, DEFAULTS, window, s_py)
    m_c = BearingModel(params)
    sol_c, rec = integrate_compiled(m_c, 0.0, window, q0, v0, DEFAULTS, sampler=s_c, record_dt=dt, log_every=7)
    stats_py, stats_c = sol_py.stats.as_dict(), sol_c.stats.as_dict()
    stats_py.pop("wall_time"), stats_c.pop("wall_time")
    assert stats_c == stats_py
    assert sol_py.stats.rejected_steps > 0 and sol_py.stats.factorizations > 3
    assert len(m_py.impacts) > 0, "the window must contain pocket impacts (the hook's branch)"
    np.testing.assert_allclose(sol_c.q, sol_py.q, rtol=1e-9, atol=1e-15)
    np.testing.assert_allclose(sol_c.v, sol_py.v, rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(s_c.q, s_py.q, rtol=1e-9, atol=1e-15)
    np.testing.assert_allclose(m_c.impact_log(), m_py.impact_log(), rtol=1e-8, atol=1e-12)
    for key, value in m_py.energy.items():
        assert m_c.energy[key] == pytest.approx(value, rel=1e-9, abs=1e-12)
    # step-end records: the first accepted step at or after each multiple of dt, within a step
    assert rec.t[0] == 0.0 and rec.t.size == int(round(window / dt)) + 1
    k = np.arange(rec.t.size)
    assert np.all(rec.t >= k * dt - 1e-15) and np.all(rec.t - k * dt <= DEFAULTS.max_step)
    assert rec.log.shape == (sol_c.stats.steps // 7, 4)
    assert np.all(np.diff(rec.log[:, 0]) > 0.0) and rec.log[-1, 2] <= sol_c.stats.residual_evaluations


def test_compiled_loop_fails_as_the_python_loop(bearing):
    """Newton allowed one iteration at a tolerance it cannot meet, at a fixed minimum step: both
    loops stop at the same time with the same message, which names the settings to change."""
    params, q0, v0 = bearing
    bad = dataclasses.replace(DEFAULTS, first_step=1e-6, min_step=1e-6, max_newton_iter=1, newton_tol=1e-12)
    with pytest.raises(IntegrationError) as py:
        _python(params, q0, v0, bad, 1e-4)
    with pytest.raises(IntegrationError) as compiled:
        integrate_compiled(BearingModel(params), 0.0, 1e-4, q0, v0, bad)
    assert str(compiled.value) == str(py.value)
    assert "max_newton_iter" in str(compiled.value) and compiled.value.t == py.value.t


def test_on_chunk_can_stop_a_run(bearing):
    """The per-chunk callback sees the time advance and may stop the run (wall-clock budgets)."""
    params, q0, v0 = bearing
    seen = []

    def stop_after_two(t, h):
        seen.append(t)
        if len(seen) == 2:
            raise RuntimeError("budget")

    with pytest.raises(RuntimeError, match="budget"):
        integrate_compiled(BearingModel(params), 0.0, 1e-2, q0, v0, DEFAULTS, on_chunk=stop_after_two, chunk_steps=50)
    assert seen[0] < seen[1] < 1e-2
