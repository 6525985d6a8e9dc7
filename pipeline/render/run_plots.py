"""The figures of a run, from its saved results: what `run.plot` returns and what the report
embeds (one drawing code; the report saves these Figures as its PNGs).

Each function reads the run's stage folders (timeseries.h5, summary.json, impacts.csv,
quasistatic.json) and returns a matplotlib Figure, or None when the run holds nothing to draw
(no cage, no dynamic run). Everything drawn from the time series marks the settled window of
`summary.json` as the verdict does.
"""

from __future__ import annotations

import csv
import json
from pathlib import Path

import numpy as np

from ..results.verdict import LAND_NAMES


def land_name(scene) -> str | None:
    """The guiding land's name from the scene's cage (`cage.guidance`): "outer-race land",
    "inner-race land", None for a ball-guided cage or none (no land burn zone)."""
    guidance = getattr(scene.cage, "guidance", None)
    if guidance is None or guidance == "ball":
        return None
    return LAND_NAMES.get(guidance, f"{guidance} land")


def _summary(simulate_dir: Path) -> dict | None:
    try:
        return json.loads((Path(simulate_dir) / "summary.json").read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None


def orbit_figure(scene, simulate_dir: Path, summary: dict | None = None):
    """The cage-centre orbit behind the verdict: start-up grey, settled window coloured, inside
    the guide clearance (ε = 1) and the film clearance C (1 + ε0); the verdict's loaded sector as
    a wedge and the cage centre at the thinnest film as a star. None without cage series."""
    from ..figures.dynamics import cage_orbit_figure
    from ..results.simulation_output import land_boundary
    from .run_series import _h5_attrs, read_series, settled_start

    path = Path(simulate_dir) / "timeseries.h5"
    summary = summary if summary is not None else _summary(simulate_dir)
    series = read_series(path, ("time", "cage/position", "cage_race/eccentricity_ratio", "cage/speed"))
    if "cage/position" not in series:
        return None
    clearance = _h5_attrs(path).get("guide_clearance_m")
    clearance = float(clearance) if clearance is not None else None
    t = np.asarray(series["time"].data, dtype=float)
    start = settled_start(series, summary, clearance)
    verdict = (summary or {}).get("verdict") or {}
    thinnest = None
    when = (summary or {}).get("land_film_min_time")
    if when is not None:
        h = verdict.get("land_film_min_um")
        thinnest = (int(np.argmin(np.abs(t - when))),
                    (f"thinnest film {h:.3g} µm" if h is not None else "thinnest film") + f" at t = {when:.4g} s")
    title = f"— {scene.name}"
    if verdict:
        title += f"\n{verdict_label(summary)}"
    return cage_orbit_figure(series["cage/position"].data, clearance, title, t=t, settled_from=start,
                             film_factor=1.0 + land_boundary(scene) if clearance and not _ball_guided(scene) else None,
                             sector_deg=verdict.get("sector_deg"), thinnest=thinnest)


def _ball_guided(scene) -> bool:
    """A cage carried by its pockets alone: no land, so no land film to draw."""
    return scene.cage is not None and scene.cage.guidance == "ball"


def verdict_label(summary: dict | None) -> str:
    """"pressed, elevated risk", with "too short to settle" when the run is (results.verdict)."""
    from ..results.verdict import short_label

    return short_label(summary)


def speed_figure(scene, simulate_dir: Path, quasistatic_dir: Path | None = None, summary: dict | None = None):
    """Cage speed against time with its settled mean and the epicyclic (pure rolling) speed of
    the quasi-static solution. None without a cage."""
    from ..figures.dynamics import cage_speed_figure
    from .run_series import read_series

    series = read_series(Path(simulate_dir) / "timeseries.h5", ("time", "cage/speed"))
    if "cage/speed" not in series:
        return None
    summary = summary if summary is not None else _summary(simulate_dir)
    kinematic = None
    if quasistatic_dir is not None:
        try:
            kinematic = json.loads((Path(quasistatic_dir) / "quasistatic.json").read_text(encoding="utf-8")).get("cage_speed")
        except (OSError, ValueError):
            kinematic = None
    window = (summary or {}).get("settled_window") or [None]
    return cage_speed_figure(series["time"].data, series["cage/speed"].data, kinematic, f"— {scene.name}", window[0])


def impacts_figure(scene, simulate_dir: Path, summary: dict | None = None):
    """Ball–pocket impacts (impacts.csv): peak force against time and orbital position."""
    from ..figures.dynamics import pocket_impacts_figure

    path = Path(simulate_dir) / "impacts.csv"
    with open(path, newline="", encoding="utf-8") as fh:
        rows = list(csv.reader(fh))
    names = [h.partition(" [")[0] for h in rows[0]]
    data = np.array([[float(v) for v in r] for r in rows[1:]], dtype=float).reshape(-1, len(names))
    column = {n: data[:, j] for j, n in enumerate(names)}
    summary = summary if summary is not None else _summary(simulate_dir)
    window = (summary or {}).get("settled_window") or [None]
    return pocket_impacts_figure(column["time"], np.radians(column["orbital_position"]), column["peak_force"],
                                 f"— {scene.name}", window[0])


def burn_zone_figure(scene, burn_map=None, simulate_dir: Path | None = None, summary: dict | None = None):
    """The polar burn map of the guiding land, centred on the hot sector (figures.burn_polar):
    from a BurnZoneMap, or built from the run's series. A cage without a land burn zone (ball
    guided, none) gets a picture that says so."""
    from ..figures.burn_polar import burn_zone_polar_figure

    land = land_name(scene)
    if burn_map is None and land is not None and simulate_dir is not None:
        from .run_series import burn_zone_of

        found = burn_zone_of(scene, Path(simulate_dir), summary if summary is not None else _summary(simulate_dir))
        burn_map = found[0] if found is not None else None
    if burn_map is None:
        return burn_zone_polar_figure(np.zeros(0), land=None if land is None else land, title=scene.name)
    return burn_zone_polar_figure(burn_map.sector_energy, burn_map.metal_energy, burn_map.film_energy,
                                  burn_map.sector, land, scene.name)


def load_distribution_figure(scene, quasistatic_dir: Path, polar: bool = True):
    """The quasi-static ball loads: polar round the bearing (default), or loads, contact angles
    and the crush screen against azimuth (`polar=False`, the quasistatic stage's PNG)."""
    from ..figures.quasistatic import ball_load_polar_figure, load_distribution_figure as by_azimuth

    result = json.loads((Path(quasistatic_dir) / "quasistatic.json").read_text(encoding="utf-8"))
    return ball_load_polar_figure(result, scene.name) if polar else by_azimuth(result, scene.name)
