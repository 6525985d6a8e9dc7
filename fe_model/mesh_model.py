"""Stage 1 on the engineer's own mesh (`[fe] model = "mesh"`, docs/model.md §3.1).

The mesh (meshes.imported) is checked (fe_model.mesh_checks), assembled with the elasticity
of `elasticity.py` (P1 or P2 tetrahedra, one material per volume region) and clamped on
fe.fixed. The perturbation loads reach the structure through a distributing coupling of the
inner seat to a reference point at its centroid: the loads of a unit resultant (F, M) at that
point are the traction field of (M.43) on the seat, and the point's six displacements are the
least-squares rigid motion of the seat (M.44), the adjoint map (docs/model.md §3.1: RBE3).
With an outer seat, each case is the pair (F, M) on the inner seat and (-F, -M) on the outer
one, and the response is the inner seat's motion relative to the outer one's (M.45).

One factorisation (a direct solver) or one AMG hierarchy (conjugate gradients) serves every
load case.
"""

from __future__ import annotations

import pathlib
import time

import numpy as np

from .config import MESH_UNITS, FEConfig
from .loads import RegionMoments, distributed_load_matrix, rigid_fit_operator
from .mesh_checks import MeshInputError, check_mesh
from .solvers import rigid_body_modes, spd_solver


def solve_mesh_perturbations(config: FEConfig, ring, progress, refine: bool = False):
    """Read, check, assemble, solve every perturbation case of `config` on its mesh file;
    `refine`: every tetrahedron split into eight first (the convergence check). Returns the
    identify module's `_Solved`."""
    from skfem import FacetBasis

    from .elasticity import ElasticModel
    from .cases import _Solved, load_cases
    from ..meshes.imported import MeshReadError, read_mesh

    timings = {}
    t0 = time.perf_counter()
    progress("read mesh", 0.0)
    path = pathlib.Path(config.mesh_file)
    try:
        imported = read_mesh(path, MESH_UNITS[config.mesh_unit])
        mesh = imported.to_skfem(config.element_order)
    except MeshReadError as exc:
        raise MeshInputError("fe.mesh_file", f"fe.mesh_file: {exc}") from None
    except ValueError as exc:  # a surface whose triangles are no faces of the tetrahedra
        raise MeshInputError("fe.mesh_file", f"fe.mesh_file: {path}: {exc}") from None
    if refine:
        mesh = _refined(mesh)
    timings["read"] = time.perf_counter() - t0
    progress("check", 0.05)
    t0 = time.perf_counter()
    regions = check_mesh(mesh, config, ring)
    timings["check"] = time.perf_counter() - t0
    progress("assemble", 0.15)
    t0 = time.perf_counter()
    materials = {m.region: (m.youngs_modulus, m.poisson_ratio) for m in config.materials}
    model = ElasticModel.build(mesh, config.element_order, materials)
    K, free = model.stiffness_upper(model.boundary_dofs(config.fixed))
    element, q = model.basis.elem, 2 * config.element_order + 1

    def seat(facets):
        return RegionMoments.of(FacetBasis(mesh, element, facets=facets, intorder=q), centre=regions.centre)

    inner = seat(regions.inner_seat)
    unit_loads = distributed_load_matrix(inner)
    fit = rigid_fit_operator(inner)
    if regions.outer_seat is not None:
        outer = seat(regions.outer_seat)
        unit_loads = unit_loads - distributed_load_matrix(outer)
        fit = fit - rigid_fit_operator(outer)
    timings["assemble"] = time.perf_counter() - t0
    progress("factor", 0.35)
    t0 = time.perf_counter()
    def near_nullspace() -> np.ndarray:
        return rigid_body_modes(model.basis.doflocs.T)[free]

    solver = spd_solver(K, config.linear_solver, near_nullspace, config.iterative_tolerance,
                        config.direct_max_dofs)
    timings["factor"] = time.perf_counter() - t0
    progress("solve", 0.6)
    t0 = time.perf_counter()
    loads, groups, names = load_cases(config)
    U = np.zeros((model.n_dofs, len(names)))
    if solver.method == "amg":
        # conjugate gradients from zero are homogeneous in the load (x_k(a b) = a x_k(b)), so a
        # case is its magnitude times the unit case of its axis: one iterative solve per axis
        axes = np.flatnonzero(np.abs(loads).sum(axis=0))
        U_unit = np.zeros((model.n_dofs, 6))
        U_unit[np.ix_(free, axes)] = solver.solve(unit_loads[free][:, axes]).reshape(free.size, -1)
        U = U_unit @ loads.T
    else:
        U[free] = solver.solve((unit_loads @ loads.T)[free]).reshape(free.size, -1)
    solver_stats = _solver_stats(solver)
    solver.free()
    responses = (fit @ U).T
    timings["solve"] = time.perf_counter() - t0
    order = config.element_order
    stats = {"model": f"mesh: {'quadratic' if order == 2 else 'linear'} tetrahedra of {path.name}"
                      + (", each split into eight" if refine else ""),
             "mesh_file": str(path), "mesh_unit": config.mesh_unit, "mesh_quadratic": imported.quadratic,
             "nodes": int(mesh.nvertices), "elements": int(mesh.nelements), "dofs": int(model.n_dofs),
             "free_dofs": int(free.size), "matrix_nonzeros_upper": int(K.nnz), "element_order": order,
             "effective_mesh_size": float((np.sum(model.basis.dx) / mesh.nelements * 6.0 * 2**0.5) ** (1 / 3)),
             "reference_point_m": regions.centre.tolist(), "outer_seat_used": regions.outer_seat is not None,
             "seats": regions.seats,
             "warnings": [{"key": k, "message": m} for k, m in regions.warnings], **solver_stats}
    material = np.zeros(mesh.nelements, dtype=np.int32)
    for index, region in enumerate(config.materials):
        material[mesh.subdomains[region.region]] = index + 1

    def write_case(path_out: pathlib.Path, k: int) -> None:
        from .artefacts import write_case_vtu

        write_case_vtu(path_out, model, U[:, k], material, {"reference_point": regions.centre})

    return _Solved(loads, responses, groups, names, stats, timings, write_case, U)


