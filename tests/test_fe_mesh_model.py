"""The hinge identified from the engineer's own mesh (`[fe] model = "mesh"`, docs/model.md §3.1).

The example housing on two feet (meshes/example_housing.py) at a coarse size keeps these fast;
the cross-check against the axisymmetric model at the documented tolerance is `slow`."""

import dataclasses

import numpy as np
import pytest

from bearingsim.fe_model import RingSeat
from bearingsim.fe_model.config import FEConfig, RegionMaterial
from bearingsim.fe_model.hinge_fit import fit_hinge
from bearingsim.fe_model.identify import identify_hinge, solve_perturbations
from bearingsim.fe_model.mesh_checks import MeshInputError
from bearingsim.meshes.example_housing import write_foot_housing_mesh
from bearingsim.meshes.imported import ImportedMesh, read_mesh, write_abaqus_inp

COARSE = 0.025  # m: a few thousand linear tetrahedra, a second per identification
MATERIALS = (RegionMaterial("shaft", 208e9, 0.3), RegionMaterial("support_a", 2.195e9, 0.0),
             RegionMaterial("support_b", 2.195e9, 0.0), RegionMaterial("housing", 71e9, 0.33))


@pytest.fixture(scope="module")
def feet_msh(tmp_path_factory):
    return write_foot_housing_mesh(tmp_path_factory.mktemp("mesh") / "feet.msh", COARSE, order=1)


def config(mesh_file, **changes) -> FEConfig:
    return dataclasses.replace(FEConfig(model="mesh", mesh_file=str(mesh_file), materials=MATERIALS,
                                        element_order=1, linear_solver="splu"), **changes)


def hinge(cfg: FEConfig, tmp_path=None):
    solved = solve_perturbations(cfg, RingSeat(), tmp_path, lambda stage, fraction: None)
    return fit_hinge(solved.loads, solved.responses, solved.groups), solved


def relative(a, b) -> float:
    return float(np.max(np.abs(np.asarray(a) - np.asarray(b)) / np.max(np.abs(b))))


def test_msh_and_the_same_mesh_as_abaqus_inp_give_the_same_hinge(feet_msh, tmp_path):
    # the .inp names the seats and the clamp as node sets (*NSET), the .msh as triangles
    inp = tmp_path / "feet.inp"
    write_abaqus_inp(inp, read_mesh(feet_msh), metres_per_unit=1e-3)
    a, _ = hinge(config(feet_msh))
    b, _ = hinge(config(inp, mesh_unit="mm"))
    # the same mesh and the same direct solve: equal to round-off (17 digits in the .inp)
    assert relative(b.H_u, a.H_u) < 1e-9 and relative(b.H_psi, a.H_psi) < 1e-9


def test_doubling_every_youngs_modulus_doubles_the_hinge(feet_msh):
    a, _ = hinge(config(feet_msh))
    stiffer = tuple(dataclasses.replace(m, youngs_modulus=2.0 * m.youngs_modulus) for m in MATERIALS)
    b, _ = hinge(config(feet_msh, materials=stiffer))
    # linear elasticity: K scales with E, the compliance halves (Poisson ratios unchanged)
    assert relative(b.H_u, 2.0 * a.H_u) < 1e-6 and relative(b.H_psi, 2.0 * a.H_psi) < 1e-6


def test_perturbation_magnitude_does_not_change_the_hinge(feet_msh):
    a, _ = hinge(config(feet_msh))
    b, _ = hinge(config(feet_msh, perturbation_forces=(3.0,), perturbation_moments=(-7.0,)))
    assert relative(b.H_u, a.H_u) < 1e-9 and relative(b.H_psi, a.H_psi) < 1e-9
    assert a.magnitude_spread < 1e-9  # each magnitude set alone gives the same H


def test_the_coupling_distributes_with_the_transpose_of_its_read_out(feet_msh):
    """RBE3: the seat loads of a unit (F, M) are L^T (F, M), with L the least-squares rigid
    motion of the seat, so the reference point's compliance L K^-1 L^T is symmetric."""
    from skfem import FacetBasis

    from bearingsim.fe_model.elasticity import ElasticModel
    from bearingsim.fe_model.loads import RegionMoments, distributed_load_matrix, rigid_fit_operator

    mesh = read_mesh(feet_msh).to_skfem(2)
    model = ElasticModel.build(mesh, 2, {m.region: (m.youngs_modulus, m.poisson_ratio) for m in MATERIALS})
    seat = RegionMoments.of(FacetBasis(mesh, model.basis.elem, facets=mesh.boundaries["inner_seat"], intorder=5),
                            centre=(0.001, -0.002, 0.003))
    P, L = distributed_load_matrix(seat), rigid_fit_operator(seat)
    assert np.allclose(P, L.T, rtol=0.0, atol=1e-9 * np.abs(P).max())
    # R: the six rigid motions about the reference point at the nodes; R^T f is a nodal load's
    # resultant and moment, so R^T P = I (the unit loads arrive whole) and L R = I (a rigid
    # motion of the seat reads back as itself)
    r = model.basis.doflocs.T - np.array([0.001, -0.002, 0.003])
    R = np.zeros((r.shape[0], 3, 6))
    for c in range(3):
        R[:, c, c] = 1.0
        R[:, :, 3 + c] = np.cross(np.eye(3)[c], r)
    R = R.reshape(-1, 6)
    assert np.allclose(R.T @ P, np.eye(6), atol=1e-9) and np.allclose(L @ R, np.eye(6), atol=1e-9)


