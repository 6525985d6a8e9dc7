"""Everything the `report` stage writes, from the saved results of the upstream stages.

Files in the output directory: `report.html` (self-contained), `burn_zone_3d.png`,
`burn_zone_map.png`, `fe_<axis>.png` + `fe_<axis>.vtu` per FE load case, and
`renders.json` (what was drawn, warp scales, burn-zone peak). Nothing is solved here.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Callable

import numpy as np

from ..artefacts import atomic_write_json
from ..results.timeseries import Series

REPORT_FILE = "report.html"
BURN_RENDER, BURN_MAP = "burn_zone_3d.png", "burn_zone_map.png"
RENDERS_FILE = "renders.json"
BURN_DATASETS = ("time", "balls/position", "contacts/outer_contact_angle", "contacts/outer_load",
                 "cage_race/friction_power", "cage_race/contact_azimuth")


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
        progress(f"FE deflection {case.axis}", 0.1 + 0.5 * n / max(1, len(cases)))
        record = render_case(case, out_dir / f"fe_{case.axis}.png", out_dir / f"fe_{case.axis}.vtu",
                             scene.name, show=show)
        record["vtu"] = f"fe_{case.axis}.vtu"
        records.append(record)
    return records


def render_burn_zone(scene, simulate_dir: Path, summary: dict | None, out_dir: Path, show: bool) -> dict | None:
    """Both burn-zone images; None when the scene has no outer-race-guided cage."""
    from .burn_zone import render_burn_zone_3d, render_burn_zone_map
    from .burn_zone_data import OuterRaceProfile, burn_zone_map, outer_semi_major_axis

    if scene.cage is None or scene.cage.guidance != "outer":
        return None
    profile = OuterRaceProfile.from_scene(scene.bearing, scene.cage)
    series = read_series(simulate_dir / "timeseries.h5", BURN_DATASETS)
    missing = [n for n in BURN_DATASETS if n not in series]
    if missing:
        raise ValueError(f"{simulate_dir / 'timeseries.h5'} lacks {', '.join(missing)}; rerun the "
                         "simulate stage (bearingsim simulate SCENE --force)")
    semi_axis = outer_semi_major_axis(scene.bearing, scene.materials.ball, scene.materials.race,
                                      series["contacts/outer_contact_angle"].data,
                                      series["contacts/outer_load"].data)
    bzm = burn_zone_map(series, profile, summary_sector=(summary or {}).get("burn_zone_sector"),
                        semi_axis=semi_axis)
    render_burn_zone_map(bzm, out_dir / BURN_MAP, scene.name)
    outside = 0.5 * scene.bearing.outer_outside_diameter if scene.bearing.outer_outside_diameter else None
    render_burn_zone_3d(bzm, out_dir / BURN_RENDER, scene.name, outside, show=show)
    peak = bzm.peak_sector
    return {
        "render": BURN_RENDER, "map": BURN_MAP, "sectors": bzm.sectors,
        "energy_total_J": float(bzm.sector_energy.sum()),
        "energy_last_half_J": _energy_last_half(series),
        "peak_sector_deg": math.degrees(bzm.sector_center(peak)) if peak is not None else None,
        "peak_sector_energy_J": float(bzm.sector_energy[peak]) if peak is not None else 0.0,
        "peak_areal_density_J_m2": float(bzm.sector_energy[peak] * bzm.areal_density_factor) if peak is not None else 0.0,
        "sector_deg": [math.degrees(v) for v in bzm.sector] if bzm.sector is not None else None,
        "land_overlap_mm": profile.land_overlap * 1e3,
        "track_outside_fraction": bzm.track_outside_fraction,
        "track_max_N_s": float(np.max(bzm.track_density, initial=0.0)),
    }


def _energy_last_half(series: dict) -> float:
    """Metal-contact energy [J] in the analysis window of the summary (last half of the
    run): tells a start-up transient from a rub that persists."""
    from ..results.cage_metrics import analysis_window, time_weights

    t = np.asarray(series["time"].data, dtype=float)
    energy = np.asarray(series["cage_race/friction_power"].data, dtype=float) * time_weights(t)
    return float(energy[analysis_window(t)].sum())


def write_run_report(scene, run_dir: Path, upstream: dict[str, Path], out_dir: Path,
                     progress: Callable[[str, float], None] = lambda text, f: None,
                     show: bool = False) -> dict:
    """Render everything the upstream stages allow and write the report; return the
    stage info (file names and headline numbers)."""
    import json

    from .report import write_report_html

    run_dir, out_dir = Path(run_dir), Path(out_dir)
    fe_records = []
    if "identify" in upstream:
        fe_records = render_fe_cases(scene, upstream["identify"], out_dir, show, progress)
    burn = None
    sim = upstream.get("simulate")
    if sim is not None and (sim / "timeseries.h5").is_file():
        progress("burn zone", 0.65)
        summary_path = sim / "summary.json"
        summary = json.loads(summary_path.read_text()) if summary_path.is_file() else None
        burn = render_burn_zone(scene, sim, summary, out_dir, show)
    progress("report", 0.9)
    write_report_html(out_dir / REPORT_FILE, scene, run_dir, upstream, out_dir, fe_records, burn)
    info = {"report": REPORT_FILE, "fe_cases": [r["file"] for r in fe_records],
            "burn_zone": burn}
    atomic_write_json(out_dir / RENDERS_FILE, {"fe": fe_records, "burn_zone": burn})
    return info
