"""Where the wall time of an HHT-α step goes (docs/performance.md).

    taskset -c 1 python -m benchmarks.step_cost [SCENE] [--window 0.015] [--set KEY=VALUE ...]

Integrates the scene's bearing over `window` from its quasi-static start with the scene's
solver settings, timing every residual evaluation, tangent build, factorisation and solve
(perf_counter around each call), and reports them per step against the whole loop; the rest
is the Python time loop (Newmark update, error norm, sampling, hooks). Then the same window
runs untimed in the Python loop and in the compiled loop (`dynamics/multibody/compiled.py`,
what `simulate` uses), alternated, best of three each. Kernels are compiled or loaded before
anything is timed. Run it on a quiet core; the load average is printed.
"""

from __future__ import annotations

import argparse
import math
import os
import time


class Timed:
    """Wraps a problem and a linear solver, accumulating wall time per call kind."""

    def __init__(self, model, solver):
        self.model, self.solver = model, solver
        self.n_dof, self.rotation_slots, self.error_weights = model.n_dof, model.rotation_slots, model.error_weights
        self.error_scales = model.error_scales
        self.on_accepted_step = self._hook
        self.time = {"residual": 0.0, "tangent": 0.0, "factor": 0.0, "solve": 0.0, "hook": 0.0}
        self.calls = dict.fromkeys(self.time, 0)

    def _timed(self, kind, fn, *args):
        t0 = time.perf_counter()
        out = fn(*args)
        self.time[kind] += time.perf_counter() - t0
        self.calls[kind] += 1
        return out

    def evaluate(self, *args):
        return self._timed("residual", self.model.evaluate, *args)

    def jacobian(self, *args):
        return self._timed("tangent", self.model.jacobian, *args)

    def factor(self, matrix):
        return self._timed("factor", self.solver.factor, matrix)

    def solve(self, rhs, out):
        return self._timed("solve", self.solver.solve, rhs, out)

    def _hook(self, *args):
        return self._timed("hook", self.model.on_accepted_step, *args)


def loop_ready(scene_name: str, overrides=()):
    """(scene, model parameters, q0, v0) of a scene's quasi-static start, its kernels compiled
    or loaded by a 20 us run of the compiled loop, with the float32 traction passes that
    `simulate_bearing` uses: what a timed window of the loop starts from."""
    from bearingsim.pipeline.machine.numba_cache import configure_numba_cache

    configure_numba_cache()

    from bearingsim.dynamics.bearing import BearingModel
    from bearingsim.dynamics.bearing.run import initial_coordinates
    from bearingsim.dynamics.multibody.compiled import integrate_compiled
    from bearingsim.pipeline.scene.load import load_scene
    from bearingsim.pipeline.stages.simulate import build_model

    scene = load_scene(scene_name, list(overrides))
    params, start = build_model(scene, None)
    params = params.with_float32_residual()  # as simulate_bearing runs it
    q0, v0 = initial_coordinates(params, start)
    integrate_compiled(BearingModel(params), 0.0, 2e-5, q0, v0, scene.solver)  # compile / load
    return scene, params, q0, v0


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("scene", nargs="?", default="helicopter-b-given-hinge")
    ap.add_argument("--window", type=float, default=0.015)
    ap.add_argument("--set", action="append", default=[], dest="overrides")
    args = ap.parse_args(argv)

    from bearingsim.dynamics.bearing import BearingModel
    from bearingsim.dynamics.multibody import integrate
    from bearingsim.dynamics.multibody.compiled import integrate_compiled
    from bearingsim.dynamics.multibody.linear_solvers import BlockArrowSolver

    scene, params, q0, v0 = loop_ready(args.scene, args.overrides)
    for window in (2e-5, args.window):  # the first run compiles / loads every kernel
        model = BearingModel(params)
        timed = Timed(model, BlockArrowSolver(params.ball_count, 6, model.nb))
        t0 = time.perf_counter()
        sol = integrate(timed, 0.0, window, q0, v0, scene.solver, linear_solver=timed)
        wall = time.perf_counter() - t0
    s = sol.stats
    print(f"{args.scene}: {window * 1e3:g} ms, {s.steps} steps, {s.newton_iterations} Newton iterations "
          f"({s.newton_iterations / s.steps:.2f} per step), {s.factorizations} factorisations, "
          f"{s.rejected_steps} rejected; load average {os.getloadavg()[0]:.2f}")
    print(f"{'part':<12}{'calls':>9}{'us per call':>13}{'us per step':>13}{'share':>8}")
    rest = wall - sum(timed.time.values())
    for kind, seconds in list(timed.time.items()) + [("time loop", rest)]:
        calls = timed.calls.get(kind, s.steps)
        print(f"{kind:<12}{calls:>9}{1e6 * seconds / max(calls, 1):>13.1f}{1e6 * seconds / s.steps:>13.1f}"
              f"{100 * seconds / wall:>7.0f}%")
    print(f"{'total':<12}{'':>9}{'':>13}{1e6 * wall / s.steps:>13.1f}{100:>7.0f}%")
    # the same window in the Python loop (no timers) and in the compiled loop, alternated
    best = {"Python loop": math.inf, "compiled loop": math.inf}
    steps = {}
    for _ in range(3):
        for name in best:
            model = BearingModel(params)
            t0 = time.perf_counter()
            if name == "compiled loop":
                sol, _ = integrate_compiled(model, 0.0, window, q0, v0, scene.solver)
            else:
                sol = integrate(model, 0.0, window, q0, v0, scene.solver,
                                linear_solver=BlockArrowSolver(params.ball_count, 6, model.nb))
            best[name] = min(best[name], time.perf_counter() - t0)
            steps[name] = sol.stats.steps  # the same as the timed run's, up to round-off decisions
    for name, seconds in best.items():
        print(f"{name:<14} {seconds:6.3f} s  {steps[name]:6d} steps  {1e6 * seconds / steps[name]:6.1f} us per step "
              "(best of 3)")
    print(f"compiled / Python: {best['compiled loop'] / best['Python loop']:.2f}; "
          f"load average {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
