"""Work–precision of the hinge identification (stage 1): stiffness against mesh size and
element order, error against the Richardson-extrapolated value, wall time and peak memory.

    python -m pipeline.studies.identify_precision [SCENE] [--quick] [--out DIR]

Each (order, mesh size) is solved by `fe_model.convergence_study` in a fresh process so that
its peak resident memory is its own. The converged value of each stiffness is the
Richardson extrapolation of the three finest P2 meshes (`fe_model.richardson`, Roache 1998
§5.4); every row's error is measured against it.
"""

from __future__ import annotations

import argparse
import dataclasses
import multiprocessing as mp
import os
import resource
import tempfile
from pathlib import Path

import numpy as np

QUANTITIES = ("H_u_xx", "H_u_yy", "H_u_zz", "H_psi_x", "H_psi_y")


def mesh_grid(quick: bool) -> dict[int, list[float]]:
    """Mesh sizes [m] per element order (the FE model allows at most 0.04 m, 4x its thinnest
    wall); P1 goes finer than P2 to cover the same range of cost."""
    if quick:
        return {1: [0.036, 0.027, 0.02], 2: [0.036, 0.027, 0.02]}
    return {1: [0.027, 0.02, 0.014, 0.01], 2: [0.036, 0.027, 0.02, 0.015]}


def _solve_one(config, ring, size: float, order: int) -> dict:
    """Child process: one identification; returns its convergence row and peak RSS [GB]."""
    from bearingsim.fe_model import convergence_study

    with tempfile.TemporaryDirectory() as tmp:
        table = convergence_study(config, ring, [size], [order], Path(tmp))
    row = dict(table["rows"][0])
    row["peak_rss_gb"] = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024**2
    return row


def run_identification_study(config, ring, quick: bool, progress=print) -> dict:
    """Rows (one per order and size) with relative errors against the Richardson value."""
    from bearingsim.fe_model import richardson

    ctx = mp.get_context("spawn")
    rows = []
    for order, sizes in mesh_grid(quick).items():
        for size in sizes:
            progress(f"FE identification: P{order}, mesh size {size:.4g} m")
            with ctx.Pool(1, maxtasksperchild=1) as pool:
                rows.append(pool.apply(_solve_one, (config, ring, size, order)))
    best = max(rows, key=lambda r: (r["element_order"], -r["effective_mesh_size"]))["element_order"]
    mine = [r for r in rows if r["element_order"] == best]
    h = np.array([r["effective_mesh_size"] for r in mine])
    limits = {q: richardson(h, np.array([r[q] for r in mine])) for q in QUANTITIES}
    for r in rows:
        r["relative_error"] = abs(r["H_u_xx"] / limits["H_u_xx"][0] - 1.0)
        r["errors"] = {q: r[q] / limits[q][0] - 1.0 for q in QUANTITIES}
    return {"rows": rows, "richardson": {q: {"value": f0, "order": p} for q, (f0, p) in limits.items()},
            "richardson_from_order": best, "load_average": os.getloadavg()[0]}


def markdown_table(study: dict) -> str:
    lines = ["| order | mesh size [m] | h_eff [m] | dofs | H_u_xx [N/m] | error H_u_xx | error H_psi_x | "
             "wall [s] | peak RSS [GB] |", "|" + "---|" * 9]
    for r in study["rows"]:
        lines.append(f"| P{r['element_order']} | {r['mesh_size']:.4g} | {r['effective_mesh_size']:.4g} | {r['dofs']} | "
                     f"{r['H_u_xx']:.5e} | {r['errors']['H_u_xx']:+.2%} | {r['errors']['H_psi_x']:+.2%} | "
                     f"{r['seconds']:.1f} | {r['peak_rss_gb']:.2f} |")
    rich = study["richardson"]
    lines.append("")
    if any(not v["order"] == v["order"] for v in rich.values()):  # nan: no asymptotic order
        lines.append("p = nan: the three finest meshes do not converge monotonically (pre-asymptotic "
                     "or mesh noise), so the finest mesh stands in for the limit and its own error reads 0.")
    lines.append(f"Richardson (three finest P{study['richardson_from_order']} meshes): " + ", ".join(
        f"{q} = {v['value']:.5e} (p = {v['order']:.2f})" for q, v in rich.items())
        + f". Load average {study['load_average']:.1f}.")
    return "\n".join(lines)


def write_identification(study: dict, out_dir: Path) -> list[Path]:
    """identification_precision.json, .md and .png in `out_dir` (atomic writes)."""
    from . import write_study_files
    from .wp_plots import plot_identification

    return write_study_files(study, out_dir, "identification_precision", markdown_table(study),
                             lambda path: plot_identification(study["rows"], path))


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("scene", nargs="?", default="helicopter-b")
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--out", type=Path, default=Path("runs/bench"))
    args = ap.parse_args(argv)
    from bearingsim.pipeline.scene import load_scene
    from bearingsim.pipeline.stages.identify import ring_seat

    scene = load_scene(args.scene)
    if scene.fe is None:
        raise SystemExit(f"{scene.name}: hinge.source is {scene.hinge.source!r}; the identification "
                         "study needs a scene with hinge.source = 'fe' (e.g. helicopter-b)")
    study = run_identification_study(dataclasses.replace(scene.fe), ring_seat(scene), args.quick)
    write_identification(study, args.out)
    print(markdown_table(study))


if __name__ == "__main__":
    main()
