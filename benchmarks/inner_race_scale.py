"""Does a looser error scale for the inner race buy steps at the accuracy bar? (docs/model.md §9)

    taskset -c 1 python -m benchmarks.inner_race_scale [FACTOR:RTOL ...]

The controller measures each coordinate's error on its physical scale (`BearingModel.error_scales`,
M.99b); the inner race's is a mean ball load over its diagonal stiffness, which sums all contacts and
the hinge, so it is several times tighter than a ball's. Over the work-precision window of
helicopter-b-given-hinge (15 ms from the quasi-static start, errors against the fixed-step reference
of `pipeline/studies/work_precision.py`) this runs HHT-α at the default rtol with today's scales, then
with the inner race's six scales multiplied by FACTOR at RTOL (default 3:1e-6 10:1e-6 30:1e-6
10:5e-7), and prints steps, residuals and the four errors of the study next to the bar (the previous
default, fixed 2e-6 s steps).
"""

from __future__ import annotations

import os
import sys


def main(argv=None) -> None:
    from bearingsim.pipeline.numba_cache import configure_numba_cache

    configure_numba_cache()

    from bearingsim.dynamics.bearing import layout, model as bearing_model
    from bearingsim.dynamics.bearing.run import initial_coordinates
    from bearingsim.pipeline.scene import load_scene
    from bearingsim.pipeline.stages.simulate import build_model
    from bearingsim.pipeline.studies import work_precision as wp, wp_metrics as wm

    args = sys.argv[1:] if argv is None else argv
    specs = [(float(f), float(r)) for f, r in (a.split(":") for a in args or ["3:1e-6", "10:1e-6", "30:1e-6", "10:5e-7"])]
    factor = {"value": 1.0}
    physical_scales = bearing_model.BearingModel.error_scales

    def scaled(self, t0, q0, v0):
        # the study builds its model inside `bearing_window`, so the scale is changed on the class
        L = physical_scales(self, t0, q0, v0).copy()
        i = layout.inner_offset(self.params.ball_count)
        L[i:i + 6] *= factor["value"]
        return L

    bearing_model.BearingModel.error_scales = scaled
    scene = load_scene("helicopter-b-given-hinge")
    params, start = build_model(scene)
    cfg = wp.StudyConfig(0.015, 5e-6, 1e-7, 1e4)
    _, ref = wp.reference_run(params, start, scene.solver, cfg)
    q0, v0 = initial_coordinates(params, start)
    L = physical_scales(bearing_model.BearingModel(params.with_float32_residual()), 0.0, q0, v0)
    i = layout.inner_offset(params.ball_count)
    print(f"{scene.name}: error scales [um] inner race (x, y, z) {', '.join(f'{1e6 * x:.2f}' for x in L[i:i + 3])}; "
          f"ball 0 (x, y, z) {', '.join(f'{1e6 * x:.2f}' for x in L[:3])}")
    print(f"{'setting':<44}{'steps':>7}{'residuals':>10}{'centre um':>11}{'speed':>9}{'inner nm':>10}{'impacts':>9}")
    bar = wp.fixed_step_method(wp.PREVIOUS_DEFAULT_STEP)
    rtol = scene.solver.rtol
    runs = [("previous default (the bar), " + bar.setting, 1.0, bar)]
    runs += [(f"inner-race scale x{f:g}, rtol {r:g}", f,
              wp.Method("HHT a=0.1 adaptive", f"rtol = {r:g}", {**wp.ADAPTIVE_DEFAULT, "rtol": r}))
             for f, r in [(1.0, rtol)] + specs]
    for label, f, method in runs:
        factor["value"] = f
        out = wp.run_method(method, params, start, scene.solver, cfg)
        e = wm.run_errors(params, out["t"], out["q"], out["v"], ref)
        print(f"{label:<44}{out['steps']:>7}{out['newton_iterations']:>10}{e['cage_centre'] * 1e6:>11.2g}"
              f"{e['cage_speed']:>9.2g}{e['inner_race'] * 1e9:>10.3f}{e['impact_force']:>9.3%}", flush=True)
    print(f"load average {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
