"""Turn a dynamic run into files a user can open elsewhere: `timeseries.h5` (every variable
with units and a description), `impacts.csv`, the figures of docs/model.md §11, and the
numbers of `summary.json` (docs/outputs.md)."""

from __future__ import annotations

import io
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np

from ...dynamics.journal.land_laws import LAWS as LAND_LAWS
from ..staging.artefacts import atomic_write_text
from .cage_metrics import DEFAULT_LAND_ROUGHNESS, CageSeries, GuideLand, PocketImpacts, cage_summary
from .summary_keys import summary_units
from .verdict import cage_verdict
from .timeseries import Series, write_timeseries


def collect_series(run, params) -> dict[str, Series]:
    """Name, unit and describe every saved variable (see README 'Results'): the run's own
    named series (`BearingRun.channels()`); per-ball series are stored as float32."""
    return {name: Series(s.data, s.unit, s.description, s.dims, store_float32="ball" in s.dims)
            for name, s in run.channels().items()}


IMPACT_UNITS = {"time": "s", "ball": "1", "orbital_position": "deg", "peak_force": "N",
                "impact_speed": "m/s", "duration": "s"}


def write_impacts_csv(path: Path, impacts: np.ndarray, fields: tuple) -> None:
    """One row per ball-pocket impact, units in the header; the orbital position (rad in the
    model's impact log) in degrees 0–360 from +x towards +y, as every user-facing file."""
    buf = io.StringIO()
    buf.write(",".join(f"{f} [{IMPACT_UNITS[f]}]" for f in fields) + "\n")
    for row in impacts:
        cells = []
        for f, x in zip(fields, row):
            if f == "ball":
                cells.append(str(int(x)))
            elif f == "orbital_position":
                cells.append(f"{np.degrees(x) % 360.0:.9g}")
            else:
                cells.append(f"{x:.9g}")
        buf.write(",".join(cells) + "\n")
    atomic_write_text(path, buf.getvalue())


def land_boundary(scene) -> float:
    """eps0 of the land film, C_film = C (1 + eps0): physics.cage_race_boundary for a land law
    with a boundary layer (`land_laws`, flag "boundary": the hybrid law), 0 otherwise (the purely
    hydrodynamic law's film clearance is C)."""
    physics = scene.physics
    return float(physics.cage_race_boundary) if LAND_LAWS[physics.cage_race].flags["boundary"] else 0.0


def land_roughness(scene) -> float:
    """Composite RMS roughness sigma of cage rim and land [m]: the scene's
    `cage.land_roughness` when it has one, else DEFAULT_LAND_ROUGHNESS (cage_metrics)."""
    value = getattr(scene.operating.cage, "land_roughness", None) if scene.cage is not None else None
    return float(value) if value is not None else DEFAULT_LAND_ROUGHNESS


def guide_land_speed(scene) -> float:
    """Speed of the race whose land guides the cage [rad/s]: the inner race for an
    inner-guided cage, else the outer race, which the dynamic model keeps fixed."""
    return float(scene.speed.inner) if getattr(scene.cage, "guidance", "outer") == "inner" else 0.0


def cage_series(t, series: dict[str, Series], scene, guide_clearance: float) -> CageSeries:
    """The cage's series for `cage_summary`, relative to what guides it: the fixed outer ring's
    land (the cage centre as saved), the inner ring's land (the cage centre less the inner
    race's, the land's heat in the frame turning with it), or the ball set (its centre, the
    mean of the ball centres, with the offset over the pockets' radial play as eccentricity
    and its direction as the contact azimuth; no land film)."""
    guidance = scene.cage.guidance
    xy = series["cage/position"].data[:, :2]
    eps, azimuth = series["cage_race/eccentricity_ratio"].data, series["cage_race/contact_azimuth"].data
    land_angle = None
    if guidance == "inner":
        xy = xy - series["inner_race/position"].data[:, :2]
        land_angle = series["inner_race/angle"].data
    elif guidance == "ball":
        xy = xy - series["balls/position"].data[:, :, :2].mean(axis=1)
        eps = np.hypot(xy[:, 0], xy[:, 1]) / guide_clearance
        azimuth = np.arctan2(xy[:, 1], xy[:, 0])
    return CageSeries(t, xy, series["cage/speed"].data, eps, azimuth, series["cage_race/friction_power"].data,
                      series["inner_race/position"].data[:, 2], film_power=series["cage_race/film_power"].data,
                      min_film=series["cage_race/min_film"].data, land_force=series["cage_race/force"].data,
                      metal_force=series["cage_race/metal_force"].data, land_angle=land_angle,
                      cage_angle=series["cage/angle"].data if "cage/angle" in series else None,
                      pocket_force=series["pocket/force"].data if "pocket/force" in series else None)


def write_simulation_results(out_dir: Path, scene, params, start, run, wall_time: float,
                             quasistatic: dict | None = None) -> dict:
    """Write all files of the simulate stage; return the summary dict. `quasistatic`: the
    quasi-static stage's result, whose crush screen the summary repeats."""
    from ..staging.provenance import package_version

    series = collect_series(run, params)
    # timeseries.h5 is written in a thread while the summary and figures are computed: its gzip
    # runs in HDF5 without the GIL, so on two cores it costs no wall time.
    # The pool's exit waits for the file, and result() re-raises a failed write here.
    with ThreadPoolExecutor(max_workers=1) as pool:
        written = pool.submit(write_timeseries, out_dir / "timeseries.h5", series,
                              {"scene": scene.name, "bearingsim": package_version(),
                               "ball_count": params.ball_count, "guide_clearance_m": params.guide_clearance})
        summary = _summary_and_figures(out_dir, scene, params, start, run, series, wall_time,
                                       screen_summary(quasistatic))
        written.result()
    summary["units"] = summary_units(summary)
    return summary


