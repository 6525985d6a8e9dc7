"""Stage 1 end to end: mesh, assemble, factor once, solve all perturbation cases, fit M.2.

What is loaded and what is measured (docs/model.md §3). The hinge of §5 ties the inner race
to a fixed frame while the outer race is fixed, so it must carry the compliance of
everything between the two raceways except the balls: inner ring -> shaft -> support
bearings -> housing -> outer-ring seat. With `load_reaction = "outer_seat"` (default)
each perturbation is applied as the pair the balls would transmit: (F, M) on the inner
ring raceway and (-F, -M) on the outer-ring seat, both about the ring centre; the
response is the rigid motion of the inner ring relative to that of the seat. The
clamped flange only removes rigid-body motion (the pair is self-equilibrated).
With `load_reaction = "flange"` the load acts on the inner ring alone and is reacted
at the flange; the response is absolute (it then includes the housing's flexibility
between seat and flange, which the bearing does not see).

How it is solved: the assembly, its clamp and its loads are axisymmetric and every load is
Fourier mode 0 or 1 round the axis, so by default the model is the meridian section with
quadratic triangles and two Fourier modes (`fe_model.axisymmetric`: an exact split of the 3-D
problem; the default section mesh is within 0.04 % of the converged hinge, docs/performance.md,
"FE identification"). Each case is then a combination of three unit solutions (F_x and M_y in mode 1,
F_z in mode 0; F_y and M_x are F_x and M_y turned by 90 degrees). `solve_perturbations(...,
model="3d")` solves the same problem on quadratic tetrahedra (`elasticity.py`) with one solve
per case: the independent cross-check.
"""

from __future__ import annotations

import dataclasses
import pathlib
import time
from dataclasses import dataclass, field
from typing import Callable

import numpy as np

from .config import FEConfig
from .cases import LOAD_AXES, _Solved, load_cases  # noqa: F401  (load_cases: public here too)
from .hinge_fit import HingeFit, fit_hinge
from .loads import RegionMoments, distributed_load_matrix, rigid_fit_operator
from .solvers import SPDFactorization
from ..meshes import RingSeat, cached_housing_mesh

Progress = Callable[[str, float], None]
MATERIAL_IDS = {"shaft": 1, "inner_ring": 2, "support_a": 3, "support_b": 3, "housing": 4}


@dataclass
class HingeIdentification:
    """Result of stage 1: hinge stiffness, fit quality, mesh statistics, timings [s]."""

    H_u: np.ndarray  # (3, 3) N/m
    H_psi: np.ndarray  # (2,) N*m/rad
    fit: HingeFit
    mesh_stats: dict
    timings: dict
    files: dict = field(default_factory=dict)

    @property
    def residual(self) -> float:
        return self.fit.relative_residual

    @property
    def condition_number(self) -> float:
        return self.fit.condition_number

    @property
    def coupling(self) -> dict:
        return self.fit.coupling


def _materials(config: FEConfig, ring: RingSeat) -> dict:
    steel = (config.shaft_youngs_modulus, config.shaft_poisson_ratio)
    support = (config.support_modulus(ring), 0.0)
    return {"shaft": steel, "inner_ring": steel, "support_a": support, "support_b": support,
            "housing": (config.housing_youngs_modulus, config.housing_poisson_ratio)}


def solve_perturbations(config: FEConfig, ring: RingSeat, cache_dir: pathlib.Path, progress: Progress,
                        model: str = "axisymmetric", refine: bool = False) -> _Solved:
    """Mesh (cached), assemble, factor once, solve every case, rigid-fit the responses.
    For the parametric housing, model: "axisymmetric" (the meridian section, default) or "3d"
    (tetrahedra); `config.model = "mesh"` solves on the engineer's mesh instead
    (fe_model.mesh_model). `refine`: a once-refined discretisation (the convergence check)."""
    config.validate(ring)
    if config.model == "mesh":
        from .mesh_model import solve_mesh_perturbations

        return solve_mesh_perturbations(config, ring, progress, refine)
    if refine:
        config = dataclasses.replace(config, mesh_size=0.5 * config.mesh_size)
    if model == "axisymmetric":
        return _solve_axisymmetric(config, ring, cache_dir, progress)
    if model == "3d":
        return _solve_3d(config, ring, cache_dir, progress)
    raise ValueError(f"FE model {model!r}: allowed 'axisymmetric' or '3d'")


