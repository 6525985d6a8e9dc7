"""Benchmark of stage 1 (hinge identification): `python -m benchmarks.fe [--part ...]`.

Parts (all by default):
  default     `identify_hinge` with the default [fe] table (axisymmetric model, .vtu output),
              against a fine axisymmetric reference; wall time per phase
  crosscheck  the 3-D solver (tetrahedra) against the axisymmetric model: on tetrahedra swept
              from the same section (16, 32, 64 sectors; faceting error ~ 1/sectors^2) and on
              the previous 3-D default mesh (0.03 m graded 0.25, ~480k dofs)
  large       the 3-D solver at ~400k P2 dofs (uniform 0.007 m): mesh + assemble + factor + solves
  solvers     PARDISO (SPD) against scipy SuperLU on a ~70k-dof 3-D model
  verify      Timoshenko cantilever and Lamé tube errors with the observed convergence order
              (3-D), Lamé tube and tube cantilever (axisymmetric modes 0 and 1)
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

REFERENCE = {"mesh_size": 0.0025, "edge_refinement": 0.02}  # axisymmetric P2, ~1.3M dofs
PREVIOUS_3D = {"mesh_size": 0.030, "edge_refinement": 0.25}  # the earlier 3-D default, for comparison


def _peak_rss_gb() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024**2


def _row(*cells) -> None:
    print("| " + " | ".join(str(c) for c in cells) + " |")


def _hinge(config: FEConfig, model: str = "axisymmetric") -> tuple[np.ndarray, dict, float]:
    """([H_u_xx, H_u_yy, H_u_zz, H_psi_x, H_psi_y], mesh statistics, seconds) without .vtu."""
    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.perf_counter()
        solved = solve_perturbations(config, RingSeat(), pathlib.Path(tmp), lambda s, f: None, model)
        fit = fit_hinge(solved.loads, solved.responses, solved.groups)
        seconds = time.perf_counter() - t0
    return np.r_[np.diag(fit.H_u), fit.H_psi], solved.mesh_stats, seconds


def _errors(values: np.ndarray, reference: np.ndarray) -> str:
    return " ".join(f"{v:+.3%}" for v in values / reference - 1.0)


def bench_reference() -> np.ndarray:
    values, stats, seconds = _hinge(dataclasses.replace(FEConfig(), **REFERENCE))
    print(f"\n## reference: axisymmetric P2, h = {REFERENCE['mesh_size']} m graded {REFERENCE['edge_refinement']}, "
          f"{stats['dofs']} dofs, {seconds:.1f} s, peak RSS {_peak_rss_gb():.2f} GB")
    print(f"H_u_xx, yy, zz [N/m], H_psi_x, y [N*m/rad]: {values}")
    return values


def bench_default(reference: np.ndarray | None) -> None:
    config = FEConfig()
    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.perf_counter()
        result = identify_hinge(config, RingSeat(), pathlib.Path(tmp))
        total = time.perf_counter() - t0
        sizes = {p.name: p.stat().st_size for p in pathlib.Path(tmp).glob("case_*.vtu")}
    t = result.timings
    print(f"\n## default [fe]: axisymmetric, h = {config.mesh_size} m graded {config.edge_refinement}, "
          f"order {config.element_order}, {result.mesh_stats['dofs']} dofs, load average {os.getloadavg()[0]:.1f}")
    _row("mesh [s]", "assemble [s]", "factor [s]", "solve [s]", "fit [s]", "write .vtu [s]", "identify_hinge [s]",
         ".vtu [MB each]")
    _row("---", "---", "---", "---", "---", "---", "---", "---")
    _row(*(f"{t[k]:.2f}" for k in ("mesh", "assemble", "factor", "solve", "fit", "write")), f"{total:.2f}",
         f"{np.mean(list(sizes.values())) / 1e6:.2f}")
    values = np.r_[np.diag(result.H_u), result.H_psi]
    print(f"H_u diag {np.diag(result.H_u)} N/m, H_psi {result.H_psi} N*m/rad, residual {result.residual:.2e}, "
          f"coupling {result.coupling['translation_rotation_max']:.2e}")
    if reference is not None:
        print(f"against the reference (H_u_xx yy zz, H_psi_x y): {_errors(values, reference)}")


def bench_crosscheck(reference: np.ndarray | None) -> None:
    """The 3-D solver converges to the axisymmetric model: an independent check of the mode
    decomposition, the Fourier loads and the rigid fit."""
    import bearingsim.fe_model.identify as identify
    from bearingsim.meshes.housing import build_section_mesh
    from bearingsim.meshes.section import revolve_to_tets

    config = dataclasses.replace(FEConfig(), mesh_size=0.03, edge_refinement=0.2)
    section = build_section_mesh(config.housing_geometry(RingSeat()), config.mesh_size, config.edge_refinement)
    axi, stats, _ = _hinge(config)
    print(f"\n## cross-check on one section (h = {config.mesh_size} m graded {config.edge_refinement}, "
          f"{stats['nodes']} nodes): 3-D P2 tetrahedra swept through n sectors vs axisymmetric P2")
    _row("sectors", "3-D dofs", "3-D [s]", "H_u_xx", "H_u_yy", "H_u_zz", "H_psi_x", "H_psi_y")
    _row("---", "---", "---", "---", "---", "---", "---", "---")
    rows = []
    original = identify.cached_housing_mesh
    try:
        for sectors in (16, 32, 64):
            tets = revolve_to_tets(section, sectors)
            identify.cached_housing_mesh = lambda *a, **k: (tets, pathlib.Path("revolved.npz"), False)
            values, s3, seconds = _hinge(config, "3d")
            rows.append(values)
            _row(sectors, s3["dofs"], f"{seconds:.1f}", *(f"{e:+.3%}" for e in values / axi - 1.0))
    finally:
        identify.cached_housing_mesh = original
    limit = np.array([richardson(np.array([1 / 16, 1 / 32, 1 / 64]), np.array(rows)[:, k]) for k in range(5)])
    print("Richardson in 1/sectors: " + ", ".join(f"{f0 / a - 1:+.3%} (p = {p:.2f})" for (f0, p), a in zip(limit, axi)))
    if reference is not None:
        values, s3, seconds = _hinge(dataclasses.replace(FEConfig(), **PREVIOUS_3D), "3d")
        print(f"\nprevious 3-D default (h = {PREVIOUS_3D['mesh_size']} m graded {PREVIOUS_3D['edge_refinement']}, "
              f"{s3['dofs']} dofs, {seconds:.1f} s, peak RSS {_peak_rss_gb():.2f} GB) against the reference: "
              f"{_errors(values, reference)}")


def bench_large(mesh_size: float = 0.007) -> dict:
    config = dataclasses.replace(FEConfig(), mesh_size=mesh_size, edge_refinement=1.0)
    with tempfile.TemporaryDirectory() as tmp:  # fresh: the mesh is built, not reused
        t0 = time.perf_counter()
        solved = solve_perturbations(config, RingSeat(), pathlib.Path(tmp), lambda s, f: None, "3d")
        t_fit = time.perf_counter()
        fit = fit_hinge(solved.loads, solved.responses, solved.groups)
        total = time.perf_counter() - t0
    t = solved.timings
    print(f"\n## large 3-D model: uniform h = {mesh_size} m, P2, {solved.mesh_stats['dofs']} dofs, "
          f"solver {solved.mesh_stats['linear_solver']}, load average {os.getloadavg()[0]:.1f}")
    _row("mesh [s]", "assemble [s]", "factor [s]", f"{len(solved.names)} solves [s]", "fit [s]",
         "total [s]", "peak RSS [GB]")
    _row("---", "---", "---", "---", "---", "---", "---")
    _row(f"{t['mesh']:.1f}", f"{t['assemble']:.1f}", f"{t['factor']:.1f}", f"{t['solve']:.1f}",
         f"{time.perf_counter() - t_fit:.3f}", f"{total:.1f}", f"{_peak_rss_gb():.2f}")
    print(f"H_u diag {np.diag(fit.H_u)} N/m, H_psi {fit.H_psi} N*m/rad")
    return {"total": total, "H_u": fit.H_u, "H_psi": fit.H_psi}


def bench_solvers(mesh_size: float = 0.016) -> None:
    print(f"\n## solvers on the h = {mesh_size} m P2 3-D model (factor + 15 solves)")
    _row("solver", "dofs", "factor + solves [s]", "max |dU| / max |U|")
    _row("---", "---", "---", "---")
    base = None
    for method in ("pardiso", "splu"):
        config = dataclasses.replace(FEConfig(), mesh_size=mesh_size, edge_refinement=1.0, linear_solver=method)
        with tempfile.TemporaryDirectory() as tmp:
            solved = solve_perturbations(config, RingSeat(), pathlib.Path(tmp), lambda s, f: None, "3d")
        U = solved.displacements
        base = U if base is None else base
        diff = np.abs(U - base).max() / np.abs(base).max()
        _row(method, solved.mesh_stats["dofs"], f"{solved.timings['factor'] + solved.timings['solve']:.1f}",
             f"{diff:.1e}")


def bench_verify() -> None:
    from bearingsim.fe_model.verification import Cantilever, LameTube, TubeCantilever

    beam, tube = Cantilever(), LameTube()
    w_ref, phi_ref = beam.timoshenko()
    sizes = np.array([0.05, 0.035, 0.025, 0.0175])
    print("\n## Timoshenko cantilever (L = 1 m, 0.1 x 0.1 m, P2 tetrahedra)")
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
    print("\n## Lamé tube (a = 0.05, b = 0.1 m, p = 100 MPa, P2): 3-D tetrahedra | axisymmetric mode 0")
    _row("h [m]", "3-D dofs", "u_r(a) error", "u_r(b) error", "axisym. dofs", "u_r(a) error", "u_r(b) error")
    _row("---", "---", "---", "---", "---", "---", "---")
    exact = tube.radial_displacement(tube.inner_radius), tube.radial_displacement(tube.outer_radius)
    for h in (0.02, 0.01, 0.005):
        ua, ub, n = tube.solve(h, 2)
        va, vb, m = tube.solve_axisymmetric(h, 2)
        _row(h, n, f"{ua / exact[0] - 1:+.4%}", f"{ub / exact[1] - 1:+.4%}", m, f"{va / exact[0] - 1:+.2e}",
             f"{vb / exact[1] - 1:+.2e}")
    cantilever = TubeCantilever()
    w_ref, phi_ref = cantilever.timoshenko()
    print("\n## tube cantilever (L = 1 m, a = 0.04, b = 0.05 m, axisymmetric mode 1, P2)")
    _row("h [m]", "dofs", "w / w_Timoshenko - 1", "phi / phi_Timoshenko - 1")
    _row("---", "---", "---", "---")
    for h in (0.01, 0.005, 0.0025):
        w, phi, n = cantilever.solve(h, 2)
        _row(h, n, f"{w / w_ref - 1:+.4%}", f"{phi / phi_ref - 1:+.4%}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--part", choices=("all", "default", "crosscheck", "large", "solvers", "verify"),
                        default="all")
    parser.add_argument("--large-mesh-size", type=float, default=0.007)
    args = parser.parse_args()
    reference = None
    if args.part in ("all", "default", "crosscheck"):
        reference = bench_reference()
    if args.part in ("all", "default"):
        bench_default(reference)
    if args.part in ("all", "crosscheck"):
        bench_crosscheck(reference)
    if args.part in ("all", "large"):
        bench_large(args.large_mesh_size)
    if args.part in ("all", "solvers"):
        bench_solvers()
    if args.part in ("all", "verify"):
        bench_verify()


if __name__ == "__main__":
    main()
