"""The integrator stops a run whose step control cycles through Newton failures
(`multibody.results.NewtonStallWatch`, docs/performance.md)."""

import numpy as np
import pytest

from bearingsim.dynamics.multibody.results import IntegrationError, NewtonStallWatch


def _feed(watch, ratios, t=0.03, h=2e-8):
    """Counters of successive windows of WINDOW accepted steps with these failure ratios."""
    steps = failures = 0
    for r in ratios:
        steps += watch.WINDOW
        failures += int(round(r * watch.WINDOW))
        watch.check(t, h, steps, failures)


def test_five_windows_of_failures_every_other_step_stop_the_run():
    with pytest.raises(IntegrationError, match=r"t = 0.03 s .*50% of the last 1000 accepted steps.*solver.alpha"):
        _feed(NewtonStallWatch(0.0), [0.5] * 5)


def test_the_hint_names_what_is_short():
    """Below the damping that takes case b through its start-up, damping; above it, the Newton
    iterations a step may take before it is rejected come first."""
    with pytest.raises(IntegrationError) as undamped:
        _feed(NewtonStallWatch(0.0, 8), [0.5] * 5)
    assert ("more numerical damping: solver.alpha between 0.05 and 0.333333 (it is 0); 0.05 and the default "
            "0.1 take case b through the start-up, where alpha = 0 cycles") in str(undamped.value)
    with pytest.raises(IntegrationError) as damped:
        _feed(NewtonStallWatch(0.1, 1), [0.5] * 5)
    assert ("more Newton iterations before a step is rejected: a larger solver.max_newton_iter (it is 1); or "
            "more numerical damping: solver.alpha between 0.05 and 0.333333 (it is 0.1)") in str(damped.value)


def test_bursts_a_converging_run_has_do_not():
    # 0.1 failures per accepted step is the worst 1000-step burst measured in runs that finish;
    # a cycle broken by one good window starts counting again
    _feed(NewtonStallWatch(0.1), [0.1] * 50 + [0.39] * 20 + [0.5] * 4 + [0.2] + [0.5] * 4)


def test_counters_are_read_per_window_of_at_least_1000_steps():
    watch = NewtonStallWatch(0.0)
    for steps in range(100, 1000, 100):  # a short chunk does not close a window
        watch.check(0.0, 1e-8, steps, steps // 2)
    assert watch.in_a_row == 0
    watch.check(0.0, 1e-8, 1000, 500)
    assert watch.in_a_row == 1


@pytest.mark.slow
def test_undamped_hht_on_case_b_stops_with_the_time_and_what_to_try():
    """alpha = 0 (trapezoidal rule) fails in case b's start-up while the cage rubs its land; how
    depends on the last bits of the kernels: the step control falling into the cycle the stall
    watch stops (from 30.7 ms with 12-47 ns steps in one build, 19.4 ms with ~0.9 us steps in
    another), or Newton failing at the minimum step (46 ms). Either way the run stops early and
    the message names the time and solver.alpha."""
    from bearingsim.dynamics.bearing import BearingModel
    from bearingsim.dynamics.bearing.run import initial_coordinates
    from bearingsim.dynamics.multibody.compiled import integrate_compiled
    from bearingsim.pipeline.scene.load import load_scene
    from bearingsim.pipeline.stages.simulate import build_model

    scene = load_scene("helicopter-b-given-hinge", ["solver.alpha=0"])
    params, start = build_model(scene, None)
    params = params.with_float32_residual()
    q0, v0 = initial_coordinates(params, start)
    with pytest.raises(IntegrationError, match="solver.alpha") as failure:
        integrate_compiled(BearingModel(params), 0.0, 0.1, q0, v0, scene.solver)
    assert failure.value.t < 0.1 and failure.value.h < 1e-5  # the default takes ~5 us steps there
    assert f"t = {failure.value.t:.9g} s" in str(failure.value)


def test_a_newton_failure_without_damping_says_to_add_damping_first():
    from bearingsim.dynamics.multibody.results import Result, damping_first

    hint = Result.NEWTON_MAX_ITER.hint
    assert damping_first(hint, 0.1) == hint
    undamped = damping_first(hint, 0.0)
    assert undamped.startswith("more numerical damping first: solver.alpha") and undamped.endswith(hint)
