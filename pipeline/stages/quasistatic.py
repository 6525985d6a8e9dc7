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
        # the crush screen's inputs (absent without a cage)
        "cage": dataclasses.asdict(scene.cage) if scene.cage is not None else None,
        "land_viscosity": scene.lubricant.eta0 if scene.lubricant is not None and scene.cage is not None else None,
        "land": (scene.physics.cage_race_boundary, scene.physics.cage_race_lands) if scene.cage is not None else None,
        # only when off, so the keys of existing runs (figures on) stay valid
        **({"figures": False} if not scene.output.figures else {}),
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


def cage_screen(scene: Scene, result):
    """The crush screen (docs/model.md §10.1) of a scene with a cage, else None."""
    if scene.cage is None:
        return None
    from bearingsim.dynamics.quasistatic.crush_screen import crush_screen

    b, c = scene.bearing, scene.cage
    return crush_screen(
        result.azimuth, result.ball_orbital_speed, result.cage_speed,
        pitch_radius=0.5 * c.mean_diameter, pocket_clearance=c.pocket_diameter - b.ball_diameter,
        guide_clearance=c.guide_clearance(b), land_radius=0.5 * c.guide_land_diameter(b),
        land_length=c.guide_land_length(b), lands=scene.physics.cage_race_lands,
        eps0=scene.physics.cage_race_boundary,
        viscosity=scene.lubricant.eta0 if scene.lubricant is not None else 0.0)


def compute(ctx: StageContext) -> dict:
    from ..figures.worker import draw

    ctx.progress("solving equilibrium", 0.0)
    result = solve(ctx.scene)
    payload = result.to_json_dict()
    screen = cage_screen(ctx.scene, result)
    if screen is not None:
        payload["cage_screen"] = screen.to_json_dict()
    atomic_write_json(ctx.out_dir / RESULT_FILE, payload)
    if ctx.scene.output.figures:
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
