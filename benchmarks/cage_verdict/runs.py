"""Run scene variants through `bearingsim simulate` in parallel and measure each settled run.

    python -m benchmarks.cage_verdict.runs PLAN OUT_DIR [--workers 2] [--duration 0.4]

PLAN names a plan in `plans.py`. Every variant is one run directory under OUT_DIR/runs/;
the metrics of each (`measure`) go to OUT_DIR/<plan>.json. A variant whose run directory
already holds a summary is measured again, not re-run (delete it to recompute).
The metrics are computed here from `timeseries.h5` over a fixed settled window (from
`settle` seconds on; the quasi-static start needs ~50 ms to die out in both reference
cases), so the study does not depend on the product's summary conventions.
"""

from __future__ import annotations

import argparse
import json
import math
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np

# the README's setting for cage-orbit surveys: the step controller on an absolute tolerance
FAST = ["solver.max_step=1e-4", "solver.rtol=1e-12", "solver.atol=1e-9"]


def run_variant(scene: str, overrides: list[str], run_dir: Path, duration: float) -> tuple[bool, str]:
    if (run_dir / "simulate" / "summary.json").is_file():
        return True, "cached"
    exe = Path(sys.executable).parent / "bearingsim"  # the console script of this environment
    args = [str(exe), "simulate", scene, "--out", str(run_dir)]
    for o in FAST + [f"solver.duration={duration}"] + overrides:
        args += ["--set", o]
    p = subprocess.run(args, capture_output=True, text=True)
    ok = p.returncode == 0 and (run_dir / "simulate" / "summary.json").is_file()
    return ok, p.stderr[-2000:]


def _circular(angles, weights=None):
    w = np.ones_like(angles) if weights is None else weights
    z = np.sum(w * np.exp(1j * angles)) / np.sum(w)
    r = min(abs(z), 1.0)
    return math.degrees(math.atan2(z.imag, z.real)) % 360.0, math.sqrt(-2.0 * math.log(r)) if r > 0 else math.inf


def measure(run_dir: Path, settle: float) -> dict:
    """Settled-window metrics of one run (t >= settle), and the same split in two halves."""
    import h5py

    with h5py.File(run_dir / "simulate" / "timeseries.h5") as f:
        t = f["time"][:]
        c = f["cage/position"][:]
        speed = f["cage/speed"][:]
        eps = f["cage_race/eccentricity_ratio"][:]
        force = f["cage_race/force"][:]
        metal = f["cage_race/metal_force"][:]
        fpow = f["cage_race/friction_power"][:]
        film = f["cage_race/film_power"][:] if "cage_race/film_power" in f else np.zeros_like(t)
        hmin = f["cage_race/min_film"][:] if "cage_race/min_film" in f else np.full_like(t, np.nan)
        pocket = f["pocket/force"][:]
    impacts = np.loadtxt(run_dir / "simulate" / "impacts.csv", delimiter=",", skiprows=1, ndmin=2)
    summary = json.loads((run_dir / "simulate" / "summary.json").read_text())

    def window(a, b):
        m = (t >= a) & (t <= b)
        tw = t[m]
        w = np.gradient(tw) if tw.size > 1 else np.ones(1)
        span = tw[-1] - tw[0]
        az = np.arctan2(c[m, 1], c[m, 0])
        az_mean, az_spread = _circular(az, w)
        phase = np.unwrap(az)
        imp = impacts[(impacts[:, 0] >= a) & (impacts[:, 0] <= b)] if impacts.size else np.zeros((0, 6))
        F = np.hypot(force[m, 0], force[m, 1])
        return {
            "eps_mean": float(np.sum(w * eps[m]) / span), "eps_max": float(eps[m].max()),
            "metal_fraction": float(np.sum(w * (eps[m] > 1.0)) / span),
            "metal_force_mean": float(np.sum(w * metal[m]) / span),
            "land_force_mean": float(np.sum(w * F) / span), "land_force_max": float(F.max()),
            "land_force_vector_mean": [float(np.sum(w * force[m, 0]) / span), float(np.sum(w * force[m, 1]) / span)],
            "offset_azimuth_deg": az_mean, "offset_spread_rad": az_spread,
            "whirl_ratio": float((phase[-1] - phase[0]) / span / np.mean(speed[m])),
            "speed_variation": float((speed[m].max() - speed[m].min()) / np.mean(speed[m])),
            "impacts_per_s": float(len(imp) / span),
            "impact_p95": float(np.percentile(imp[:, 3], 95)) if len(imp) else 0.0,
            "impact_max": float(imp[:, 3].max()) if len(imp) else 0.0,
            "impact_regions_deg": _impact_regions(imp),
            "pocket_force_mean": float(np.mean(pocket[m])),
            "metal_energy": float(np.sum(w * fpow[m])), "film_energy": float(np.sum(w * film[m])),
            "film_power_mean": float(np.sum(w * film[m]) / span),
            "min_film_um": float(np.nanmin(hmin[m]) * 1e6) if np.isfinite(hmin[m]).any() else None,
        }

    end = float(t[-1])
    mid = 0.5 * (settle + end)
    out = {"settled": window(settle, end), "first_half": window(settle, mid), "second_half": window(mid, end),
           "startup_metal_energy": float(np.sum(np.gradient(t[t < settle]) * fpow[t < settle])) if (t < settle).sum() > 1 else 0.0,
           "duration": end, "settle": settle,
           "newton_failures": summary.get("newton_failures"), "steps": summary.get("steps"),
           "non_guiding_gap_min_um": (1e6 * summary["non_guiding_gap_min"]) if "non_guiding_gap_min" in summary else None,
           "screen": summary.get("crush_screen"), "verdict_class": (summary.get("verdict") or {}).get("class"),
           "integration_wall_time": summary.get("integration_wall_time")}
    return out


def _impact_regions(imp: np.ndarray, bins: int = 12) -> list[list[float]]:
    """Orbital positions [deg] of the impacts: the 30° bins holding the most impacts
    (with their share), strongest first."""
    if not len(imp):
        return []
    az = np.degrees(np.mod(imp[:, 2], 2 * math.pi))
    h, edges = np.histogram(az, bins=bins, range=(0, 360))
    order = np.argsort(h)[::-1][:3]
    return [[float(edges[i] + 15.0), float(h[i] / h.sum())] for i in order if h[i] > 0]


def main(argv=None) -> None:
    from .plans import PLANS

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("plan", choices=sorted(PLANS))
    ap.add_argument("out", type=Path)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--duration", type=float, default=0.4)
    ap.add_argument("--settle", type=float, default=0.1)
    a = ap.parse_args(argv)
    variants = PLANS[a.plan]()
    a.out.mkdir(parents=True, exist_ok=True)

    def one(v):
        name, scene, overrides = v
        run_dir = a.out / "runs" / name
        ok, msg = run_variant(scene, overrides, run_dir, a.duration)
        print(f"{name}: {'ok' if ok else 'FAILED'}", file=sys.stderr, flush=True)
        if not ok:
            return name, {"error": msg, "overrides": overrides, "scene": scene}
        return name, {**measure(run_dir, a.settle), "overrides": overrides, "scene": scene}

    with ThreadPoolExecutor(a.workers) as pool:
        results = dict(pool.map(one, variants))
    (a.out / f"{a.plan}.json").write_text(json.dumps(results, indent=1))
    print(json.dumps({k: (v.get("settled", {}).get("eps_mean"), v.get("settled", {}).get("metal_fraction"))
                      for k, v in results.items()}, indent=0))


if __name__ == "__main__":
    main()