def _solve_axisymmetric(config: FEConfig, ring: RingSeat, cache_dir: pathlib.Path, progress: Progress) -> _Solved:
    from skfem import Basis, FacetBasis

    from .axisymmetric import (AxisymmetricRegion, HarmonicModel, HarmonicSolution,
                                                  mode0_load, mode1_load, rigid_fit_rows, unit_responses)
    from ..meshes.cache import cached_section_mesh

    timings = {}
    t0 = time.perf_counter()
    progress("mesh", 0.0)
    geometry = config.housing_geometry(ring)
    section, mesh_file, reused = cached_section_mesh(geometry, config.mesh_size, cache_dir, config.edge_refinement)
    mesh = section.to_skfem()
    timings["mesh"] = time.perf_counter() - t0
    progress("assemble", 0.15)
    t0 = time.perf_counter()
    model = HarmonicModel.build(mesh, config.element_order, _materials(config, ring))
    clamp = model.boundary_dofs("housing_flange")
    K1, red1 = model.stiffness_upper(1, clamp)
    K0, red0 = model.stiffness_upper(0, clamp)
    e, q = model.basis.elem, config.element_order + 3  # phi r^2 on lines, phi r z on cells

    def region(group: str, volume: bool = False) -> AxisymmetricRegion:
        if volume:
            return AxisymmetricRegion.of(Basis(mesh, e, elements=mesh.subdomains[group], intorder=q))
        return AxisymmetricRegion.of(FacetBasis(mesh, e, facets=mesh.boundaries[group], intorder=q))

    race = region("inner_ring_race")
    F1 = np.column_stack([mode1_load(race, 1.0, 0.0), mode1_load(race, 0.0, 1.0)])
    F0 = mode0_load(race, 1.0)
    L1, L0 = rigid_fit_rows(region("inner_ring", volume=True))
    if config.load_reaction == "outer_seat":
        seat = region("outer_ring_seat")
        F1 = F1 - np.column_stack([mode1_load(seat, 1.0, 0.0), mode1_load(seat, 0.0, 1.0)])
        F0 = F0 - mode0_load(seat, 1.0)
        S1, S0 = rigid_fit_rows(seat)
        L1, L0 = L1 - S1, L0 - S0
    timings["assemble"] = time.perf_counter() - t0
    progress("factor", 0.35)
    t0 = time.perf_counter()
    solver1 = SPDFactorization(K1, config.linear_solver)
    solver0 = SPDFactorization(K0, config.linear_solver)
    timings["factor"] = time.perf_counter() - t0
    progress("solve", 0.7)
    t0 = time.perf_counter()
    U1 = red1.expand(solver1.solve(red1.restrict(F1)).reshape(red1.size, 2))
    U0 = red0.expand(solver0.solve(red0.restrict(F0)).reshape(red0.size))
    solver1.free()
    solver0.free()
    # linear: each case is a combination of the unit responses (F_y, M_x by turning F_x, M_y)
    unit = unit_responses(L1 @ U1, L0 @ U0)
    loads, groups, names = load_cases(config)
    responses = loads[:, :5] @ unit.T
    timings["solve"] = time.perf_counter() - t0
    area = 0.5 * float(np.sum(model.basis.dx))
    stats = {"model": "axisymmetric: meridian section, Fourier modes 0 and 1",
             "nodes": int(mesh.nvertices), "elements": int(mesh.nelements),
             "dofs": int(5 * model.basis.N),  # U_r, U_theta, U_z of mode 1 + U_r, U_z of mode 0
             "free_dofs": red1.size + red0.size, "matrix_nonzeros_upper": int(K1.nnz + K0.nnz),
             "mesh_size": config.mesh_size, "edge_refinement": config.edge_refinement,
             "element_order": config.element_order,
             "effective_mesh_size": float((2.0 * area / mesh.nelements * 2.0 / 3.0**0.5) ** 0.5),
             "mesh_file": mesh_file.name, "mesh_reused": reused, "linear_solver": solver1.method}
    solution = HarmonicSolution(model, U1, U0)
    view = {}

    def write_case(path: pathlib.Path, k: int) -> None:
        from .artefacts import RevolvedView, write_revolved_case_vtu

        if "view" not in view:
            view["view"] = RevolvedView.of(solution, geometry, cache_dir, MATERIAL_IDS)
        write_revolved_case_vtu(path, view["view"], loads[k])

    return _Solved(loads, responses, groups, names, stats, timings, write_case)