def test_the_reference_point_is_the_seat_centroid_and_the_fit_is_reported(feet_msh, tmp_path):
    result = identify_hinge(config(feet_msh), RingSeat(), tmp_path, write_fields=False)
    ref = np.array(result.mesh_stats["reference_point_m"])
    assert np.linalg.norm(ref) < 1e-3  # the seat is a cylinder round the z axis, centred at z = 0 [m]
    assert 0.0 < result.residual < 0.05 and result.mesh_stats["outer_seat_used"]
    # the housing stands on feet below it: translation along x (across the feet) and y (towards
    # them) differ, which no axisymmetric model can show
    assert abs(result.H_u[0, 0] - result.H_u[1, 1]) > 1e-3 * result.H_u[0, 0]
    text = (tmp_path / "hinge.toml").read_text()
    assert "[fit]" in text and "reference_point_m" in text


def test_quadratic_file_keeps_its_curved_edges(tmp_path):
    """A 10-node mesh is solved isoparametrically: against the same corners with straight
    edges it differs by the curvature of the cylinders, a small amount."""
    curved = write_foot_housing_mesh(tmp_path / "p2.msh", 0.03, order=2)
    imported = read_mesh(curved)
    assert imported.quadratic
    straight = ImportedMesh(imported.points[: imported.n_corners], imported.tets, None, imported.volumes,
                            imported.surfaces, imported.node_sets)
    write_abaqus_inp(tmp_path / "p1.inp", straight)
    a, sa = hinge(config(curved, element_order=2))
    b, _ = hinge(config(tmp_path / "p1.inp", element_order=2))
    assert type(read_mesh(curved).to_skfem(2)).__name__ == "MeshTet2"
    change = relative(a.H_psi, b.H_psi)
    assert 0.0 < change < 0.05, change


def test_refinement_check_reports_the_change_of_each_term(feet_msh, tmp_path):
    result = identify_hinge(config(feet_msh, refinement_check=True), RingSeat(), tmp_path, write_fields=False)
    import tomllib

    refinement = tomllib.loads((tmp_path / "hinge.toml").read_text())["refinement"]
    assert refinement["dofs"] > 4 * result.mesh_stats["dofs"]
    # linear tetrahedra converge from the stiff side: the refined hinge is softer
    assert all(v > 0.0 for v in refinement["relative_change"].values()), refinement


# --- errors before any solve, naming key and region ---------------------------------------------
def test_missing_region_names_the_key_and_the_regions_the_mesh_has(feet_msh):
    with pytest.raises(MeshInputError) as err:
        hinge(config(feet_msh, inner_seat="bore"))
    assert err.value.key == "fe.inner_seat" and "'bore'" in str(err.value) and "outer_seat" in str(err.value)


def test_a_volume_named_as_seat_or_a_missing_material_is_refused(feet_msh):
    with pytest.raises(MeshInputError) as err:
        hinge(config(feet_msh, fixed="housing"))
    assert err.value.key == "fe.fixed" and "volume" in str(err.value)
    with pytest.raises(MeshInputError) as err:
        hinge(config(feet_msh, materials=MATERIALS[:3]))
    assert err.value.key == "fe.materials" and "'housing'" in str(err.value)


def test_mesh_in_millimetres_read_as_metres_is_refused(feet_msh, tmp_path):
    inp = tmp_path / "mm.inp"
    write_abaqus_inp(inp, read_mesh(feet_msh), metres_per_unit=1e-3)
    with pytest.raises(MeshInputError) as err:
        hinge(config(inp, mesh_unit="m"))
    text = str(err.value)
    assert err.value.key == "fe.inner_seat" and "not on this seat" in text and "fe.mesh_unit = 'mm'" in text


def test_empty_region_is_refused(feet_msh, tmp_path):
    mesh = read_mesh(feet_msh)
    inp = tmp_path / "empty.inp"
    write_abaqus_inp(inp, dataclasses.replace(mesh, surfaces={k: v for k, v in mesh.surfaces.items() if k != "fixed"},
                                              node_sets={"fixed": np.array([0, 1], dtype=np.int64)}))
    with pytest.raises(MeshInputError) as err:
        hinge(config(inp))
    assert err.value.key == "fe.fixed" and "empty" in str(err.value)


