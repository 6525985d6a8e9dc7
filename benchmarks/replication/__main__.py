"""Rerun every run of docs/replication.md, write its numbers and the page:

    python -m benchmarks.replication [--work runs/replication] [--only NAME ...] [--page-only]

From the repository root with the package installed. The runs (`plan.py`) go to
WORK/<name>/ (bearingsim run directories: a run whose inputs and code are unchanged is not
repeated, so a second call only re-measures); their numbers, the crush screen's sensitivities
and the closed-form estimates go to benchmarks/replication/data/replication.json, and the page to
docs/replication.md. `--only` reruns the named runs and keeps the others' numbers from the
JSON; `--page-only` rewrites the page from the JSON without running anything.

The runs are made one after another in this process, on one core.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import sys
import time
from pathlib import Path

from . import measure, page, plan, screen

DATA = Path(__file__).resolve().parent / "data" / "replication.json"
PAGE = Path("docs/replication.md")


def resolved_value(scene, dotted: str):
    """The value a resolved scene uses for a dotted key (defaults included)."""
    section, key = dotted.split(".", 1)
    if section == "thermal":
        temps = scene.temperatures
        return {"inner_ring": temps.inner_ring, "outer_ring": temps.outer_ring, "ball": temps.ball, "cage": temps.cage}
    if section == "lubricant":
        return getattr(scene.lubricant, key)
    if section == "bearing":
        return getattr(scene.nominal.bearing if scene.nominal else scene.bearing, key)
    value = getattr({"physics": scene.physics, "solver": scene.solver, "hinge": scene.hinge,
                     "load": scene.load, "speed": scene.speed}[section], key)
    return list(value) if isinstance(value, tuple) else value


def preset_keys() -> dict:
    """Each key of the page's preset table as the preset scene and the shipped scene resolve it."""
    from bearingsim.pipeline.scene.load import load_scene

    out = {}
    for case, name in plan.PRESETS.items():
        preset, shipped = load_scene(name), load_scene(plan.CASES[case])
        out[case] = {key: {"preset": resolved_value(preset, key), "shipped": resolved_value(shipped, key)}
                     for _, key, _ in page.PAPER_ROWS}
    return out


def axial_positions() -> dict:
    """The inner ring's quasi-static axial position [mm] of each case as shipped, as the preset
    sets it, and with the diametral clearance that puts it where the paper's runs settle
    (docs/validation.md §12.7)."""
    from bearingsim.pipeline.scene.load import load_scene
    from bearingsim.pipeline.stages.quasistatic import solve

    d_o = plan.OUTER_GROOVE_CENTRE + (140.5e-6 - plan.PD_TABLE1)
    out = {}
    for case in ("a", "b"):
        for label, scene, overrides in (("shipped", plan.CASES[case], []), ("paper", plan.PRESETS[case], []),
                                        ("pd140", plan.CASES[case], [f"bearing.outer_groove_center_diameter={d_o!r}"])):
            out[f"{case}-{label}"] = 1e3 * float(solve(load_scene(scene, overrides)).inner_displacement[2])
    return out


def run_all(work: Path, only: set[str] | None, progress=print) -> dict:
    """Make (or find up to date) every run of the plan and measure it. A run the product's cache
    serves keeps the wall time it took when it was made (from the previous JSON)."""
    import bearingsim

    previous = json.loads(DATA.read_text(encoding="utf-8"))["runs"] if DATA.is_file() else {}
    results = {}
    for name, scene, overrides in plan.runs():
        if only and name not in only:
            if name in previous:
                results[name] = previous[name]
            continue
        t0 = time.perf_counter()
        run = bearingsim.run(scene, work / name, stages=["simulate"], overrides=overrides + plan.FIGURES_OFF)
        wall = time.perf_counter() - t0
        computed = run.stages.get("simulate") == "computed"
        if not computed and name in previous:
            wall = previous[name]["wall_time_s"]
        results[name] = {"scene": scene, "overrides": overrides, "wall_time_s": wall, "computed_now": computed,
                         **measure.measure(work / name)}
        r = results[name]
        progress(f"{name}: {r['class']} (eps {r['eps_mean']:.2f}), metal {100 * r['metal_fraction']:.0f} %, "
                 f"p95 {r['impact_p95_N']:.0f} N, {wall:.0f} s{'' if computed else ' (made earlier)'}",
                 file=sys.stderr, flush=True)
    return results


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--work", type=Path, default=Path("runs/replication"), help="folder of the run directories")
    ap.add_argument("--only", nargs="+", help="rerun only these runs (names of plan.py)")
    ap.add_argument("--page-only", action="store_true", help="rewrite the page from the JSON, run nothing")
    a = ap.parse_args(argv)
    if not a.page_only:
        from bearingsim.pipeline.staging.provenance import versions

        load_before = os.getloadavg()
        runs = run_all(a.work, set(a.only) if a.only else None)
        t0 = time.perf_counter()
        sens = screen.sensitivities()
        t_screen = time.perf_counter() - t0
        t_runs = sum(r["wall_time_s"] for r in runs.values())
        generated = {"command": "python -m benchmarks.replication", "runs": len(runs),
                     "runs_wall_time_s": t_runs, "screen_wall_time_s": t_screen,
                     "total_wall_time_s": t_runs + t_screen,
                     "runs_made_now": sum(bool(r.get("computed_now")) for r in runs.values()),
                     "load_average_before": load_before[0], "load_average_after": os.getloadavg()[0],
                     "cpu_count": os.cpu_count(), "machine": platform.machine(),
                     "git_commit": versions().get("git_commit"), "source_fingerprint": versions().get("source_fingerprint")}
        data = {"generated": generated, "preset": preset_keys(), "axial_positions_mm": axial_positions(),
                "screen": sens, "runs": runs}
        DATA.write_text(json.dumps(data, indent=1, ensure_ascii=False) + "\n", encoding="utf-8")
    PAGE.write_text(page.render(json.loads(DATA.read_text(encoding="utf-8"))), encoding="utf-8")
    print(f"wrote {PAGE} from {DATA}", file=sys.stderr)


if __name__ == "__main__":
    main()
