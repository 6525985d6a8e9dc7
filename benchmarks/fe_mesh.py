"""Benchmark of the mesh model (`[fe] model = "mesh"`): `python -m benchmarks.fe_mesh [--part ...]`.

Parts:
  large    one identification of the example housing on two feet (meshes/example_housing.py) at
           ~300k dofs (10-node tetrahedra, --mesh-size, default 0.0082 m) with the default solver
           choice (auto: AMG + CG beyond fe.direct_max_dofs): wall time per phase, peak memory,
           solver, AMG levels and CG iterations
  solvers  SuperLU against AMG + CG on the same housing at ~85k dofs (0.015 m), where both fit
Timings are wall-clock on whatever else the machine is running: note the load average (the
script prints `os.getloadavg()` before and after).
"""

from __future__ import annotations

import argparse
import os
import pathlib
import resource
import tempfile
import time

import numpy as np

from bearingsim.fe_model import RingSeat
from bearingsim.fe_model.config import FEConfig, RegionMaterial
from bearingsim.fe_model.identify import identify_hinge
from bearingsim.meshes.example_housing import write_foot_housing_mesh

MATERIALS = (RegionMaterial("shaft", 208e9, 0.3), RegionMaterial("support_a", 2.195e9, 0.0),
             RegionMaterial("support_b", 2.195e9, 0.0), RegionMaterial("housing", 71e9, 0.33))


def _peak_rss_gb() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024**2


def identify(mesh_size: float, solver: str) -> dict:
    """One identification on the example mesh of `mesh_size` [m]; returns what it measured."""
    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.perf_counter()
        mesh = write_foot_housing_mesh(pathlib.Path(tmp) / "feet.msh", mesh_size, order=2)
        meshing = time.perf_counter() - t0
        config = FEConfig(model="mesh", mesh_file=str(mesh), materials=MATERIALS, linear_solver=solver)
        t0 = time.perf_counter()
        result = identify_hinge(config, RingSeat(), pathlib.Path(tmp) / "identify", write_fields=False)
        total = time.perf_counter() - t0
    return {"mesh_size": mesh_size, "meshing_s": meshing, "identify_s": total, "timings": result.timings,
            "stats": result.mesh_stats, "H": np.r_[np.diag(result.H_u), result.H_psi],
            "peak_rss_gb": _peak_rss_gb()}


def report(row: dict) -> None:
    s = row["stats"]
    phases = ", ".join(f"{k} {v:.1f} s" for k, v in row["timings"].items())
    amg = (f", {s['amg_levels']} AMG levels, CG iterations <= {s['cg_iterations_max']} to relative residual "
           f"{s['cg_relative_residual_max']:.1e}" if s["linear_solver"] == "amg" else "")
    print(f"h = {row['mesh_size']} m: {s['dofs']} dofs ({s['free_dofs']} free), {s['elements']} tetrahedra, "
          f"solver {s['linear_solver']}{amg}")
    print(f"  identify {row['identify_s']:.1f} s ({phases}); meshing (gmsh) {row['meshing_s']:.1f} s; "
          f"peak RSS {row['peak_rss_gb']:.2f} GB")
    print("  H_u_xx H_u_yy H_u_zz [N/m], H_psi_x H_psi_y [N m/rad]: " + " ".join(f"{v:.5e}" for v in row["H"]))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--part", choices=("large", "solvers"), default="large")
    parser.add_argument("--mesh-size", type=float, default=0.0082)
    args = parser.parse_args()
    print(f"load average before: {os.getloadavg()}")
    if args.part == "large":
        report(identify(args.mesh_size, "auto"))
    else:
        rows = [identify(0.015, solver) for solver in ("splu", "amg")]
        for row in rows:
            report(row)
        a, b = rows[0]["H"], rows[1]["H"]
        print(f"  AMG against SuperLU: largest relative difference {np.max(np.abs(b / a - 1.0)):.2e}")
    print(f"load average after: {os.getloadavg()}")


if __name__ == "__main__":
    main()