def _refined(mesh):
    """Every tetrahedron split into eight (skfem's uniform refinement: the new vertices are
    the edge midpoints, vertex n_vertices + edge), volume and surface regions kept (each facet
    into its four children). A quadratic (curved) mesh is refined on its straight corner mesh:
    the check then measures the discretisation, not the curvature of the file's edges."""
    from skfem import MeshTet1

    from ..meshes.mesh_data import facet_lookup

    base = MeshTet1(mesh.p[:, : mesh.nvertices], mesh.t[:4], _subdomains=mesh.subdomains)
    fine = base.refined()
    lookup = facet_lookup(fine.facets)
    n = base.nvertices
    facet_edges = {}
    edges = {tuple(e): i for i, e in enumerate(np.sort(base.edges, axis=0).T.tolist())}
    boundaries = {}
    for name, facets in (mesh.boundaries or {}).items():
        children = []
        for f in np.asarray(facets):
            a, b, c = base.facets[:, f]
            if f not in facet_edges:
                facet_edges[f] = [n + edges[tuple(sorted(pair))] for pair in ((a, b), (b, c), (c, a))]
            ab, bc, ca = facet_edges[f]
            children += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        boundaries[name] = np.array([lookup[tuple(sorted(t))] for t in children], dtype=np.int64)
    return fine.with_boundaries(boundaries)


def _solver_stats(solver) -> dict:
    stats = {"linear_solver": solver.method}
    if solver.method == "amg":
        stats.update(amg_levels=solver.levels, cg_iterations_max=int(max(solver.iterations, default=0)),
                     cg_relative_residual_max=float(max(solver.residuals, default=0.0)),
                     cg_tolerance=solver.tolerance)
    return stats