def _solve_3d(config: FEConfig, ring: RingSeat, cache_dir: pathlib.Path, progress: Progress) -> _Solved:
    from skfem import Basis, FacetBasis

    from .elasticity import ElasticModel

    timings = {}
    t0 = time.perf_counter()
    progress("mesh", 0.0)
    data, mesh_file, reused = cached_housing_mesh(
        config.housing_geometry(ring), config.mesh_size, cache_dir, config.edge_refinement)
    mesh = data.to_skfem()
    timings["mesh"] = time.perf_counter() - t0
    progress("assemble", 0.15)
    t0 = time.perf_counter()
    model = ElasticModel.build(mesh, config.element_order, _materials(config, ring))
    K, free = model.stiffness_upper(model.boundary_dofs("housing_flange"))
    e, q = model.basis.elem, config.element_order + 2
    race = RegionMoments.of(FacetBasis(mesh, e, facets=mesh.boundaries["inner_ring_race"], intorder=q))
    ring_fit = rigid_fit_operator(RegionMoments.of(Basis(mesh, e, elements=mesh.subdomains["inner_ring"], intorder=q)))
    unit_loads = distributed_load_matrix(race)
    if config.load_reaction == "outer_seat":
        seat = RegionMoments.of(FacetBasis(mesh, e, facets=mesh.boundaries["outer_ring_seat"], intorder=q))
        unit_loads = unit_loads - distributed_load_matrix(seat)
        ring_fit = ring_fit - rigid_fit_operator(seat)
    timings["assemble"] = time.perf_counter() - t0
    progress("factor", 0.35)
    t0 = time.perf_counter()
    solver = SPDFactorization(K, config.linear_solver)
    timings["factor"] = time.perf_counter() - t0
    progress("solve", 0.7)
    t0 = time.perf_counter()
    loads, groups, names = load_cases(config)
    U = np.zeros((model.n_dofs, len(names)))
    U[free] = solver.solve((unit_loads @ loads.T)[free]).reshape(free.size, -1)
    solver.free()
    responses = (ring_fit @ U).T
    timings["solve"] = time.perf_counter() - t0
    stats = {"model": "3-D: quadratic tetrahedra",
             "nodes": mesh.nvertices, "elements": mesh.nelements, "dofs": model.n_dofs,
             "free_dofs": int(free.size), "matrix_nonzeros_upper": int(K.nnz),
             "mesh_size": config.mesh_size, "edge_refinement": config.edge_refinement,
             "element_order": config.element_order,
             "effective_mesh_size": float((np.sum(model.basis.dx) / mesh.nelements * 6.0 * 2**0.5) ** (1 / 3)),
             "mesh_file": mesh_file.name, "mesh_reused": reused, "linear_solver": solver.method}
    material = np.zeros(mesh.nelements, dtype=np.int32)
    for name, ident in MATERIAL_IDS.items():
        material[mesh.subdomains[name]] = ident

    def write_case(path: pathlib.Path, k: int) -> None:
        from .artefacts import write_case_vtu

        write_case_vtu(path, model, U[:, k], material)

    return _Solved(loads, responses, groups, names, stats, timings, write_case, U)


