"""Do the shipped solver defaults give the statistics of a tight-tolerance run? (issue: fast by default)

    python -m benchmarks.default_vs_reference [--cases helicopter-b helicopter-a] [--out DIR]

For each reference case, the full run (0.8 s) is integrated four times:

* three runs at the scene's own tolerance that differ only in their first step
  (`solver.first_step` 1e-6 s — the default — and 5e-7 s, 2e-6 s). Their step sequences differ
  from the first step on, and the cage's motion, once it presses or rubs its land, amplifies any
  perturbation: the spread of their statistics is the run-to-run spread of a statistic at that
  tolerance;
* one reference at a 10x tighter tolerance (`solver.rtol` 1e-7).

A statistic of the default agrees with the reference when the reference lies within the
default-tolerance runs' range widened by that range's own width (the reference carries a spread
of its own, which one tight run cannot measure). Class and risk must be equal. Writes
default_vs_reference.json and .md in DIR (default runs/default_vs_reference). Wall times are on
whatever else the machine runs; the load average is recorded.
"""

from __future__ import annotations

import argparse
import json
import os
import time
from pathlib import Path

RUNS = {  # label: overrides
    "default": [],
    "first_step 5e-7": ["solver.first_step=5e-7"],
    "first_step 2e-6": ["solver.first_step=2e-6"],
    "reference rtol 1e-7": ["solver.rtol=1e-7"],
}
NUMERIC = ("cage_eps_mean", "cage_metal_contact_fraction", "cage_whirl_ratio", "cage_offset_azimuth_mean",
           "cage_land_force_mean", "land_film_min", "pocket_impacts", "pocket_impact_force_p95",
           "burn_zone_energy_total", "cage_speed_mean")
SECTORS = ("cage_offset_sector", "burn_zone_sector")


def run_case(scene_name: str, out: Path, progress=print) -> dict:
    import bearingsim

    rows = {}
    # compile (or load) the kernels before anything is timed
    bearingsim.run(scene_name, out / scene_name / "warm-up", stages=["simulate"],
                   overrides=["solver.duration=1e-3"], force=["simulate"])
    for label, overrides in RUNS.items():
        run_dir = out / scene_name / label.replace(" ", "_")
        t0 = time.perf_counter()
        bearingsim.run(scene_name, run_dir, stages=["simulate"], overrides=overrides, force=["simulate"])
        wall = time.perf_counter() - t0
        s = json.loads((run_dir / "simulate" / "summary.json").read_text())
        v = s["verdict"]
        rows[label] = {"class": v["class"], "risk": v["risk"], "wall": wall,
                       "integration_wall_time": s["integration_wall_time"], "steps": s["steps"],
                       **{k: s.get(k) for k in NUMERIC + SECTORS}}
        progress(f"{scene_name} {label}: {v['class']}/{v['risk']}, integration {s['integration_wall_time']:.1f} s, "
                 f"{s['steps']} steps")
    return {"runs": rows, "agreement": agreement(rows)}


def agreement(rows: dict) -> dict:
    same_tol = [r for k, r in rows.items() if not k.startswith("reference")]
    ref = rows["reference rtol 1e-7"]
    out = {"class": all(r["class"] == ref["class"] and r["risk"] == ref["risk"] for r in same_tol)}
    for key in NUMERIC:
        vals = [r[key] for r in same_tol if r[key] is not None]
        if not vals or ref[key] is None:
            continue
        lo, hi = min(vals), max(vals)
        width = hi - lo
        out[key] = {"range": [lo, hi], "reference": ref[key], "agrees": lo - width <= ref[key] <= hi + width}
    return out


def markdown(study: dict) -> str:
    lines = []
    for case, res in study["cases"].items():
        runs = res["runs"]
        labels = list(runs)
        lines += [f"### {case}", "", "| statistic | " + " | ".join(labels) + " | agrees |",
                  "|---|" + "---|" * (len(labels) + 1)]
        lines.append("| class / risk | " + " | ".join(f"{runs[k]['class']} / {runs[k]['risk']}" for k in labels)
                     + f" | {'yes' if res['agreement']['class'] else 'NO'} |")
        for key in NUMERIC:
            a = res["agreement"].get(key)
            cells = " | ".join("-" if runs[k][key] is None else f"{runs[k][key]:.4g}" for k in labels)
            lines.append(f"| {key} | {cells} | {'-' if a is None else ('yes' if a['agrees'] else 'NO')} |")
        for key in SECTORS:
            lines.append(f"| {key} [deg] | " + " | ".join(str(runs[k][key]) for k in labels) + " | |")
        lines.append("| integration wall [s] | " + " | ".join(f"{runs[k]['integration_wall_time']:.1f}" for k in labels) + " | |")
        lines.append("| steps | " + " | ".join(str(runs[k]['steps']) for k in labels) + " | |")
        lines.append("")
    lines.append(f"Load average {study['load_average']:.2f} at the end of the study.")
    return "\n".join(lines)


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cases", nargs="+", default=["helicopter-b", "helicopter-a"])
    ap.add_argument("--out", type=Path, default=Path("runs/default_vs_reference"))
    args = ap.parse_args(argv)
    study = {"cases": {c: run_case(c, args.out) for c in args.cases}}
    study["load_average"] = os.getloadavg()[0]
    args.out.mkdir(parents=True, exist_ok=True)
    (args.out / "default_vs_reference.json").write_text(json.dumps(study, indent=1, default=str))
    (args.out / "default_vs_reference.md").write_text(markdown(study))
    print(markdown(study))


if __name__ == "__main__":
    main()
