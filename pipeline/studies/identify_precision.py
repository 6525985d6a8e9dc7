"""Work–precision of the hinge identification (stage 1): stiffness against mesh size, element
order and model, error against a converged reference, wall time and peak memory.

    python -m bearingsim.pipeline.studies.identify_precision [SCENE] [--quick | --fine] [--out DIR]

Rows: the axisymmetric model (the default; meridian section, Fourier modes 0 and 1) with
quadratic (P2) and linear (P1) triangles on a self-similar family of section meshes — the
scene's `edge_refinement`, `mesh_size` scaled by 2 — and, unless --quick, the 3-D model on
quadratic tetrahedra graded as the previous default (edge_refinement 0.25), for comparison.
Each row is solved by `fe_model.convergence_study` in a fresh process so that its peak
resident memory is its own; its wall time is mesh + assembly + factorisation + solves + fit
(no process start, no .vtu output).

The converged value of each stiffness is the Richardson extrapolation through the three
finest P2 axisymmetric meshes in their mesh size, the family's exact scale
(`fe_model.richardson`, Roache 1998 §5.4), with the observed order; the same extrapolation in
the effective element size is reported as a check. Every row's error is against it.
"""

from __future__ import annotations

import argparse
import dataclasses
import math
import multiprocessing as mp
import os
import resource
import tempfile
from pathlib import Path

import numpy as np

QUANTITIES = ("H_u_xx", "H_u_yy", "H_u_zz", "H_psi_x", "H_psi_y")
PREVIOUS_3D = {"mesh_size": 0.030, "edge_refinement": 0.25}  # the earlier 3-D default, for comparison


def mesh_grid(quick: bool, fine: bool = False) -> list[tuple[str, int, float, float | None]]:
    """(model, order, mesh size [m], edge_refinement or None for the scene's) of every row.
    `fine` adds the 0.00125 m P2 mesh (4.3M dofs, ~10 GB on the reference scene)."""
    if quick:
        return [("axisymmetric", 2, h, None) for h in (0.02, 0.01, 0.005)] + \
               [("axisymmetric", 1, h, None) for h in (0.01, 0.005)]
    p2 = (0.02, 0.01, 0.005, 0.0025) + ((0.00125,) if fine else ())
    return [("axisymmetric", 2, h, None) for h in p2] + \
           [("axisymmetric", 1, h, None) for h in (0.02, 0.01, 0.005, 0.0025)] + \
           [("3d", 2, h, PREVIOUS_3D["edge_refinement"]) for h in (0.036, PREVIOUS_3D["mesh_size"])]


def _solve_one(config, ring, size: float, order: int, model: str) -> dict:
    """Child process: one identification; returns its convergence row and peak RSS [GB]."""
    from ...fe_model import convergence_study

    with tempfile.TemporaryDirectory() as tmp:
        table = convergence_study(config, ring, [size], [order], Path(tmp), model)
    row = dict(table["rows"][0])
    row["peak_rss_gb"] = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024**2
    return row


def run_identification_study(config, ring, quick: bool, progress=print, fine: bool = False) -> dict:
    """Rows (one per model, order and size) with relative errors against the Richardson value."""
    from ...fe_model import richardson

    ctx = mp.get_context("spawn")
    rows = []
    for model, order, size, refinement in mesh_grid(quick, fine):
        cfg = config if refinement is None else dataclasses.replace(config, edge_refinement=refinement)
        progress(f"FE identification: {model} P{order}, mesh size {size:.4g} m, "
                 f"edge refinement {cfg.edge_refinement:g}")
        with ctx.Pool(1, maxtasksperchild=1) as pool:
            rows.append(pool.apply(_solve_one, (cfg, ring, size, order, model)))
    family = sorted((r for r in rows if r["model"] == "axisymmetric" and r["element_order"] == 2),
                    key=lambda r: -r["mesh_size"])
    h = np.array([r["mesh_size"] for r in family])
    h_eff = np.array([r["effective_mesh_size"] for r in family])
    limits = {q: richardson(h, np.array([r[q] for r in family])) for q in QUANTITIES}
    check = {q: richardson(h_eff, np.array([r[q] for r in family])) for q in QUANTITIES}
    for r in rows:
        r["errors"] = {q: r[q] / limits[q][0] - 1.0 for q in QUANTITIES}
        r["max_error"] = max(abs(e) for e in r["errors"].values())
        r["relative_error"] = r["max_error"]
        r["default"] = (r["model"] == "axisymmetric" and r["element_order"] == config.element_order
                        and math.isclose(r["mesh_size"], config.mesh_size)
                        and math.isclose(r["edge_refinement"], config.edge_refinement))
    return {"rows": rows,
            "richardson": {q: {"value": f0, "order": p} for q, (f0, p) in limits.items()},
            "richardson_effective_size": {q: {"value": f0, "order": p} for q, (f0, p) in check.items()},
            "richardson_from": {"model": "axisymmetric", "element_order": 2,
                                "mesh_sizes": sorted(h.tolist(), reverse=True)[-3:],
                                "edge_refinement": config.edge_refinement},
            "load_average": os.getloadavg()[0]}


