"""Everything the `report` stage writes, from the saved results of the upstream stages.

Files in the output directory: `report.html` (self-contained), `burn_zone_polar.png` (the
land's heat round the bearing, centred on the hot sector), `burn_zone_3d.png`,
`burn_zone_map.png`, `verdict_orbit.png` (the cage orbit behind the verdict: start-up and
settled window), `ball_loads_polar.png` (the quasi-static ball loads round the bearing), `fe_<axis>.png` + `fe_<axis>.vtu` per FE load case, and `renders.json`
(what was drawn, warp scales, burn-zone peak and heat). Nothing is solved here.

Everything drawn from the time series covers the settled window of `summary.json`
(`settled_window`); a summary written before it existed has none, and the window is then
found from the series by the same rule (`results.settled_window`), or is the whole run
when the series lack the cage.
"""

from __future__ import annotations

import logging
import math
import multiprocessing
from contextlib import contextmanager
from pathlib import Path
from typing import Callable

import numpy as np

from ..staging.artefacts import atomic_write_json
from ..results.timeseries import Series

REPORT_FILE = "report.html"
BURN_RENDER, BURN_MAP, BURN_POLAR = "burn_zone_3d.png", "burn_zone_map.png", "burn_zone_polar.png"
ORBIT_FIGURE = "verdict_orbit.png"
RENDERS_FILE = "renders.json"
BURN_DATASETS = ("time", "balls/position", "contacts/outer_contact_angle", "contacts/outer_load",
                 "cage_race/friction_power", "cage_race/contact_azimuth")
OPTIONAL_DATASETS = ("cage_race/eccentricity_ratio", "cage_race/film_power", "cage/position", "cage/speed")


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


def render_fe_cases(scene, identify_dir: Path, out_dir: Path, show: bool,
                    progress: Callable[[str, float], None]) -> list[dict]:
    """One PNG and one ParaView `.vtu` per FE load case of the identify stage."""
    from .fe_deflection import find_cases, render_case

    records = []
    cases = find_cases(identify_dir)
    for n, case in enumerate(cases):
        progress(f"FE deflection {case.axis}", 0.75 + 0.15 * n / max(1, len(cases)))
        record = render_case(case, out_dir / f"fe_{case.axis}.png", out_dir / f"fe_{case.axis}.vtu",
                             scene.name, show=show)
        record["vtu"] = f"fe_{case.axis}.vtu"
        records.append(record)
    return records


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
    """(BurnZoneMap, its OuterRaceProfile, whether the window is the settled one, whether the
    series hold the film power) from the
    saved series; None when the scene's cage is not guided by the outer race's land (the map
    of the land that guides it: pipeline.render.burn_zone_data)."""
    from ..results.simulation_output import guide_land_speed, land_boundary
    from .burn_zone_data import OuterRaceProfile, burn_zone_map, outer_semi_major_axis

    if scene.cage is None or scene.cage.guidance != "outer":
        return None
    parts = scene.operating
    profile = OuterRaceProfile.from_scene(parts.bearing, parts.cage)
    path = simulate_dir / "timeseries.h5"
    series = read_series(path, BURN_DATASETS + OPTIONAL_DATASETS)
    missing = [n for n in BURN_DATASETS if n not in series]
    if missing:
        raise ValueError(f"{path} lacks {', '.join(missing)}; rerun the "
                         "simulate stage (bearingsim simulate SCENE --force)")
    clearance = _h5_attrs(path).get("guide_clearance_m")
    start = settled_start(series, summary, float(clearance) if clearance is not None else None)
    startup = (summary or {}).get("startup") or {}
    semi_axis = outer_semi_major_axis(parts.bearing, parts.materials.ball, parts.materials.race,
                                      series["contacts/outer_contact_angle"].data,
                                      series["contacts/outer_load"].data)
    bzm = burn_zone_map(series, profile, summary_sector=(summary or {}).get("burn_zone_sector"),
                        semi_axis=semi_axis, start=start, land_boundary=land_boundary(scene),
                        land_speed=guide_land_speed(scene),
                        startup_metal_energy=_startup_metal(series, start, startup))
    return bzm, profile, start is not None, "cage_race/film_power" in series


