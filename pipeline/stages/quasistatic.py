"""Stage `quasistatic`: load distribution, contact angles, stiffness, initial state (§10)."""

from __future__ import annotations

import dataclasses

from ..staging.artefacts import atomic_write_json
from ..quasistatic.solution import cage_screen, land_shift, screen_payload, solve  # noqa: F401 - used by bench, tests
from ..staging.runner import Stage, StageContext
from ..scene.load import Scene

RESULT_FILE = "quasistatic.json"
FIGURE_FILE = "load_distribution.png"
SAMPLES_FILE = "tolerance_samples.csv"
TOLERANCE_FIGURE = "crush_probability.png"


def quasistatic_inputs(scene: Scene) -> dict:
    return {
        # the parts the stage computes with: at their operating temperatures
        "bearing": dataclasses.asdict(scene.operating.bearing),
        "ball": dataclasses.asdict(scene.operating.materials.ball),
        "race": dataclasses.asdict(scene.operating.materials.race),
        "load": dataclasses.asdict(scene.load),
        "speed": dataclasses.asdict(scene.speed),
        "centrifugal": scene.physics.centrifugal,
        "gyroscopic": scene.physics.gyroscopic,
        # the crush screen's inputs (absent without a cage)
        "cage": dataclasses.asdict(scene.operating.cage) if scene.cage is not None else None,
        "land_viscosity": scene.lubricant.eta0 if scene.lubricant is not None and scene.cage is not None else None,
        "land": (scene.physics.cage_race_boundary, scene.physics.cage_race_lands) if scene.cage is not None else None,
        # the operating parts above follow from these; the margin at reference temperature needs them too
        "temperatures": dataclasses.asdict(scene.temperatures),
        "expansion": dataclasses.asdict(scene.expansion),
        **({"tolerances": scene.raw["tolerances"]} if "tolerances" in scene.raw else {}),
        # only when off, so the keys of existing runs (figures on) stay valid
        **({"figures": False} if not scene.output.figures else {}),
    }


def compute(ctx: StageContext) -> dict:
    from ..figures.worker import draw

    from ..machine.kernel_cache import ensure_compiled

    ctx.progress("solving equilibrium", 0.0)
    solved = []  # on a cold cache the first solve compiles, once per machine (pipeline.machine.kernel_cache)
    ensure_compiled(ctx.scene, lambda: solved.append(solve(ctx.scene)), "quasistatic")
    result = solved[0] if solved else solve(ctx.scene)
    payload = result.to_json_dict()
    screen = screen_payload(ctx.scene, result)
    if screen is not None:
        payload["cage_screen"] = screen
    tolerance = None
    if ctx.scene.tolerances is not None and screen is not None:
        from ..quasistatic.tolerances import analyse, summary, write_samples_csv

        ctx.progress(f"crush probability over {ctx.scene.tolerances.samples} tolerance stacks", 0.4)
        tolerance = analyse(ctx.scene)
        payload["crush_probability"] = summary(tolerance, ctx.scene)
        write_samples_csv(ctx.out_dir / SAMPLES_FILE, tolerance)
    atomic_write_json(ctx.out_dir / RESULT_FILE, payload)
    if ctx.scene.output.figures:
        ctx.progress("drawing load distribution", 0.7)
        # in the worker `bearingsim quasistatic` prestarted, if any (see figures.worker)
        draw("load_distribution", payload, ctx.out_dir / FIGURE_FILE, title=ctx.scene.name)
        if tolerance is not None:
            ok = tolerance.valid_mask  # the stacks that are bearings
            draw("crush_probability", {"margin": tolerance.margin[ok].tolist(), "regime": tolerance.regime[ok].tolist(),
                                       "summary": payload["crush_probability"]},
                 ctx.out_dir / TOLERANCE_FIGURE, title=ctx.scene.name)
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