def markdown_table(study: dict) -> str:
    lines = ["| model | order | mesh size [m] | edge ref. | h_eff [m] | dofs | " +
             " | ".join(f"error {q}" for q in QUANTITIES) + " | wall [s] | peak RSS [GB] |",
             "|" + "---|" * (len(QUANTITIES) + 8)]
    for r in study["rows"]:
        model = ("axisym." if r["model"] == "axisymmetric" else "3-D") + (" (default)" if r.get("default") else "")
        errors = " | ".join(f"{r['errors'][q]:+.3%}" for q in QUANTITIES)
        lines.append(f"| {model} | P{r['element_order']} | {r['mesh_size']:.4g} | {r['edge_refinement']:g} | "
                     f"{r['effective_mesh_size']:.3g} | {r['dofs']} | {errors} | {r['seconds']:.1f} | "
                     f"{r['peak_rss_gb']:.2f} |")
    rich, check, src = study["richardson"], study["richardson_effective_size"], study["richardson_from"]
    lines.append("")
    if any(not v["order"] == v["order"] for v in rich.values()):  # nan: no asymptotic order
        lines.append("p = nan: the three finest meshes do not converge monotonically (pre-asymptotic "
                     "or mesh noise), so the finest mesh stands in for the limit and its own error reads 0.")
    lines.append(f"Reference: Richardson through the axisymmetric P2 meshes of size "
                 f"{', '.join(f'{h:g}' for h in src['mesh_sizes'])} m (edge refinement {src['edge_refinement']:g}), "
                 "in the mesh size: " + ", ".join(f"{q} = {v['value']:.6e} (p = {v['order']:.2f})"
                                                  for q, v in rich.items()) + ". In the effective element size: "
                 + ", ".join(f"{q} {check[q]['value'] / v['value'] - 1:+.1e}" for q, v in rich.items())
                 + f" from that. Load average {study['load_average']:.1f}.")
    return "\n".join(lines)


def plot_identification(study: dict, path: Path) -> Path:
    """Largest stiffness error (of H_u_xx, yy, zz, H_psi_x, y) against wall time and peak
    memory, one curve per model and order; the default marked."""
    from ..figures import new_figure, save_png

    fig = new_figure(figsize=(10, 4.2), layout="tight")
    axes = fig.subplots(1, 2)
    curves = list(dict.fromkeys((r["model"], r["element_order"]) for r in study["rows"]))
    for model, order in curves:
        mine = [r for r in study["rows"] if (r["model"], r["element_order"]) == (model, order) and r["max_error"] > 0]
        label = (f"axisymmetric P{order} triangles" if model == "axisymmetric"
                 else f"3-D P{order} tetrahedra (previous default scheme)")
        for ax, key in zip(axes, ("seconds", "peak_rss_gb")):
            ax.loglog([r[key] for r in mine], [r["max_error"] for r in mine], "o-", ms=4, label=label)
            for r in mine:
                if r.get("default"):
                    ax.loglog([r[key]], [r["max_error"]], "*", ms=14, color="k", label="default")
    for ax, xlabel in zip(axes, ("wall time (mesh to fit) [s]", "peak memory [GB]")):
        ax.axhline(0.01, color="grey", lw=0.8, ls="--")
        ax.set_xlabel(xlabel)
        ax.set_ylabel("largest |H / reference - 1|")
        ax.grid(True, which="both", alpha=0.3)
    axes[0].legend(fontsize=7)
    fig.suptitle("Hinge identification: error against cost (reference: Richardson limit of the "
                 f"axisymmetric P2 family; load average {study['load_average']:.1f})", fontsize=9)
    save_png(fig, path, dpi=80)
    return path


def write_identification(study: dict, out_dir: Path) -> list[Path]:
    """identification_precision.json, .md and .png in `out_dir` (atomic writes)."""
    from . import write_study_files

    return write_study_files(study, out_dir, "identification_precision", markdown_table(study),
                             lambda path: plot_identification(study, path))


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("scene", nargs="?", default="helicopter-b")
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--fine", action="store_true", help="add the 0.00125 m P2 mesh (~90 s, ~10 GB)")
    ap.add_argument("--out", type=Path, default=Path("runs/bench"))
    args = ap.parse_args(argv)
    from ..scene.load import load_scene
    from ..stages.identify import ring_seat

    scene = load_scene(args.scene)
    if scene.fe is None:
        raise SystemExit(f"{scene.name}: hinge.source is {scene.hinge.source!r}; the identification "
                         "study needs a scene with hinge.source = 'fe' (e.g. helicopter-b)")
    study = run_identification_study(dataclasses.replace(scene.fe), ring_seat(scene), args.quick, fine=args.fine)
    write_identification(study, args.out)
    print(markdown_table(study))


if __name__ == "__main__":
    main()
