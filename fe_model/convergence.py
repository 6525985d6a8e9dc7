"""Hinge stiffness against mesh size and element order, with Richardson extrapolation."""

from __future__ import annotations

import csv
import dataclasses
import io
import math
import pathlib
import time

import numpy as np
from scipy.optimize import brentq

from .artefacts import atomic_write_bytes
from .config import FEConfig
from .hinge_fit import fit_hinge
from .identify import solve_perturbations
from ..meshes import RingSeat

QUANTITIES = ("H_u_xx", "H_u_yy", "H_u_zz", "H_psi_x", "H_psi_y")


def richardson(h: np.ndarray, f: np.ndarray) -> tuple[float, float]:
    """(f0, p) with f = f0 + C h^p through the three finest points (any size ratios).

    The order p solves (f1 - f2)/(f2 - f3) = (h1^p - h2^p)/(h2^p - h3^p); if the three
    values are not monotone (pre-asymptotic or noisy meshes) no order exists and
    (finest value, nan) is returned. Roache, "Verification and Validation in
    Computational Science and Engineering" (1998), §5.4, generalised refinement ratio.
    """
    order = np.argsort(h)[::-1][-3:]
    if order.size < 3:
        return float(f[np.argmin(h)]), math.nan
    (h1, h2, h3), (f1, f2, f3) = h[order], f[order]
    ratio = (f1 - f2) / (f2 - f3) if f2 != f3 else math.inf
    if not (ratio > 0.0 and math.isfinite(ratio)):
        return float(f3), math.nan

    def mismatch(p: float) -> float:
        return (h1**p - h2**p) / (h2**p - h3**p) - ratio

    try:
        p = brentq(mismatch, 0.05, 12.0)
    except ValueError:
        return float(f3), math.nan
    C = (f2 - f3) / (h2**p - h3**p)
    return float(f3 - C * h3**p), float(p)


def _row(order: int, size: float, solved, fit, seconds: float, model: str) -> dict:
    s = solved.mesh_stats
    return {"model": model, "element_order": order, "mesh_size": size, "edge_refinement": s["edge_refinement"],
            "effective_mesh_size": s["effective_mesh_size"],
            "dofs": s["dofs"], "H_u_xx": fit.H_u[0, 0], "H_u_yy": fit.H_u[1, 1], "H_u_zz": fit.H_u[2, 2],
            "H_psi_x": fit.H_psi[0], "H_psi_y": fit.H_psi[1], "seconds": seconds,
            "timings": dict(solved.timings)}


def convergence_study(
    config: FEConfig,
    ring: RingSeat,
    mesh_sizes,
    orders,
    out_dir: pathlib.Path,
    model: str = "axisymmetric",
) -> dict:
    """Solve the identification for every (order, mesh size) at the config's edge_refinement
    (a self-similar family: the meshes differ by a scale); write convergence.csv and
    convergence.md to `out_dir`. Returns {"rows": [...], "richardson": {order: {q: (f0, p)}}}
    with the extrapolation in the effective element size (of the mean element's measure).
    model: "axisymmetric" (default) or "3d" (fe_model.identify.solve_perturbations)."""
    out_dir = pathlib.Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    rows = []
    for order in orders:
        for size in sorted(mesh_sizes, reverse=True):
            cfg = dataclasses.replace(config, mesh_size=float(size), element_order=int(order))
            t0 = time.perf_counter()
            solved = solve_perturbations(cfg, ring, out_dir, lambda stage, fraction: None, model)
            fit = fit_hinge(solved.loads, solved.responses, solved.groups)
            rows.append(_row(order, size, solved, fit, time.perf_counter() - t0, model))
            del solved
    extrapolated = {}
    for order in orders:
        mine = [r for r in rows if r["element_order"] == order]
        h = np.array([r["effective_mesh_size"] for r in mine])
        extrapolated[order] = {q: richardson(h, np.array([r[q] for r in mine])) for q in QUANTITIES}
    table = {"rows": rows, "richardson": extrapolated}
    _write_tables(out_dir, table)
    return table


def _write_tables(out_dir: pathlib.Path, table: dict) -> None:
    rows = table["rows"]
    buf = io.StringIO()
    fields = [k for k in rows[0] if k != "timings"]
    writer = csv.DictWriter(buf, fieldnames=fields, extrasaction="ignore")
    writer.writeheader()
    writer.writerows(rows)
    atomic_write_bytes(out_dir / "convergence.csv", buf.getvalue().encode())
    lines = ["# Hinge stiffness vs mesh (N/m, N*m/rad)", "",
             "| order | h [m] | h_eff [m] | dofs | " + " | ".join(QUANTITIES) + " | time [s] |",
             "|" + "---|" * (len(QUANTITIES) + 5)]
    for r in rows:
        values = " | ".join(f"{r[q]:.4e}" for q in QUANTITIES)
        lines.append(f"| {r['element_order']} | {r['mesh_size']:.4g} | {r['effective_mesh_size']:.4g} | "
                     f"{r['dofs']} | {values} | {r['seconds']:.1f} |")
    for order, est in table["richardson"].items():
        values = " | ".join(f"{f0:.4e} (p={p:.2f})" for f0, p in est.values())
        lines.append(f"| {order} | Richardson | | | {values} | |")
    atomic_write_bytes(out_dir / "convergence.md", ("\n".join(lines) + "\n").encode())
