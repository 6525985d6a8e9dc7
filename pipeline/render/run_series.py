"""The saved series a run's figures read: named datasets of timeseries.h5, the settled window,
and the burn-zone map of the guiding land (pipeline.render.burn_zone_data). Nothing is solved here."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..results.timeseries import Series

BURN_DATASETS = ("time", "balls/position", "cage_race/friction_power", "cage_race/contact_azimuth")
OPTIONAL_DATASETS = ("cage_race/eccentricity_ratio", "cage_race/film_power", "cage/position", "cage/speed")


def burn_datasets(ring: str) -> tuple[str, ...]:
    """The series the burn zone of the `ring`'s land needs (the inner ring's: its angle too)."""
    return BURN_DATASETS + (f"contacts/{ring}_contact_angle", f"contacts/{ring}_load") + (
        ("inner_race/angle",) if ring == "inner" else ())


def read_series(path: Path, names: tuple[str, ...]) -> dict[str, Series]:
    """Only the named datasets of a `timeseries.h5` (a 0.8 s run holds ~250 MB; the
    burn zone needs a fraction). Same result as `read_timeseries` for those names."""
    import h5py

    out = {}
    with h5py.File(path, "r") as h5:
        for name in names:
            if name in h5:
                ds = h5[name]
                out[name] = Series(ds[()], str(ds.attrs.get("units", "")), str(ds.attrs.get("description", "")),
                                   tuple(str(ds.attrs.get("dims", "")).split(",")))
    return out


def _h5_attrs(path: Path) -> dict:
    import h5py

    with h5py.File(path, "r") as h5:
        return {k: v for k, v in h5.attrs.items()}


def settled_start(series: dict, summary: dict | None, guide_clearance: float | None) -> float | None:
    """Start of the settled window [s]: the summary's, else found from the series by the
    summary's rule, else None (the whole run)."""
    window = (summary or {}).get("settled_window")
    if window and window[0] is not None:
        return float(window[0])
    if all(n in series for n in ("cage_race/eccentricity_ratio", "cage/position", "cage/speed")):
        from ..results.settled_window import detect_settled_window

        return detect_settled_window(series["time"].data, series["cage_race/eccentricity_ratio"].data,
                                     series["cage/position"].data[:, :2], series["cage/speed"].data,
                                     guide_clearance).start
    return None


def burn_zone_of(scene, simulate_dir: Path, summary: dict | None):
    """(BurnZoneMap, its RaceProfile, whether the window is the settled one, whether the series
    hold the film power) from the saved series: the map of the land that guides the cage (the
    outer ring's, or the inner ring's in the frame turning with it; pipeline.render.burn_zone_data);
    None for a scene without a land-guided cage."""
    from ..results.simulation_output import guide_land_speed, land_boundary
    from .burn_zone_data import RaceProfile, burn_zone_map, race_semi_major_axis

    if scene.cage is None or scene.cage.guide_ring is None:
        return None
    ring = scene.cage.guide_ring
    parts = scene.operating
    profile = RaceProfile.from_scene(parts.bearing, parts.cage)
    path = simulate_dir / "timeseries.h5"
    needed = burn_datasets(ring)
    series = read_series(path, needed + OPTIONAL_DATASETS)
    missing = [n for n in needed if n not in series]
    if missing:
        raise ValueError(f"{path} lacks {', '.join(missing)}; rerun the "
                         "simulate stage (bearingsim simulate SCENE --force)")
    clearance = _h5_attrs(path).get("guide_clearance_m")
    start = settled_start(series, summary, float(clearance) if clearance is not None else None)
    startup = (summary or {}).get("startup") or {}
    semi_axis = race_semi_major_axis(parts.bearing, parts.materials.ball, parts.materials.race,
                                     series[f"contacts/{ring}_contact_angle"].data,
                                     series[f"contacts/{ring}_load"].data, ring)
    bzm = burn_zone_map(series, profile, summary_sector=(summary or {}).get("burn_zone_sector"),
                        semi_axis=semi_axis, start=start, land_boundary=land_boundary(scene),
                        land_speed=guide_land_speed(scene),
                        startup_metal_energy=_startup_metal(series, start, startup))
    return bzm, profile, start is not None, "cage_race/film_power" in series


def _startup_metal(series: dict, start: float | None, startup: dict) -> float:
    """Metal-contact energy [J] before the settled window (the summary's when it has it)."""
    if startup.get("metal_energy") is not None:
        return float(startup["metal_energy"])
    if start is None:
        return 0.0
    from ..results.cage_metrics import split_weights

    t = np.asarray(series["time"].data, dtype=float)
    return float(np.sum(np.asarray(series["cage_race/friction_power"].data, dtype=float) * split_weights(t, start)[0]))
