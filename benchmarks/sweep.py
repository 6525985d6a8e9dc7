"""Scaling of `bearingsim sweep`: wall time of the same sweep on 1 and 2 local workers.

Run: nice -n 10 python -m benchmarks.sweep [--moments 0,600] [--speeds 2000,6000]
     [--duration 0.003] [--workers 1,2]

Every run starts from an empty sweep directory and stage store (nothing shared between
runs but numba's on-disk cache, so the first point of each worker pays the cache load).
On a machine shared with other work the speed-up is a lower bound.
"""

from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path


def time_sweep(workers: int, moments: str, speeds: str, duration: float, scene: str) -> dict:
    from bearingsim.pipeline.sweep.driver import dask_client, plan_sweep, run_sweep

    with tempfile.TemporaryDirectory(prefix="bench-sweep-") as tmp:
        plan = plan_sweep(scene, [f"solver.duration={duration}"],
                          [f"load.moment={moments}", f"speed.inner_rpm={speeds}"], out=Path(tmp) / "sw")
        t0 = time.perf_counter()
        with dask_client(None, workers) as client:
            t1 = time.perf_counter()
            records = run_sweep(plan, client, poll_s=0.2)
            t2 = time.perf_counter()
        finished = [r for r in records if r and "wall_time_s" in r]
    return {"workers": workers, "points": len(plan.points), "cluster_s": t1 - t0, "sweep_s": t2 - t1,
            "point_wall_s": sum(r["wall_time_s"] for r in finished),
            "point_cpu_s": sum(r["cpu_time_s"] for r in finished),
            "failed": sum(1 for r in records if not r or r["status"] != "done")}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--moments", default="0,600", help="load.moment values [N.m]")
    parser.add_argument("--speeds", default="2000,6000", help="speed.inner_rpm values [rev/min]")
    parser.add_argument("--duration", type=float, default=0.003, help="simulated time per point [s]")
    parser.add_argument("--workers", default="1,2", help="worker counts to compare")
    parser.add_argument("--scene", default="helicopter-b-given-hinge")
    args = parser.parse_args()
    results = [time_sweep(int(w), args.moments, args.speeds, args.duration, args.scene)
               for w in args.workers.split(",")]
    base = results[0]["sweep_s"]
    # points' CPU / wall < 1: the workers waited for a core (other processes, or fewer cores than workers)
    print(f"{'workers':>7}{'points':>8}{'cluster [s]':>13}{'sweep [s]':>11}{'points wall [s]':>17}"
          f"{'points CPU [s]':>16}{'CPU/wall':>10}{'speed-up':>10}{'failed':>8}")
    for r in results:
        print(f"{r['workers']:>7}{r['points']:>8}{r['cluster_s']:>13.2f}{r['sweep_s']:>11.2f}"
              f"{r['point_wall_s']:>17.2f}{r['point_cpu_s']:>16.2f}{r['point_cpu_s'] / r['point_wall_s']:>10.2f}"
              f"{base / r['sweep_s']:>10.2f}{r['failed']:>8}")


if __name__ == "__main__":
    main()
