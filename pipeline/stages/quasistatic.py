"""Stage `quasistatic`: load distribution, contact angles, stiffness, initial state (§10)."""

from __future__ import annotations

import dataclasses

import numpy as np

from ..artefacts import atomic_write_json
from ..runner import Stage, StageContext
from ..scene import Scene

RESULT_FILE = "quasistatic.json"
FIGURE_FILE = "load_distribution.png"
SAMPLES_FILE = "tolerance_samples.csv"
TOLERANCE_FIGURE = "crush_probability.png"


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
        # the operating parts above follow from these; the margin at reference temperature needs them too
        "temperatures": dataclasses.asdict(scene.temperatures),
        "expansion": dataclasses.asdict(scene.expansion),
        **({"tolerances": scene.raw["tolerances"]} if "tolerances" in scene.raw else {}),
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


def land_shift(scene: Scene, result) -> np.ndarray:
    """(2, 2) [m]: the guiding land's centre minus the non-guiding land's, in x and y, at the
    cage's two ends (z = -+w_c/2 from the inner ring's centre), from the inner ring's
    displacement and tilt (M.124)."""
    from bearingsim.dynamics.quasistatic.result import tilt_rotation_matrix

    axis = tilt_rotation_matrix(np.asarray(result.inner_tilt, float))[:, 2]
    half = 0.5 * scene.cage.width
    centres = np.array([result.inner_displacement[:2] + axis[:2] * z / axis[2] for z in (-half, half)])
    return -centres if scene.cage.guidance == "outer" else centres


def cage_screen(scene: Scene, result, parts=None):
    """The crush screen (docs/model.md §10.1) of a scene with a cage, else None; `parts`
    (default: the operating parts) gives the clearances."""
    if scene.cage is None:
        return None
    from bearingsim.dynamics.quasistatic.crush_screen import crush_screen, excursion_of

    from ..clearances import cage_clearances, land_film
    from ..scene import Parts

    parts = parts or Parts(scene.bearing, scene.cage, scene.materials)
    excursion = excursion_of(result.azimuth, result.ball_orbital_speed, 0.5 * scene.cage.mean_diameter)
    return crush_screen(excursion, result.cage_speed, cage_clearances(parts), land_film(scene),
                        land_shift(scene, result))


def screen_payload(scene: Scene, result) -> dict | None:
    """`cage_screen` of quasistatic.json: the screen at operating clearances, the margin the
    drawing's (reference-temperature) clearances would give with the same ball excursion, and
    the clearance table."""
    screen = cage_screen(scene, result)
    if screen is None:
        return None
    from ..clearances import clearance_table

    payload = screen.to_json_dict()
    if scene.nominal is not None:
        cold = cage_screen(scene, result, parts=scene.nominal)
        payload["crush_margin_at_reference_temperature"] = cold.crush_margin
        payload["regime_at_reference_temperature"] = cold.regime
    payload["clearances"] = clearance_table(scene)
    return payload


def _timed(fn) -> float:
    import time

    t0 = time.perf_counter()
    fn()
    return time.perf_counter() - t0


def compute(ctx: StageContext) -> dict:
    from ..figures.worker import draw

    from ..kernel_cache import ensure_compiled

    ctx.progress("solving equilibrium", 0.0)
    first = []  # on a cold cache the first solve compiles, once per machine (pipeline.kernel_cache)
    ensure_compiled(ctx.scene, lambda: _timed(lambda: first.append(solve(ctx.scene))), "quasistatic")
    result = first[0] if first else solve(ctx.scene)
    payload = result.to_json_dict()
    screen = screen_payload(ctx.scene, result)
    if screen is not None:
        payload["cage_screen"] = screen
    tolerance = None
    if ctx.scene.tolerances is not None and screen is not None:
        from ..tolerances import analyse, summary, write_samples_csv

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
            draw("crush_probability", {"margin": tolerance.margin.tolist(), "regime": tolerance.regime.tolist(),
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
