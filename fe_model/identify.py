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
"""

from __future__ import annotations

import pathlib
import time
from dataclasses import dataclass, field
from typing import Callable

import numpy as np

from bearingsim.fe_model.config import FEConfig
from bearingsim.fe_model.elasticity import ElasticModel
from bearingsim.fe_model.hinge_fit import HingeFit, fit_hinge
from bearingsim.fe_model.loads import RegionMoments, distributed_load_matrix, rigid_fit_operator
from bearingsim.fe_model.solvers import SPDFactorization
from bearingsim.meshes import RingSeat, cached_housing_mesh

Progress = Callable[[str, float], None]
MATERIAL_IDS = {"shaft": 1, "inner_ring": 2, "support_a": 3, "support_b": 3, "housing": 4}
LOAD_AXES = (("fx", 0), ("fy", 1), ("fz", 2), ("mx", 3), ("my", 4))


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


@dataclass
class _Solved:
    model: ElasticModel
    loads: np.ndarray  # (n, 6)
    responses: np.ndarray  # (n, 6)
    groups: np.ndarray  # (n,) magnitude index
    names: list
    displacements: np.ndarray  # (3N, n)
    mesh_stats: dict
    timings: dict


def load_cases(config: FEConfig) -> tuple[np.ndarray, np.ndarray, list[str]]:
    """All perturbation cases: (n, 6) loads [N, N*m], magnitude-set label, case names."""
    loads, groups, names = [], [], []
    for axis_name, axis in LOAD_AXES:
        values = config.perturbation_forces if axis < 3 else config.perturbation_moments
        for k, value in enumerate(values):
            row = np.zeros(6)
            row[axis] = value
            loads.append(row)
            groups.append(k)
            names.append(f"{axis_name}_{value:+g}")
    return np.array(loads), np.array(groups), names


def _materials(config: FEConfig, ring: RingSeat) -> dict:
    steel = (config.shaft_youngs_modulus, config.shaft_poisson_ratio)
    support = (config.support_modulus(ring), 0.0)
    return {"shaft": steel, "inner_ring": steel, "support_a": support, "support_b": support,
            "housing": (config.housing_youngs_modulus, config.housing_poisson_ratio)}


def solve_perturbations(config: FEConfig, ring: RingSeat, cache_dir: pathlib.Path, progress: Progress) -> _Solved:
    """Mesh (cached), assemble, factor once, solve every case, rigid-fit the responses."""
    from skfem import Basis, FacetBasis

    config.validate(ring)
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
    stats = {"nodes": mesh.nvertices, "elements": mesh.nelements, "dofs": model.n_dofs,
             "free_dofs": int(free.size), "matrix_nonzeros_upper": int(K.nnz),
             "mesh_size": config.mesh_size, "element_order": config.element_order,
             "effective_mesh_size": float((np.sum(model.basis.dx) / mesh.nelements * 6.0 * 2**0.5) ** (1 / 3)),
             "mesh_file": mesh_file.name, "mesh_reused": reused, "linear_solver": solver.method}
    return _Solved(model, loads, responses, groups, names, U, stats, timings)


def identify_hinge(
    config: FEConfig,
    ring: RingSeat,
    out_dir: pathlib.Path,
    progress: Progress | None = None,
    write_fields: bool = True,
) -> HingeIdentification:
    """Identify H_u (3x3) and H_psi (2) from the FE model and write the artefacts:
    `hinge.toml`, `case_<axis>.vtu` (largest magnitude of each load axis) and the mesh
    cache `mesh-<key>.npz`, all in `out_dir`."""
    from bearingsim.fe_model.artefacts import write_case_vtu, write_hinge_toml

    progress = progress or (lambda stage, fraction: None)
    out_dir = pathlib.Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    solved = solve_perturbations(config, ring, out_dir, progress)
    progress("fit", 0.85)
    t0 = time.perf_counter()
    fit = fit_hinge(solved.loads, solved.responses, solved.groups)
    solved.timings["fit"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    files = {}
    if write_fields:
        progress("write", 0.9)
        material = np.zeros(solved.model.mesh.nelements, dtype=np.int32)
        for name, ident in MATERIAL_IDS.items():
            material[solved.model.mesh.subdomains[name]] = ident
        for axis_name, axis in LOAD_AXES:
            pick = int(np.argmax(np.abs(solved.loads[:, axis])))
            path = out_dir / f"case_{axis_name}.vtu"
            write_case_vtu(path, solved.model, solved.displacements[:, pick], material)
            files[axis_name] = path.name
    solved.timings["write"] = time.perf_counter() - t0
    result = HingeIdentification(fit.H_u, fit.H_psi, fit, solved.mesh_stats, solved.timings, files)
    write_hinge_toml(out_dir / "hinge.toml", fit.H_u, fit.H_psi, _meta(config, solved, fit, files))
    files["hinge"] = "hinge.toml"
    progress("done", 1.0)
    return result


def _meta(config: FEConfig, solved: _Solved, fit: HingeFit, files: dict) -> dict:
    import dataclasses

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
        "config": dataclasses.asdict(config),
        "cases": cases,
    }
