"""Turn a dynamic run into files a user can open elsewhere: `timeseries.h5` (every variable
with units and a description), `impacts.csv`, the figures of docs/model.md §11, and the
numbers of `summary.json` (docs/scenes.md)."""

from __future__ import annotations

import io
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np

from ..artefacts import atomic_write_text
from .cage_metrics import DEFAULT_LAND_ROUGHNESS, CageSeries, GuideLand, PocketImpacts, cage_summary
from .verdict import cage_verdict
from .timeseries import Series, write_timeseries


def collect_series(run, params) -> dict[str, Series]:
    """Name, unit and describe every saved variable (see README 'Results'): the run's own
    named series (`BearingRun.channels()`); per-ball series are stored as float32."""
    return {name: Series(s.data, s.unit, s.description, s.dims, store_float32="ball" in s.dims)
            for name, s in run.channels().items()}


def write_impacts_csv(path: Path, impacts: np.ndarray, fields: tuple) -> None:
    units = {"time": "s", "ball": "-", "orbital_position": "rad", "peak_force": "N",
             "impact_speed": "m/s", "duration": "s"}
    buf = io.StringIO()
    buf.write(",".join(f"{f} [{units[f]}]" for f in fields) + "\n")
    for row in impacts:
        buf.write(",".join(str(int(x)) if f == "ball" else f"{x:.9g}" for f, x in zip(fields, row)) + "\n")
    atomic_write_text(path, buf.getvalue())


def land_boundary(scene) -> float:
    """eps0 of the land film, C_film = C (1 + eps0): physics.cage_race_boundary in the hybrid
    model, 0 in the purely hydrodynamic one (its film clearance is C)."""
    physics = scene.physics
    return float(physics.cage_race_boundary) if physics.cage_race == "hybrid" else 0.0


def land_roughness(scene) -> float:
    """Composite RMS roughness sigma of cage rim and land [m]: the scene's
    `cage.land_roughness` when it has one, else DEFAULT_LAND_ROUGHNESS (cage_metrics)."""
    value = getattr(scene.cage, "land_roughness", None) if scene.cage is not None else None
    return float(value) if value is not None else DEFAULT_LAND_ROUGHNESS


def guide_land_speed(scene) -> float:
    """Speed of the race whose land guides the cage [rad/s]: the inner race for an
    inner-guided cage, else the outer race, which the dynamic model keeps fixed."""
    return float(scene.speed.inner) if getattr(scene.cage, "guidance", "outer") == "inner" else 0.0


def write_simulation_results(out_dir: Path, scene, params, start, run, wall_time: float) -> dict:
    """Write all files of the simulate stage; return the summary dict."""
    from ..provenance import package_version

    series = collect_series(run, params)
    # timeseries.h5 is written in a thread while the summary and figures are computed: its gzip
    # (~3 s for a 0.8 s run) runs in HDF5 without the GIL, so on two cores it costs no wall time.
    # The pool's exit waits for the file, and result() re-raises a failed write here.
    with ThreadPoolExecutor(max_workers=1) as pool:
        written = pool.submit(write_timeseries, out_dir / "timeseries.h5", series,
                              {"scene": scene.name, "bearingsim": package_version(),
                               "ball_count": params.ball_count, "guide_clearance_m": params.guide_clearance})
        summary = _summary_and_figures(out_dir, scene, params, start, run, series, wall_time)
        written.result()
    return summary


def _summary_and_figures(out_dir: Path, scene, params, start, run, series: dict[str, Series],
                         wall_time: float) -> dict:
    """`impacts.csv`, the figures and the summary dict of `write_simulation_results`."""
    write_impacts_csv(out_dir / "impacts.csv", run.impacts, run.impact_fields)
    stats = dict(run.stats)
    summary = {"duration": float(run.t[-1]), "wall_time": wall_time,
               "integration_wall_time": stats.pop("wall_time"), **stats,
               "energy": run.energy, "kinematic_cage_speed": float(start["cage_angular_speed"])}
    if params.has_cage:
        impacts = run.impacts if len(run.impacts) else np.zeros((0, 4))
        summary.update(cage_summary(
            CageSeries(run.t, series["cage/position"].data[:, :2], series["cage/speed"].data,
                       series["cage_race/eccentricity_ratio"].data, series["cage_race/contact_azimuth"].data,
                       series["cage_race/friction_power"].data, series["inner_race/position"].data[:, 2],
                       film_power=series["cage_race/film_power"].data, min_film=series["cage_race/min_film"].data,
                       land_force=series["cage_race/force"].data, metal_force=series["cage_race/metal_force"].data),
            PocketImpacts(impacts[:, 3], times=impacts[:, 0], orbital_positions=impacts[:, 2]),
            GuideLand(params.guide_clearance, land_boundary(scene), land_roughness(scene),
                      film=scene.physics.cage_race in ("hybrid", "hydrodynamic"), speed=guide_land_speed(scene))))
        summary["verdict"] = cage_verdict(summary, guidance=getattr(scene.cage, "guidance", "outer"))
    else:
        summary["inner_race_axial_mean"] = float(np.mean(series["inner_race/position"].data[:, 2]))
    if scene.output.figures:
        from .simulation_figures import draw_simulation_figures

        draw_simulation_figures(out_dir, series, run, params, start, scene.name)
    return summary