def render_burn_zone(scene, simulate_dir: Path, summary: dict | None, out_dir: Path, show: bool,
                     maps: dict | None = None) -> dict | None:
    """The burn-zone images (polar map, unrolled map, 3-D render); None when the scene has no
    outer-race-guided cage. The map drawn (a BurnZoneMap) is put in `maps["burn_zone"]` when
    `maps` is given."""
    from ..figures import save_png
    from .burn_zone import heat_caption, render_burn_zone_3d, render_burn_zone_map
    from .run_plots import burn_zone_figure

    found = burn_zone_of(scene, simulate_dir, summary)
    if found is None:
        return None
    bzm, profile, settled, film_layer = found
    if maps is not None:
        maps["burn_zone"] = bzm
    save_png(burn_zone_figure(scene, bzm), out_dir / BURN_POLAR)
    render_burn_zone_map(bzm, out_dir / BURN_MAP, scene.name)
    outside = 0.5 * scene.operating.bearing.outer_outside_diameter if scene.operating.bearing.outer_outside_diameter else None
    render_burn_zone_3d(bzm, out_dir / BURN_RENDER, scene.name, outside, show=show)
    peak = bzm.peak_sector
    return {
        "render": BURN_RENDER, "map": BURN_MAP, "polar": BURN_POLAR, "sectors": bzm.sectors,
        "window_s": list(bzm.window),
        "settled": settled,
        "energy_total_J": float(bzm.sector_energy.sum()),
        "energy_metal_J": float(bzm.metal_energy.sum()),
        "energy_film_J": float(bzm.film_energy.sum()),
        "film_layer": film_layer,
        "startup_metal_energy_J": bzm.startup_metal_energy,
        "caption": heat_caption(bzm),
        "peak_sector_deg": math.degrees(bzm.sector_center(peak)) if peak is not None else None,
        "peak_sector_energy_J": float(bzm.sector_energy[peak]) if peak is not None else 0.0,
        "peak_areal_density_J_m2": float(bzm.sector_energy[peak] * bzm.areal_density_factor) if peak is not None else 0.0,
        "sector_deg": [math.degrees(v) for v in bzm.sector] if bzm.sector is not None else None,
        "land_overlap_mm": profile.land_overlap * 1e3,
        "track_outside_fraction": bzm.track_outside_fraction,
        "track_max_N_s": float(np.max(bzm.track_density, initial=0.0)),
    }


def _startup_metal(series: dict, start: float | None, startup: dict) -> float:
    """Metal-contact energy [J] before the settled window (the summary's when it has it)."""
    if startup.get("metal_energy") is not None:
        return float(startup["metal_energy"])
    if start is None:
        return 0.0
    from ..results.cage_metrics import split_weights

    t = np.asarray(series["time"].data, dtype=float)
    return float(np.sum(np.asarray(series["cage_race/friction_power"].data, dtype=float) * split_weights(t, start)[0]))


def render_verdict_orbit(scene, simulate_dir: Path, summary: dict | None, out_dir: Path) -> str | None:
    """`verdict_orbit.png`: the orbit behind the verdict (`run_plots.orbit_figure`); None when
    the run has no cage series."""
    from ..figures import save_png
    from .run_plots import orbit_figure

    fig = orbit_figure(scene, simulate_dir, summary)
    if fig is None:
        return None
    save_png(fig, out_dir / ORBIT_FIGURE)
    return ORBIT_FIGURE


def render_paraview(scene, simulate_dir: Path, out_dir: Path, burn_map=None) -> dict:
    """The ParaView motion series and the outer race with its land heat, into
    `out_dir/paraview/` (render.paraview_series); {what: path relative to out_dir}."""
    from .paraview_series import PARAVIEW_DIR, write_paraview

    files = write_paraview(simulate_dir / "timeseries.h5", scene, out_dir / PARAVIEW_DIR,
                           scene.output.paraview_frames, burn_map)
    return {k: f"{PARAVIEW_DIR}/{v}" for k, v in files.items()}


