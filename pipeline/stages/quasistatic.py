"""Stage `quasistatic`: load distribution, contact angles, stiffness, initial state (§10)."""

from __future__ import annotations

import dataclasses
import logging

from ..artefacts import atomic_write_json
from ..runner import Stage, StageContext
from ..scene import Scene

RESULT_FILE = "quasistatic.json"
FIGURE_FILE = "load_distribution.png"


def quasistatic_inputs(scene: Scene) -> dict:
    return {
        "bearing": dataclasses.asdict(scene.bearing),
        "ball": dataclasses.asdict(scene.materials.ball),
        "race": dataclasses.asdict(scene.materials.race),
        "load": dataclasses.asdict(scene.load),
        "speed": dataclasses.asdict(scene.speed),
        "centrifugal": scene.physics.centrifugal,
        "gyroscopic": scene.physics.gyroscopic,
    }


def solve(scene: Scene):
    """Solve the quasi-static equilibrium of `scene` (no files)."""
    from dynamics.quasistatic import solve_quasistatic

    return solve_quasistatic(
        scene.bearing, scene.materials.ball, scene.materials.race,
        axial=scene.load.axial, radial=scene.load.radial, moment=scene.load.moment,
        inner_speed=scene.speed.inner, outer_speed=scene.speed.outer,
        centrifugal=scene.physics.centrifugal, gyroscopic=scene.physics.gyroscopic,
    )


def compute(ctx: StageContext) -> dict:
    from ..figures.worker import FigureWorkerError, take_worker

    # the figure's process imports matplotlib on the other core while this one solves
    with take_worker() as worker:
        ctx.progress("solving equilibrium", 0.0)
        result = solve(ctx.scene)
        payload = result.to_json_dict()
        atomic_write_json(ctx.out_dir / RESULT_FILE, payload)
        ctx.progress("drawing load distribution", 0.7)
        try:
            worker.draw("load_distribution", payload, ctx.out_dir / FIGURE_FILE, title=ctx.scene.name)
        except FigureWorkerError as exc:  # draw here instead, and say so in run.log
            logging.getLogger("bearingsim").warning("quasistatic: %s; drawing in this process", exc)
            from ..figures.quasistatic import plot_load_distribution

            plot_load_distribution(payload, ctx.out_dir / FIGURE_FILE, title=ctx.scene.name)
    return {"converged": bool(payload.get("converged")),
            "max_inner_load_N": max(b["inner_load"] for b in payload["balls"])}


STAGE = Stage(
    name="quasistatic",
    depends=(),
    needed=lambda scene: True,
    inputs=quasistatic_inputs,
    compute=compute,
    summary="static equilibrium: ball loads, contact angles, stiffness",
)
