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
from .run_series import BURN_DATASETS, OPTIONAL_DATASETS, _h5_attrs, burn_zone_of, read_series, settled_start  # noqa: F401

REPORT_FILE = "report.html"
BURN_RENDER, BURN_MAP, BURN_POLAR = "burn_zone_3d.png", "burn_zone_map.png", "burn_zone_polar.png"
ORBIT_FIGURE = "verdict_orbit.png"
RENDERS_FILE = "renders.json"


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


def render_burn_zone(scene, simulate_dir: Path, summary: dict | None, out_dir: Path, show: bool,
                     maps: dict | None = None) -> dict | None:
    """The burn-zone images of the guiding land (polar map, unrolled map, 3-D render: the outer
    ring's, or the inner ring's in the frame turning with it); None when the scene has no
    land-guided cage. The map drawn (a BurnZoneMap) is put in `maps["burn_zone"]` when `maps`
    is given."""
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
    b = scene.operating.bearing
    rim = b.outer_outside_diameter if profile.ring == "outer" else b.inner_bore_diameter
    render_burn_zone_3d(bzm, out_dir / BURN_RENDER, scene.name, 0.5 * rim if rim else None, show=show)
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
        "ring": profile.ring,
        "track_outside_fraction": bzm.track_outside_fraction,
        "track_max_N_s": float(np.max(bzm.track_density, initial=0.0)),
    }


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
