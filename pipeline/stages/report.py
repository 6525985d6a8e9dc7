"""Stage `report`: renders and the run report, from saved results only (never re-solves).

Writes into the stage directory (`<run>/report/`): `report.html` (one self-contained
page), the burn-zone renders, one PNG + ParaView `.vtu` per FE load case, the ParaView
motion series and land-heat surface (`paraview/`, `pipeline.render.paraview_series`), and
`renders.json` (see `pipeline.render.run_report`). Its key hashes the scene's name and
description, the render settings and the upstream stages' keys, so any change of
results upstream redraws it.

`bearingsim render RUN` (`render_run`) redraws it from a finished run directory without
running any other stage: it takes the upstream keys from their `stage.json` manifests and
writes the same manifest a `run` would, so a later `bearingsim run` of the same scene finds
the report up to date instead of drawing it again. It draws only results computed from the
directory's scene.toml (pipeline.stages.consistency) and intact, and draws the upstream
stages' missing figures again from their data (pipeline.render.stage_figures).
"""

from __future__ import annotations

import dataclasses
import logging
from pathlib import Path

from ..staging.runner import Stage, StageContext, StageOutcome

class StageResultsDamaged(ValueError):
    """A finished stage's files changed or went missing since it wrote them: `render` shows
    no edited or partial result (a run recomputes the stage, render never re-solves)."""


RENDER_SETTINGS = {"burn_zone_sectors": 360, "track_bins": [360, 96], "fe_warp_fraction": 0.06,
                   "paraview": "balls, cage, inner race, outer race with land heat"}


def report_inputs(scene) -> dict:
    return {"name": scene.name, "description": scene.description, "render": RENDER_SETTINGS,
            "paraview_frames": scene.output.paraview_frames}


def compute(ctx: StageContext, show: bool = False) -> dict:
    from ..render.run_report import write_run_report

    return write_run_report(ctx.scene, ctx.run_dir, ctx.upstream, ctx.out_dir, ctx.progress, show=show)


STAGE = Stage(
    name="report",
    depends=("identify", "quasistatic", "simulate"),
    needed=lambda scene: True,
    inputs=report_inputs,
    compute=compute,
    summary="burn-zone and FE renders, HTML report",
)


class SceneNotOfResults(ValueError):
    """scene.toml does not describe the results of the run directory (edited, or written by a
    later command with other inputs): `render` draws no report over them."""


def finished_upstream(run_dir: Path, scene, progress=None) -> dict[str, str]:
    """name -> key of the upstream stages that finished in `run_dir` (manifest status done),
    after checking them against `scene` (pipeline.stages.consistency): SceneNotOfResults when a
    stage was computed from other inputs, StageResultsDamaged when one of its data files changed
    or is missing; a changed or missing figure is drawn again from the stage's data."""
    from ..render.stage_figures import redraw_figures
    from .consistency import check_run_directory, mismatch_message

    checks = [c for c in check_run_directory(run_dir, scene, _upstream_stages()) if c.name in STAGE.depends]
    mismatch = mismatch_message(run_dir, checks)
    if mismatch:
        raise SceneNotOfResults(mismatch)
    for check in checks:
        if check.damaged_data:
            raise StageResultsDamaged(
                f"{Path(run_dir) / check.name}: {', '.join(check.damaged_data[:5])} changed or went missing since the "
                f"{check.name} stage wrote it; render draws only results as computed. Recompute it with "
                f"`bearingsim run {Path(run_dir) / 'scene.toml'} --out {run_dir}`; then "
                f"`bearingsim render {run_dir}` redraws the report")
    for check in checks:
        if check.damaged_figures:
            if progress:
                progress(f"redrawing {check.name} figures", 0.0)
            drawn = redraw_figures(check.name, Path(run_dir) / check.name, scene, check.damaged_figures)
            logging.getLogger("bearingsim").info("render: drew %s of %s again (%s were missing or changed)",
                                                 ", ".join(drawn), check.name, ", ".join(check.damaged_figures))
    return {c.name: c.key for c in checks if c.key}


def _upstream_stages() -> list[Stage]:
    """The stages the report reads, in pipeline order."""
    from .identify import STAGE as IDENTIFY
    from .quasistatic import STAGE as QUASISTATIC
    from .simulate import STAGE as SIMULATE

    return [IDENTIFY, QUASISTATIC, SIMULATE]


def render_run(run_dir: Path, show: bool = False, progress=None) -> StageOutcome:
    """Redraw `<run_dir>/report/` from the saved results (atomically, as the stage does), and
    the figures of the upstream stages that are missing. The caller holds the run directory's
    lock.

    Raises FileNotFoundError when `run_dir` holds no scene.toml or no finished stage,
    SceneNotOfResults and StageResultsDamaged (finished_upstream).
    """
    from ..staging.runner import compute_stage, stage_key
    from ..scene.load import load_scene

    run_dir = Path(run_dir)
    scene_file = run_dir / "scene.toml"
    if not scene_file.is_file():
        raise FileNotFoundError(f"{run_dir} is not a run directory: it has no scene.toml "
                                "(written by `bearingsim run SCENE`; give the directory it printed)")
    scene = load_scene(scene_file)
    upstream = finished_upstream(run_dir, scene, progress)
    if not upstream:
        raise FileNotFoundError(f"{run_dir} holds no finished stage ({', '.join(STAGE.depends)}): "
                                f"run `bearingsim run {scene_file}` first")
    logging.getLogger("bearingsim").info("render %s: from stages %s", run_dir, sorted(upstream))
    stage = dataclasses.replace(STAGE, compute=lambda ctx: compute(ctx, show=show))
    key = stage_key(STAGE, scene, upstream)
    # the runner's own stage executor: same staged directory swap and manifest as `run`
    return compute_stage(stage, scene, run_dir, key, upstream, progress)
