"""The figures of the quasistatic and simulate stages drawn again from their saved results.

`bearingsim render` regenerates what a run drew; a figure (PNG) of a finished stage that was
deleted or changed is drawn again here from the files the stage wrote beside it — never by
solving — with the same figure functions the stage used:

- quasistatic: `load_distribution.png` from `quasistatic.json`, `crush_probability.png` from
  `tolerance_samples.csv` and the analysis in `quasistatic.json`;
- simulate: the figures of docs/model.md §11 from `timeseries.h5`, `impacts.csv` and
  `summary.json` (the settled window, the kinematic cage speed).

The redrawn files are recorded in the stage's manifest (size and checksum), so the stage stays
intact for the cache and for the next `render`.
"""

from __future__ import annotations

import csv
import json
from pathlib import Path
from types import SimpleNamespace

import numpy as np


def redraw_figures(stage: str, stage_dir: Path, scene, names: list[str]) -> list[str]:
    """Draw the figures `names` of the finished stage `stage` in `stage_dir` again and record
    them in its manifest; returns the names drawn. ValueError when the stage's data cannot
    give one of them."""
    drawers = {"quasistatic": _quasistatic_figures, "simulate": _simulate_figures}
    if stage not in drawers:
        raise ValueError(f"{stage_dir}: {', '.join(names)} changed or went missing; the {stage} stage has no "
                         "figures to draw again")
    stage_dir = Path(stage_dir)
    drawn = drawers[stage](stage_dir, scene, set(names))
    missing = sorted(set(names) - set(drawn))
    if missing:
        raise ValueError(f"{stage_dir}: {', '.join(missing)} changed or went missing and the {stage} stage's "
                         "data do not say how to draw it again")
    _record(stage_dir, drawn)
    return drawn


def _record(stage_dir: Path, names: list[str]) -> None:
    from ..staging.artefacts import MANIFEST, atomic_write_json, file_digest, read_manifest

    manifest = read_manifest(stage_dir)
    for name in names:
        path = stage_dir / name
        manifest.setdefault("files", {})[name] = {"size": path.stat().st_size, "sha256": file_digest(path)}
    atomic_write_json(stage_dir / MANIFEST, manifest)  # a new file: a manifest shared by hard link stays


def _quasistatic_figures(stage_dir: Path, scene, names: set[str]) -> list[str]:
    from ..figures.worker import draw

    result = json.loads((stage_dir / "quasistatic.json").read_text(encoding="utf-8"))
    drawn = []
    if "load_distribution.png" in names:
        draw("load_distribution", result, stage_dir / "load_distribution.png", title=scene.name)
        drawn.append("load_distribution.png")
    if "crush_probability.png" in names and result.get("crush_probability"):
        margin, regime = _tolerance_samples(stage_dir / "tolerance_samples.csv")
        draw("crush_probability", {"margin": margin, "regime": regime, "summary": result["crush_probability"]},
             stage_dir / "crush_probability.png", title=scene.name)
        drawn.append("crush_probability.png")
    return drawn


def _tolerance_samples(path: Path) -> tuple[list[float], list[int]]:
    """(margin, regime code) of the valid stacks of a `tolerance_samples.csv`."""
    codes = {"free": 0, "pressed": 1, "crushed": 2}
    margin, regime = [], []
    with open(path, newline="", encoding="utf-8") as fh:
        for row in csv.DictReader(fh):
            if row["regime"] in codes:
                margin.append(float(row["crush_margin [1]"]))
                regime.append(codes[row["regime"]])
    return margin, regime


def _simulate_figures(stage_dir: Path, scene, names: set[str]) -> list[str]:
    from ..results.simulation_figures import draw_simulation_figures
    from ..results.timeseries import read_timeseries

    series, attrs = read_timeseries(stage_dir / "timeseries.h5")
    summary = json.loads((stage_dir / "summary.json").read_text(encoding="utf-8"))
    has_cage = "cage/position" in series
    params = SimpleNamespace(has_cage=has_cage, guide_clearance=float(attrs.get("guide_clearance_m", 0.0) or 0.0))
    run = SimpleNamespace(impacts=_impacts(stage_dir / "impacts.csv"))
    start = {"cage_angular_speed": summary.get("kinematic_cage_speed", 0.0)}
    window = summary.get("settled_window") or [None]
    # draws them all (one pass over the series); each is recorded
    return draw_simulation_figures(stage_dir, series, run, params, start, scene.name, settled_from=window[0])


def _impacts(path: Path) -> np.ndarray:
    """impacts.csv as the run's impact array (its columns in the file's order)."""
    with open(path, newline="", encoding="utf-8") as fh:
        rows = list(csv.reader(fh))
    if len(rows) <= 1:
        return np.zeros((0, max(4, len(rows[0]) if rows else 4)))
    return np.array([[float(x) for x in row] for row in rows[1:]], dtype=float)
