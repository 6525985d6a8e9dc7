"""Do the shipped solver defaults give the statistics of a tight-tolerance run? (docs/validation.md)

    python -m benchmarks.default_vs_reference [--cases helicopter-b helicopter-a] [--out DIR] [--data DIR]

For each reference case the full run (0.8 s) is integrated four times at the scene's own
tolerance and four times at a 10x tighter one (`solver.rtol` 1e-7, the reference). Within a
group the runs differ only in the moment load, by 0, +1e-6, -1e-6 and +2e-6 of its value (0.4 to
0.9 mN.m on 430 N.m): far below what a test rig holds its load to, so each run is another run
of the same bearing, and the range of a statistic over the four is its run-to-run spread at that
tolerance. A cage that wanders on its film (case a) makes each run one sample of a chaotic
motion, and the spread shows it; one pressed onto its land (case b) barely varies.

A statistic agrees when the means of the two groups differ by no more than the larger of the
two groups' ranges. Class and risk must be equal in every run. The runs go to --out (default
runs/default_vs_reference), and default_vs_reference.json and .md to --data (default
benchmarks/data, where docs/validation.md reads them); `--reuse` reads a run whose summary.json
exists instead of running it again. Wall times are on whatever else the machine runs; the load
average is recorded.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import time
from pathlib import Path

TOLERANCES = {"default": [], "reference": ["solver.rtol=1e-7"]}  # group: overrides
MOMENT_CHANGES = (0.0, 1e-6, -1e-6, 2e-6)  # relative: one run of the rig after another
NUMERIC = ("cage_eps_mean", "cage_metal_contact_fraction", "cage_whirl_ratio", "cage_offset_azimuth_mean",
           "cage_land_force_mean", "land_film_min", "pocket_impacts", "pocket_impact_force_p95",
           "burn_zone_energy_total", "cage_speed_mean")
SECTORS = ("cage_offset_sector", "burn_zone_sector")


def runs(scene_name: str) -> dict[str, list[str]]:
    """label -> overrides: each tolerance group with each moment change."""
    from bearingsim.pipeline.scene.load import load_scene

    moment = load_scene(scene_name).load.moment
    return {f"{group}, moment {dm:+.0e}": overrides + [f"load.moment={moment * (1.0 + dm)!r}"]
            for group, overrides in TOLERANCES.items() for dm in MOMENT_CHANGES}


def run_case(scene_name: str, out: Path, reuse: bool = False, progress=print) -> dict:
    import bearingsim

    rows = {}
    # compile (or load) the kernels before anything is timed
    if not reuse:
        bearingsim.run(scene_name, out / scene_name / "warm-up", stages=["simulate"],
                       overrides=["solver.duration=1e-3"], force=["simulate"])
    for label, overrides in runs(scene_name).items():
        run_dir = out / scene_name / label.replace(" ", "_").replace(",", "").replace("+", "p")
        summary = run_dir / "simulate" / "summary.json"
        t0 = time.perf_counter()
        if not (reuse and summary.exists()):
            bearingsim.run(scene_name, run_dir, stages=["simulate"], overrides=overrides, force=["simulate"])
        wall = time.perf_counter() - t0
        s = json.loads(summary.read_text())
        v = s["verdict"]
        rows[label] = {"class": v["class"], "risk": v["risk"], "wall": wall,
                       "integration_wall_time": s["integration_wall_time"], "steps": s["steps"],
                       **{k: s.get(k) for k in NUMERIC + SECTORS}}
        progress(f"{scene_name} {label}: {v['class']}/{v['risk']}, integration {s['integration_wall_time']:.1f} s, "
                 f"{s['steps']} steps")
    return {"runs": rows, "agreement": agreement(rows)}


def agreement(rows: dict) -> dict:
    groups = {"default": [r for k, r in rows.items() if k.startswith("default")],
              "reference": [r for k, r in rows.items() if k.startswith("reference")]}
    out = {"class": len({(r["class"], r["risk"]) for r in rows.values()}) == 1}
    for key in NUMERIC:
        vals = {g: [r[key] for r in runs if r[key] is not None] for g, runs in groups.items()}
        if not all(vals.values()):
            continue
        means = {g: sum(v) / len(v) for g, v in vals.items()}
        spread = max(max(v) - min(v) for v in vals.values())
        out[key] = {"means": means, "spread": spread,
                    "agrees": abs(means["default"] - means["reference"]) <= spread}
    return out


def markdown(study: dict) -> str:
    lines = []
    for case, res in study["cases"].items():
        runs = res["runs"]
        labels = list(runs)
        lines += [f"### {case}", "", "| statistic | " + " | ".join(labels) + " | means (default / reference), spread | agrees |",
                  "|---|" + "---|" * (len(labels) + 2)]
        lines.append("| class / risk | " + " | ".join(f"{runs[k]['class']} / {runs[k]['risk']}" for k in labels)
                     + f" | | {'yes' if res['agreement']['class'] else 'NO'} |")
        for key in NUMERIC:
            a = res["agreement"].get(key)
            cells = " | ".join("-" if runs[k][key] is None else f"{runs[k][key]:.4g}" for k in labels)
            summary = "-" if a is None else (f"{a['means']['default']:.4g} / {a['means']['reference']:.4g}, "
                                             f"{a['spread']:.3g}")
            lines.append(f"| {key} | {cells} | {summary} | {'-' if a is None else ('yes' if a['agrees'] else 'NO')} |")
        for key in SECTORS:
            lines.append(f"| {key} [deg] | " + " | ".join(
                "-" if runs[k][key] is None else "–".join(f"{math.degrees(x):.0f}" for x in runs[k][key])
                for k in labels) + " | | |")
        lines.append("| integration wall [s] | " + " | ".join(f"{runs[k]['integration_wall_time']:.1f}" for k in labels)
                     + " | | |")
        lines.append("| steps | " + " | ".join(str(runs[k]['steps']) for k in labels) + " | | |")
        lines.append("")
    lines.append(f"Load average {study['load_average']:.2f} at the end of the study.")
    return "\n".join(lines)


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cases", nargs="+", default=["helicopter-b", "helicopter-a"])
    ap.add_argument("--out", type=Path, default=Path("runs/default_vs_reference"))
    ap.add_argument("--data", type=Path, default=Path(__file__).resolve().parent / "data",
                    help="where the study's JSON file and table go")
    ap.add_argument("--reuse", action="store_true", help="read runs whose summary.json exists")
    args = ap.parse_args(argv)
    study = {"cases": {c: run_case(c, args.out, args.reuse) for c in args.cases}}
    study["load_average"] = os.getloadavg()[0]
    args.data.mkdir(parents=True, exist_ok=True)
    (args.data / "default_vs_reference.json").write_text(json.dumps(study, indent=1, default=str))
    (args.data / "default_vs_reference.md").write_text(markdown(study))
    print(markdown(study))


if __name__ == "__main__":
    main()