def identify_hinge(
    config: FEConfig,
    ring: RingSeat,
    out_dir: pathlib.Path,
    progress: Progress | None = None,
    write_fields: bool = True,
    model: str = "axisymmetric",
) -> HingeIdentification:
    """Identify H_u (3x3) and H_psi (2) from the FE model and write the artefacts:
    `hinge.toml`, `case_<axis>.vtu` (largest magnitude of each load axis) and the mesh
    cache (`section-<key>.npz`, or `mesh-<key>.npz` for model "3d"), all in `out_dir`."""
    from .artefacts import write_hinge_toml

    progress = progress or (lambda stage, fraction: None)
    out_dir = pathlib.Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    solved = solve_perturbations(config, ring, out_dir, progress, model)
    progress("fit", 0.85)
    t0 = time.perf_counter()
    fit = fit_hinge(solved.loads, solved.responses, solved.groups)
    solved.timings["fit"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    files = {}
    if write_fields:
        progress("write", 0.9)
        for axis_name, axis in LOAD_AXES:
            pick = int(np.argmax(np.abs(solved.loads[:, axis])))
            path = out_dir / f"case_{axis_name}.vtu"
            solved.write_case(path, pick)
            files[axis_name] = path.name
    solved.timings["write"] = time.perf_counter() - t0
    meta = _meta(config, solved, fit, files)
    if config.refinement_check:
        progress("refine", 0.92)
        t0 = time.perf_counter()
        meta["refinement"] = refinement_change(config, ring, out_dir, fit, model)
        solved.timings["refinement_check"] = time.perf_counter() - t0
    result = HingeIdentification(fit.H_u, fit.H_psi, fit, solved.mesh_stats, solved.timings, files)
    write_hinge_toml(out_dir / "hinge.toml", fit.H_u, fit.H_psi, meta)
    files["hinge"] = "hinge.toml"
    progress("done", 1.0)
    return result


def refinement_change(config: FEConfig, ring: RingSeat, out_dir: pathlib.Path, fit: HingeFit,
                      model: str = "axisymmetric") -> dict:
    """The hinge on a once-refined discretisation and the relative change of each term
    (refined - scene) / refined: an estimate of the scene's discretisation error."""
    fine_solved = solve_perturbations(config, ring, out_dir, lambda stage, fraction: None, model, refine=True)
    fine = fit_hinge(fine_solved.loads, fine_solved.responses, fine_solved.groups)
    change = {name: float((value(fit) - value(fine)) / value(fine)) for name, value in HINGE_TERMS.items()}
    return {"what": ("mesh_size halved" if config.model != "mesh" else "every tetrahedron split into eight"),
            "dofs": int(fine_solved.mesh_stats["dofs"]),
            "H_u_refined": fine.H_u.tolist(), "H_psi_refined": fine.H_psi.tolist(),
            "relative_change": change, "largest_relative_change": float(max(abs(v) for v in change.values()))}


HINGE_TERMS = {"H_u_xx": lambda f: f.H_u[0, 0], "H_u_yy": lambda f: f.H_u[1, 1], "H_u_zz": lambda f: f.H_u[2, 2],
               "H_psi_x": lambda f: f.H_psi[0], "H_psi_y": lambda f: f.H_psi[1]}


def _meta(config: FEConfig, solved: _Solved, fit: HingeFit, files: dict) -> dict:
    config_table = dataclasses.asdict(config)
    config_table["materials"] = {m.region: {"youngs_modulus": m.youngs_modulus, "poisson_ratio": m.poisson_ratio}
                                 for m in config.materials}
    cases = [
        {"name": n, "load": l.tolist(), "displacement_m": r[:3].tolist(), "rotation_rad": r[3:].tolist()}
        for n, l, r in zip(solved.names, solved.loads, solved.responses)
    ]
    return {
        "fit": {
            "residual_translation_m": fit.residual_u,
            "residual_rotation_rad": fit.residual_psi,
            "relative_residual": fit.relative_residual,
            "condition_number": fit.condition_number,
            "magnitude_spread": fit.magnitude_spread,
            "load_reaction": config.load_reaction,
        },
        "coupling": fit.coupling,
        "flexibility": {"matrix": fit.flexibility.tolist(),
                        "rows": "u_x u_y u_z [m], theta_x theta_y theta_z [rad]",
                        "columns": "F_x F_y F_z [N], M_x M_y [N*m]"},
        "mesh": solved.mesh_stats,
        "timings_s": solved.timings,
        "files": files,
        "config": config_table,
        "cases": cases,
    }
