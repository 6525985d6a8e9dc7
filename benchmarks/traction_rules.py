"""What the traction rule's node count buys: its error against the contacts' time mid-run.

    taskset -c 1 python -m benchmarks.traction_rules

For each node-count setting of `FastTraction.build` (radial nodes x rays of the rule used when the
spin pole lies inside the contact, which is where mid-run contacts have it): the worst error
against the (128, 1024) quadrature over two samples of 240 random operating points of the
reference scene (`benchmarks.traction._points`, seeds 1 and 2; metrics of
tests/test_traction_fast.py, whose bound is the 2 % of docs/model.md §6.4), and the time of one
evaluation of every contact of helicopter-b-given-hinge 20 ms into a run, as the time loop calls
it (float32 residual passes; `benchmarks.contacts`, hinge and gyroscopic terms off). The question
it answers (README, *Why 0.8 s do not fit in 10 s*): how much of a residual a coarser rule could
save inside the accuracy the model promises.
"""

from __future__ import annotations

import dataclasses
import os

import numpy as np

from benchmarks.contacts import MID_RUN, _time_kernel
from benchmarks.traction import _points, worst_errors

SETTINGS = {"default (10 x 20/24/32)": {}}
for _n_radial in (10, 9, 8):
    for _rays in ((20, 24, 32), (18, 22, 28), (16, 20, 24)):
        if (_n_radial, _rays) != (10, (20, 24, 32)):
            SETTINGS[f"{_n_radial} x {'/'.join(map(str, _rays))}"] = {"n_radial": _n_radial, "n_angle": _rays}


def main() -> None:
    from bearingsim.dynamics.bearing import BearingModel, simulate_bearing
    from bearingsim.dynamics.lubrication.lubricant import load_builtin_lubricant
    from bearingsim.dynamics.traction import quadrature
    from bearingsim.dynamics.traction.fast import FastTraction
    from bearingsim.pipeline.scene import load_scene
    from bearingsim.pipeline.stages.simulate import build_model

    lub = load_builtin_lubricant("nato-o156")
    P = np.concatenate([_points(240, lub, seed=1), _points(240, lub, seed=2)])
    ref = [quadrature.traction_quadrature(*p[:4], lub.eyring_stress, lub.model_code, lub.rheology_params(),
                                          *p[4:], 128, 1024) for p in P]
    scene = load_scene("helicopter-b-given-hinge")
    params, start = build_model(scene)
    run = simulate_bearing(params, start, scene.solver, MID_RUN, MID_RUN)
    q_mid, v_mid = run.q[-1], run.v[-1]
    own = params.traction
    print(f"traction rule against the mid-run contacts of {scene.name} (load average {os.getloadavg()[0]:.2f})")
    print(f"{'rule (radial x rays)':<26}{'max dF/F':>10}{'max dM':>9}{'max dJ':>9}{'contacts':>11}{'ratio':>7}")
    base = None
    for name, kwargs in SETTINGS.items():
        ft = FastTraction.build(lub, **kwargs)
        eF, eM, eJ = worst_errors(ft, P, ref)
        # the scene's own viscosity table and Eyring stress, this setting's nodes
        scene_rule = FastTraction(own.eta_table, own.p_step, own.tau0, ft.rule).traction_rule(True)
        bearing = dataclasses.replace(params, traction=scene_rule).without("hinge", "gyroscopic")
        t = _time_kernel(BearingModel(bearing), q_mid, v_mid, False, 400)
        base = base or t
        print(f"{name:<26}{eF:>10.2%}{eM:>9.2%}{eJ:>9.2%}{t * 1e6:>8.1f} us{t / base:>7.2f}")
    print("errors: worst over 480 points against the (128, 1024) quadrature (itself <= 0.4 % from converged);")
    print("dM relative to max(|M|, |F| b). contacts: best mean of 25 runs of 400 calls from a numba loop.")


if __name__ == "__main__":
    main()
