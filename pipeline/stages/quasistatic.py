"""Stage `quasistatic`: load distribution, contact angles, stiffness, initial state (§10)."""

from __future__ import annotations

import dataclasses

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
    from bearingsim.dynamics.quasistatic.solver import solve_quasistatic

    return solve_quasistatic(
        scene.bearing, scene.materials.ball, scene.materials.race,
        axial=scene.load.axial, radial=scene.load.radial, moment=scene.load.moment,
        inner_speed=scene.speed.inner, outer_speed=scene.speed.outer,
        centrifugal=scene.physics.centrifugal, gyroscopic=scene.physics.gyroscopic,
    )


def compute(ctx: StageContext) -> dict:
    from ..figures.worker import draw

    ctx.progress("solving equilibrium", 0.0)
    result = solve(ctx.scene)
    payload = result.to_json_dict()
    atomic_write_json(ctx.out_dir / RESULT_FILE, payload)
    ctx.progress("drawing load distribution", 0.7)
    # in the worker `bearingsim quasistatic` prestarted, if any (see figures.worker)
    draw("load_distribution", payload, ctx.out_dir / FIGURE_FILE, title=ctx.scene.name)
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
