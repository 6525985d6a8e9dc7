"""Time to evaluate every contact of the reference bearing once (issue 3 target: <= 50 us).

    python -m pipeline.bench.contacts [SCENE]

Reports the full residual evaluation of the bearing model (44 ball–race contacts with
film and Eyring traction, 22 ball–pocket contacts, 1 cage–race journal, hinge, loads) and
its parts, on the quasi-static start state. Minimum over repeats (other work on the
machine only makes times longer).
"""

from __future__ import annotations

import sys

import numpy as np

from pipeline.bench import best_time


def _best(fn, repeats: int = 7, number: int = 300) -> float:
    return best_time(fn, repeat=repeats, number=number)


def main(scene_name: str = "helicopter-b-given-hinge") -> None:
    from dataclasses import replace

    from dynamics.bearing import BearingModel
    from dynamics.bearing.run import initial_coordinates
    from pipeline.scene import load_scene
    from pipeline.stages.simulate import build_model

    scene = load_scene(scene_name)
    rows = []
    for label, physics in (("all contacts (Eyring traction, film, pockets, journal)", {}),
                           ("without traction", {"traction": "none"}),
                           ("without traction and film", {"traction": "none", "ehd_film": False})):
        s = replace(scene, physics=replace(scene.physics, **physics))
        params, start = build_model(s)
        model = BearingModel(params)
        q, v = initial_coordinates(params, start)
        n = model.n_dof
        a, ma, g = np.zeros(n), np.zeros(n), np.zeros(n)
        model.evaluate(0.0, q, v, a, ma, g)  # compile / load from cache
        model.jacobian(0.0, q, v, a, 1.0, 1e-6, 1e-12)
        rows.append((label, _best(lambda: model.evaluate(0.0, q, v, a, ma, g)),
                     _best(lambda: model.jacobian(0.0, q, v, a, 1.0, 1e-6, 1e-12), number=50)))
    print(f"bearing contacts of {scene_name} (Z = {params.ball_count}), one core, best of 7")
    print(f"{'':58s} {'residual':>10s} {'+tangent':>10s}")
    for label, t_res, t_jac in rows:
        print(f"{label:58s} {t_res * 1e6:8.1f} us {t_jac * 1e6:8.1f} us")
    print("target (issue 3): all contacts incl. traction <= 50 us")


if __name__ == "__main__":
    main(*sys.argv[1:])