def test_free_body_is_named(feet_msh, tmp_path):
    # without its supports the shaft touches nothing: clamping the feet leaves it free
    mesh = read_mesh(feet_msh)
    keep = np.setdiff1d(np.arange(mesh.tets.shape[0]), np.r_[mesh.volumes["support_a"], mesh.volumes["support_b"]])
    new = np.full(mesh.tets.shape[0], -1)
    new[keep] = np.arange(keep.size)
    volumes = {k: new[v] for k, v in mesh.volumes.items() if k in ("shaft", "housing")}
    inp = tmp_path / "free.inp"
    write_abaqus_inp(inp, dataclasses.replace(mesh, tets=mesh.tets[keep], volumes=volumes))
    with pytest.raises(MeshInputError) as err:
        hinge(config(inp, materials=(MATERIALS[0], MATERIALS[3])))
    assert err.value.key == "fe.fixed" and "'shaft'" in str(err.value) and "free" in str(err.value)


def test_unreadable_file_names_the_key(tmp_path):
    bad = tmp_path / "housing.inp"
    bad.write_text("*NODE\n1, a, b\n")
    with pytest.raises(MeshInputError) as err:
        hinge(config(bad))
    assert err.value.key == "fe.mesh_file" and str(bad) in str(err.value)
    with pytest.raises(MeshInputError) as err:
        hinge(config(tmp_path / "missing.msh"))
    assert err.value.key == "fe.mesh_file" and "does not exist" in str(err.value)


def test_a_mesh_without_outer_seat_is_measured_against_the_ground(feet_msh, tmp_path):
    mesh = read_mesh(feet_msh)
    inp = tmp_path / "no_outer.inp"
    write_abaqus_inp(inp, dataclasses.replace(mesh, surfaces={k: v for k, v in mesh.surfaces.items()
                                                              if k != "outer_seat"}))
    paired, _ = hinge(config(feet_msh))
    grounded, solved = hinge(config(inp))
    assert any(w["key"] == "fe.outer_seat" for w in solved.mesh_stats["warnings"])
    # the ground-relative hinge adds the housing between seat and feet: softer
    assert grounded.H_psi[0] < paired.H_psi[0] and grounded.H_u[1, 1] < paired.H_u[1, 1]


# --- cross-check: the 3-D mesh of the axisymmetric assembly against the axisymmetric model --------
def axisymmetric_assembly_as_mesh(tmp_path, mesh_size: float, edge_refinement: float, order: int = 2):
    """The repository's own 3-D mesh of the parametric assembly (meshes/housing.py), written as
    a .msh, as `[fe] model = "mesh"` reads it: loads on the raceway, reacted on the outer-ring
    seat, the flange clamped, the axisymmetric model's materials."""
    from bearingsim.fe_model.identify import _materials
    from bearingsim.meshes.housing import build_housing_mesh

    ring, base = RingSeat(), FEConfig()
    path = tmp_path / "assembly.msh"
    build_housing_mesh(base.housing_geometry(ring), mesh_size, edge_refinement, msh_file=path)
    materials = tuple(RegionMaterial(name, E, nu) for name, (E, nu) in _materials(base, ring).items())
    return FEConfig(model="mesh", mesh_file=str(path), materials=materials, inner_seat="inner_ring_race",
                    outer_seat="outer_ring_seat", fixed="housing_flange", element_order=order)


def test_mesh_of_the_axisymmetric_assembly_is_near_the_axisymmetric_hinge(tmp_path):
    """A coarse uniform 3-D mesh (0.03 m, P2, ~40k dofs) against the default axisymmetric hinge
    (itself within 0.04 % of its converged value, docs/model.md §3). Tetrahedra converge from the
    stiff side; the radial and bending terms are within 1 % already, the axial one, governed by
    the singular stresses at the support edges, within 12 %. The documented tolerance holds on
    the graded mesh of the slow test below (docs/validation.md §14)."""
    axi, _ = hinge(FEConfig(), tmp_path)
    mesh, _ = hinge(axisymmetric_assembly_as_mesh(tmp_path, 0.03, 1.0), tmp_path)
    a, m = np.r_[np.diag(axi.H_u), axi.H_psi], np.r_[np.diag(mesh.H_u), mesh.H_psi]
    excess = m / a - 1.0
    assert np.all(excess > 0.0), excess
    assert np.all(excess[[0, 1, 3, 4]] < 0.015) and excess[2] < 0.15, excess


@pytest.mark.slow
def test_graded_mesh_of_the_axisymmetric_assembly_agrees_within_the_documented_tolerance(tmp_path):
    """The earlier 3-D default mesh (0.03 m graded 0.25 to the edges, P2, ~480k dofs: AMG + CG)
    read as a user's mesh agrees with the axisymmetric hinge within 1.5 % on every term
    (docs/validation.md §14: measured +0.63, +0.48, +1.23, -0.97, -0.91 %)."""
    axi, _ = hinge(FEConfig(), tmp_path)
    mesh, solved = hinge(dataclasses.replace(axisymmetric_assembly_as_mesh(tmp_path, 0.03, 0.25),
                                             linear_solver="auto"), tmp_path)
    assert solved.mesh_stats["linear_solver"] == "amg"
    a, m = np.r_[np.diag(axi.H_u), axi.H_psi], np.r_[np.diag(mesh.H_u), mesh.H_psi]
    assert np.all(np.abs(m / a - 1.0) < 0.015), m / a - 1.0