def _render_fe_cases_beside(scene, identify_dir: Path, out_dir: Path) -> list[dict]:
    """`render_fe_cases` off-screen in a second process, whose progress nobody shows."""
    return render_fe_cases(scene, identify_dir, out_dir, False, lambda text, fraction: None)


@contextmanager
def fe_renders(scene, identify_dir: Path | None, out_dir: Path, show: bool,
               progress: Callable[[str, float], None], beside: bool):
    """Yield a function that returns the FE load cases' render records (`render_fe_cases`; [] when
    there is no identify stage). With `beside`, on a machine with a second core, they are drawn in
    a second process while this one draws the burn zone and the ParaView series: they read only
    the identify stage, and the two take about as long. Otherwise, and when the second process
    cannot start or dies, they are drawn here."""
    from concurrent.futures import ProcessPoolExecutor
    from concurrent.futures.process import BrokenProcessPool

    from ..machine.cores import usable_cores

    if identify_dir is None:
        yield lambda: []
        return

    def here() -> list[dict]:
        return render_fe_cases(scene, identify_dir, out_dir, show, progress)

    if show or not beside or usable_cores() < 2:
        yield here
        return
    with ProcessPoolExecutor(max_workers=1, mp_context=multiprocessing.get_context("spawn")) as pool:
        try:
            job = pool.submit(_render_fe_cases_beside, scene, identify_dir, out_dir)
        except OSError as exc:  # no process could be started (process or memory limits)
            logging.getLogger("bearingsim").warning(
                "the FE renders' second process could not start (%s): drawing them in this process", exc)
            job = None

        def records() -> list[dict]:
            if job is None:
                return here()
            try:
                return job.result()
            except BrokenProcessPool as exc:
                logging.getLogger("bearingsim").warning(
                    "the FE renders' second process died (%s): drawing them in this process", exc)
                return here()

        yield records


def write_run_report(scene, run_dir: Path, upstream: dict[str, Path], out_dir: Path,
                     progress: Callable[[str, float], None] = lambda text, f: None,
                     show: bool = False) -> dict:
    """Render everything the upstream stages allow and write the report; return the
    stage info (file names and headline numbers)."""
    import json

    from .report import write_report_html

    run_dir, out_dir = Path(run_dir), Path(out_dir)
    burn = orbit = summary = paraview = None
    sim = upstream.get("simulate")
    has_series = sim is not None and (sim / "timeseries.h5").is_file()
    with fe_renders(scene, upstream.get("identify"), out_dir, show, progress, beside=has_series) as draw_fe:
        if has_series:
            progress("burn zone", 0.3)
            summary_path = sim / "summary.json"
            summary = json.loads(summary_path.read_text()) if summary_path.is_file() else None
            maps: dict = {}
            burn = render_burn_zone(scene, sim, summary, out_dir, show, maps)
            progress("verdict", 0.6)
            orbit = render_verdict_orbit(scene, sim, summary, out_dir)
            progress("ParaView series", 0.7)
            paraview = render_paraview(scene, sim, out_dir, maps.get("burn_zone"))
        progress("FE deflections", 0.8)
        fe_records = draw_fe()
    progress("report", 0.9)
    qs = upstream.get("quasistatic")
    if qs is not None and (qs / "quasistatic.json").is_file():
        from ..figures import save_png
        from .report import BALL_LOAD_FIGURE
        from .run_plots import load_distribution_figure

        save_png(load_distribution_figure(scene, qs, polar=True), out_dir / BALL_LOAD_FIGURE)
    write_report_html(out_dir / REPORT_FILE, scene, run_dir, upstream, out_dir, fe_records, burn,
                      evidence={"orbit": orbit})
    info = {"report": REPORT_FILE, "fe_cases": [r["file"] for r in fe_records],
            "burn_zone": burn, "paraview": paraview}
    atomic_write_json(out_dir / RENDERS_FILE, {"fe": fe_records, "burn_zone": burn, "paraview": paraview})
    return info