def _non_guiding(t, series: dict[str, Series], scene) -> dict:
    """The gap to the non-guiding land along the run (pipeline.results.non_guiding)."""
    from .non_guiding import non_guiding_gap, non_guiding_summary

    cage, bearing = scene.operating.cage, scene.operating.bearing
    clearance = cage.non_guiding_clearance(bearing)
    if clearance is None:
        return {}
    gaps = []
    for ring in cage.non_guiding_rings():
        pair = bearing.shoulders(ring)
        if pair is None:
            continue
        own = cage.clearance_to(ring, min(pair) if ring == "outer" else max(pair))
        inner = ring == "inner"
        gaps.append(non_guiding_gap(series["cage/position"].data, series["inner_race/position"].data if inner else None,
                                    series["inner_race/axis"].data if inner else None, own, 0.5 * cage.width))
    return non_guiding_summary(t, np.minimum.reduce(gaps), clearance)


def screen_summary(quasistatic: dict | None) -> dict | None:
    """The crush screen's verdict at the clearances the run used (docs/model.md §10.1–§10.2):
    regime, margin, the operating clearances and, with tolerances, the crush probability."""
    screen = (quasistatic or {}).get("cage_screen")
    if not screen:
        return None
    clear = screen.get("clearances", {})
    out = {"regime": screen["regime"], "crush_margin": screen["crush_margin"],
           "crush_margin_at_reference_temperature": screen.get("crush_margin_at_reference_temperature"),
           "guide_clearance": screen["guide_clearance"], "pocket_clearance": screen["pocket_clearance"],
           "non_guiding_gap": screen.get("non_guiding_gap"),
           "guide_clearance_at_reference_temperature": clear.get("guide_clearance", {}).get("reference"),
           "pocket_clearance_at_reference_temperature": clear.get("pocket_clearance", {}).get("reference"),
           "temperatures_degC": clear.get("temperatures_degC")}
    tol = (quasistatic or {}).get("crush_probability")
    if tol:
        out["crush_probability"] = tol["crush_probability"]
        out["crush_probability_standard_error"] = tol["regime_probability"]["crushed"]["standard_error"]
        out["tolerance_samples"] = tol["samples"]
        out["margin_p5"] = tol["margin_percentiles"]["p5"]
    return out


def energy_balance(energy: dict, series: dict[str, Series]) -> dict:
    """The run's work and dissipation [J] with the change of the stored (kinetic, Hertz and
    hinge) energy over the run and what the balance leaves: drive + external - dissipated -
    stored change. The residual is the integrator's own dissipation (HHT-alpha damps the
    highest frequencies) and the error of integrating the powers over the steps; docs/model.md §11."""
    stored = sum(float(series[name].data[-1] - series[name].data[0])
                 for name in ("energy/kinetic", "energy/hertz", "energy/hinge") if name in series)
    residual = energy["drive"] + energy["external"] - energy["dissipated"] - stored
    return {**energy, "stored_change": stored, "balance_residual": residual}


def _summary_and_figures(out_dir: Path, scene, params, start, run, series: dict[str, Series],
                         wall_time: float, screen: dict | None = None) -> dict:
    """`impacts.csv`, the figures and the summary dict of `write_simulation_results`."""
    write_impacts_csv(out_dir / "impacts.csv", run.impacts, run.impact_fields)
    stats = dict(run.stats)
    summary = {"duration": float(run.t[-1]), "wall_time": wall_time,
               "integration_wall_time": stats.pop("wall_time"), **stats,
               "energy": energy_balance(run.energy, series), "kinematic_cage_speed": float(start["cage_angular_speed"])}
    if params.has_cage:
        impacts = run.impacts if len(run.impacts) else np.zeros((0, 4))
        on_land = scene.cage.guide_ring is not None
        summary.update(cage_summary(
            cage_series(run.t, series, scene, params.guide_clearance),
            PocketImpacts(impacts[:, 3], times=impacts[:, 0], orbital_positions=impacts[:, 2]),
            GuideLand(params.guide_clearance, land_boundary(scene), land_roughness(scene),
                      film=on_land and LAND_LAWS[scene.physics.cage_race].film,
                      speed=guide_land_speed(scene))))
        summary["cage_guidance"] = scene.cage.guidance
        summary.update(_non_guiding(run.t, series, scene))
        if summary.get("non_guiding_gap_min", 0.0) < 0.0:
            summary["warnings"].append(
                f"the cage touches the non-guiding land ({100 * summary['non_guiding_contact_fraction']:.2g} % of the "
                f"run, gap down to {summary['non_guiding_gap_min'] * 1e6:.0f} µm): the model applies no force there")
        if screen is not None:
            summary["crush_screen"] = screen
        summary["verdict"] = cage_verdict(summary, guidance=getattr(scene.cage, "guidance", "outer"))
    else:
        summary["inner_race_axial_mean"] = float(np.mean(series["inner_race/position"].data[:, 2]))
    if scene.output.figures:
        from .simulation_figures import draw_simulation_figures

        window = summary.get("settled_window") or [None]
        draw_simulation_figures(out_dir, series, run, params, start, scene.name, settled_from=window[0])
    return summary
