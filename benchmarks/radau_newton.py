"""Would a fifth-order method spend fewer residuals than HHT-α at the accuracy bar? (docs/model.md §9)

    taskset -c 1 python -m benchmarks.radau_newton

Over the work-precision window of helicopter-b-given-hinge (15 ms from the quasi-static start,
errors against the fixed-step reference of `pipeline/studies/work_precision.py`):
- the previous default (fixed 2e-6 s steps), whose errors are the accuracy bar;
- HHT-α at the default rtol and at 1.3e-6, 1.5e-6 and 2e-6 (where the bar is crossed);
- scipy's Radau IIA (three stages, order 5) with `jac_sparsity` at rtol 1e-3, as scipy runs it
  and with a fresh finite-difference Jacobian at the start of every step (so that a stale matrix
  cannot inflate its Newton iterations). scipy counts the residuals of its Newton
iterations (three per iteration, one per stage) and of each accepted step in `nfev`, not those of
its finite-difference Jacobians; this script also counts the iterations of every collocation solve.
A three-stage method breaks even with HHT-α when 3 x its iterations per step, plus one, reach
HHT-α's residuals per step times its step-count ratio.
"""

from __future__ import annotations

import os

from scipy import integrate
from scipy.integrate._ivp import radau

COUNT = {"solves": 0, "iterations": 0, "diverged": 0}
_solve_collocation = radau.solve_collocation_system


def _counted_solve(*args, **kwargs):
    converged, n_iter, Z, rate = _solve_collocation(*args, **kwargs)
    COUNT["solves"] += 1
    COUNT["iterations"] += n_iter
    COUNT["diverged"] += not converged
    return converged, n_iter, Z, rate


class FreshJacobianRadau(integrate.Radau):
    """scipy's Radau with the Jacobian re-evaluated (and both LU factors redone) before every step."""

    def _step_impl(self):
        self.J = self.jac(self.t, self.y, self.f)
        self.current_jac = True
        self.LU_real = self.LU_complex = None
        return super()._step_impl()


def main() -> None:
    from bearingsim.pipeline.scene import load_scene
    from bearingsim.pipeline.stages.simulate import build_model
    from bearingsim.pipeline.studies import work_precision as wp

    radau.solve_collocation_system = _counted_solve  # count the iterations of every collocation solve
    scene = load_scene("helicopter-b-given-hinge")
    params, start = build_model(scene)
    ivp = {"method": "Radau", "rtol": 1e-3, "atol": 1e-8, "sparse": True}
    methods = [wp.fixed_step_method(wp.PREVIOUS_DEFAULT_STEP, "HHT a=0.1 fixed h (previous default: the bar)"),
               wp.Method("HHT a=0.1 adaptive", "rtol = 1e-06", {**wp.ADAPTIVE_DEFAULT, "rtol": 1e-6}),
               *(wp.Method("HHT a=0.1 adaptive", f"rtol = {r:g}", {**wp.ADAPTIVE_DEFAULT, "rtol": r})
                 for r in (1.3e-6, 1.5e-6, 2e-6)),
               wp.Method("Radau, jac_sparsity", "rtol = 0.001", ivp=ivp),
               wp.Method("Radau, jac_sparsity, fresh Jacobian each step", "rtol = 0.001",
                         ivp={**ivp, "solver_class": FreshJacobianRadau})]
    counts = []

    def progress(text):
        counts.append(dict(COUNT))
        print(text, flush=True)

    study = wp.run_study(params, start, scene.solver, False, progress=progress, methods=methods,
                         cfg=wp.StudyConfig(0.015, 5e-6, 1e-7, 1e4))
    counts.append(dict(COUNT))
    print(f"\n{scene.name}, 15 ms window, load average {os.getloadavg()[0]:.2f}")
    print(f"{'method':<64}{'steps':>7}{'residuals':>10}{'per step':>9}{'Newton/step':>12}{'diverged':>9}"
          f"{'centre um':>11}{'speed':>9}{'inner nm':>9}{'impacts':>9}")
    for i, r in enumerate(study["rows"]):
        it = counts[i + 2]["iterations"] - counts[i + 1]["iterations"]
        dv = counts[i + 2]["diverged"] - counts[i + 1]["diverged"]
        newton = f"{it / r['steps']:.2f}" if it else "-"
        print(f"{r['curve'] + ', ' + r['setting']:<64}{r['steps']:>7}{r['newton_iterations']:>10}"
              f"{r['newton_iterations'] / r['steps']:>9.2f}{newton:>12}{dv if it else '-':>9}"
              f"{r['cage_centre'] * 1e6:>11.2g}{r['cage_speed']:>9.2g}{r['inner_race'] * 1e9:>9.3f}"
              f"{r['impact_force']:>9.2%}")
    print("residuals: HHT-alpha's Newton iterations (one residual each); scipy's nfev (stage residuals of its")
    print("Newton iterations and one per accepted step, not its finite-difference Jacobians).")


if __name__ == "__main__":
    main()
