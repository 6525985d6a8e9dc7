"""Benchmark of stage 1 (hinge identification): `python -m benchmarks.fe [--part ...]`.

Parts (all by default):
  large     mesh + assemble + factor + all solves + fit at ~400k P2 dofs (target <= 45 s, <= 5 GB)
  default   `identify_hinge` with the default [fe] table, against a fine-mesh reference
  solvers   PARDISO (SPD) against scipy SuperLU on a ~70k-dof model
  verify    Timoshenko cantilever and Lamé tube errors with the observed convergence order
Timings are wall-clock on whatever else the machine is running: note the load average.
"""

from __future__ import annotations

import argparse
import dataclasses
import os
import pathlib
import resource
import tempfile
import time

import numpy as np

from bearingsim.fe_model import FEConfig, RingSeat, fit_hinge, identify_hinge, richardson
from bearingsim.fe_model.identify import solve_perturbations


def _peak_rss_gb() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024**2


def _row(*cells) -> None:
    print("| " + " | ".join(str(c) for c in cells) + " |")


def bench_large(mesh_size: float = 0.007) -> dict:
    config = dataclasses.replace(FEConfig(), mesh_size=mesh_size, edge_refinement=1.0)
    with tempfile.TemporaryDirectory() as tmp:  # fresh: the mesh is built, not reused
        t0 = time.perf_counter()
        solved = solve_perturbations(config, RingSeat(), pathlib.Path(tmp), lambda s, f: None)
        t_fit = time.perf_counter()
        fit = fit_hinge(solved.loads, solved.responses, solved.groups)
        total = time.perf_counter() - t0
    t = solved.timings
    print(f"\n## large model: uniform h = {mesh_size} m, P2, {solved.mesh_stats['dofs']} dofs, "
          f"solver {solved.mesh_stats['linear_solver']}, load average {os.getloadavg()[0]:.1f}")
    _row("mesh [s]", "assemble [s]", "factor [s]", f"{len(solved.names)} solves [s]", "fit [s]",
         "total [s]", "peak RSS [GB]")
    _row("---", "---", "---", "---", "---", "---", "---")
    _row(f"{t['mesh']:.1f}", f"{t['assemble']:.1f}", f"{t['factor']:.1f}", f"{t['solve']:.1f}",
         f"{time.perf_counter() - t_fit:.3f}", f"{total:.1f}", f"{_peak_rss_gb():.2f}")
    print(f"H_u diag {np.diag(fit.H_u)} N/m, H_psi {fit.H_psi} N*m/rad")
    return {"total": total, "H_u": fit.H_u, "H_psi": fit.H_psi}


def bench_default(reference: dict | None) -> None:
    config = FEConfig()
    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.perf_counter()
        result = identify_hinge(config, RingSeat(), pathlib.Path(tmp))
        total = time.perf_counter() - t0
    print(f"\n## default [fe]: h = {config.mesh_size} m, order {config.element_order}, "
          f"{result.mesh_stats['dofs']} dofs: identify_hinge {total:.1f} s (with .vtu output)")
    print(f"H_u diag {np.diag(result.H_u)} N/m, H_psi {result.H_psi} N*m/rad, "
          f"residual {result.residual:.2e}, coupling {result.coupling['translation_rotation_max']:.2e}")
    if reference is not None:
        dev_u = np.diag(result.H_u) / np.diag(reference["H_u"]) - 1
        dev_psi = result.H_psi / reference["H_psi"] - 1
        print(f"relative to the large model: H_u diag {dev_u}, H_psi {dev_psi}")


def bench_solvers(mesh_size: float = 0.016) -> None:
    print(f"\n## solvers on the h = {mesh_size} m P2 model (factor + 20 solves)")
    _row("solver", "dofs", "factor + solves [s]", "max |dU| / max |U|")
    _row("---", "---", "---", "---")
    base = None
    for method in ("pardiso", "splu"):
        config = dataclasses.replace(FEConfig(), mesh_size=mesh_size, edge_refinement=1.0, linear_solver=method)
        with tempfile.TemporaryDirectory() as tmp:
            solved = solve_perturbations(config, RingSeat(), pathlib.Path(tmp), lambda s, f: None)
        U = solved.displacements
        base = U if base is None else base
        diff = np.abs(U - base).max() / np.abs(base).max()
        _row(method, solved.mesh_stats["dofs"], f"{solved.timings['factor'] + solved.timings['solve']:.1f}",
             f"{diff:.1e}")


def bench_verify() -> None:
    from bearingsim.fe_model.verification import Cantilever, LameTube

    beam, tube = Cantilever(), LameTube()
    w_ref, phi_ref = beam.timoshenko()
    sizes = np.array([0.05, 0.035, 0.025, 0.0175])
    print("\n## Timoshenko cantilever (L = 1 m, 0.1 x 0.1 m, P2)")
    _row("h [m]", "dofs", "w / w_Timoshenko - 1", "phi / phi_Timoshenko - 1")
    _row("---", "---", "---", "---")
    res = []
    for h in sizes:
        w, phi, n = beam.solve(h, 2)
        res.append((w, phi))
        _row(h, n, f"{w / w_ref - 1:+.4%}", f"{phi / phi_ref - 1:+.4%}")
    res = np.array(res)
    for name, col, ref in (("w", 0, w_ref), ("phi", 1, phi_ref)):
        f0, p = richardson(sizes, res[:, col])
        print(f"{name}: observed order {p:.2f}, Richardson limit {f0 / ref - 1:+.4%} from Timoshenko")
    print("\n## Lamé tube (a = 0.05, b = 0.1 m, p = 100 MPa, P2)")
    _row("h [m]", "dofs", "u_r(a) error", "u_r(b) error")
    _row("---", "---", "---", "---")
    for h in (0.02, 0.01, 0.005):
        ua, ub, n = tube.solve(h, 2)
        _row(h, n, f"{ua / tube.radial_displacement(tube.inner_radius) - 1:+.4%}",
             f"{ub / tube.radial_displacement(tube.outer_radius) - 1:+.4%}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--part", choices=("all", "large", "default", "solvers", "verify"), default="all")
    parser.add_argument("--large-mesh-size", type=float, default=0.007)
    args = parser.parse_args()
    reference = None
    if args.part in ("all", "large"):
        reference = bench_large(args.large_mesh_size)
    if args.part in ("all", "default"):
        bench_default(reference)
    if args.part in ("all", "solvers"):
        bench_solvers()
    if args.part in ("all", "verify"):
        bench_verify()


if __name__ == "__main__":
    main()
