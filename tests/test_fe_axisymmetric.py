"""Axisymmetric model (Fourier modes 0 and 1 on the meridian section) against exact
properties, closed forms and the independent 3-D solver.

References: Lamé's thick-walled cylinder with free ends (Timoshenko & Goodier, Theory of
Elasticity, 3rd ed., §28); Timoshenko beam deflection P L^3/(3EI) + P L/(kappa G A) and
rotation P L^2/(2EI) with Cowper's shear coefficient of a hollow circle (J. Appl. Mech.
33:335, 1966, Table 1).
"""

import dataclasses
import math

import numpy as np
import pytest

from bearingsim.fe_model import FEConfig, RingSeat, fit_hinge
from bearingsim.fe_model.axisymmetric import (AxisymmetricRegion, HarmonicModel, mode0_load, mode1_load,
                                              rigid_fit_rows, unit_responses)
from bearingsim.fe_model.elasticity import full_from_upper
from bearingsim.fe_model.identify import solve_perturbations
from bearingsim.fe_model.verification import LameTube, TubeCantilever
from bearingsim.meshes.section import mesh_rectangles

R0, R1, Z0, Z1 = 0.04, 0.06, -0.03, 0.05  # m: a tube section off the axis, not centred in z
MATERIAL = {"tube": (200e9, 0.3)}


def _tube(r0=R0, order=2, size=0.01):
    lines = {"bore": lambda k: k[0] == "r" and math.isclose(k[1], r0, abs_tol=1e-6),
             "top": lambda k: k[0] == "z" and math.isclose(k[1], Z1, abs_tol=1e-6)}
    mesh = mesh_rectangles({"tube": [(r0, R1, Z0, Z1)]}, lines, size, size, 1.0, 1e-6).to_skfem()
    return HarmonicModel.build(mesh, order, MATERIAL)


def _rigid(model, kind: str) -> np.ndarray:
    """Section field of a rigid motion: 'tz' (mode 0), 'tx' and 'ry' (mode 1)."""
    r, z = model.basis.doflocs
    U = np.zeros((model.basis.N, 3))
    if kind == "tz":
        U[:, 2] = 1.0
    elif kind == "tx":
        U[:, 0], U[:, 1] = 1.0, -1.0
    else:  # rotation about +y: u = (z, 0, -x)
        U[:, 0], U[:, 1], U[:, 2] = z, -z, -r
    return U.ravel()


@pytest.mark.parametrize("order", [1, 2])
def test_rigid_motions_are_strain_free_in_their_mode(order):
    model = _tube(order=order)
    for mode, kinds in ((0, ("tz",)), (1, ("tx", "ry"))):
        K, reduction = model.stiffness_upper(mode, np.empty(0, dtype=np.int64))
        K = full_from_upper(K)
        scale = abs(K).max()
        for kind in kinds:
            x = reduction.restrict(_rigid(model, kind))
            assert np.abs(K @ x).max() < 1e-10 * scale, (mode, kind)


def test_load_resultants_and_rigid_fit_are_exact():
    """M.43 loads carry the requested force and moment (their work on a unit rigid motion);
    M.44 recovers a rigid motion exactly; both on a surface and on a volume region."""
    from skfem import Basis, FacetBasis

    model = _tube()
    mesh, e = model.mesh, model.basis.elem
    for basis in (FacetBasis(mesh, e, facets=mesh.boundaries["bore"], intorder=5),
                  FacetBasis(mesh, e, facets=mesh.boundaries["top"], intorder=5),
                  Basis(mesh, e, intorder=5)):
        region = AxisymmetricRegion.of(basis)
        f1, f0 = mode1_load(region, 3.0, -2.0), mode0_load(region, 5.0)
        # virtual work round the axis: the load vectors already carry the angular integral
        assert f1 @ _rigid(model, "tx") == pytest.approx(3.0, rel=1e-12)
        assert f1 @ _rigid(model, "ry") == pytest.approx(-2.0, rel=1e-12)
        assert f0 @ _rigid(model, "tz") == pytest.approx(5.0, rel=1e-12)
        L1, L0 = rigid_fit_rows(region)
        np.testing.assert_allclose(L1 @ _rigid(model, "tx"), [1, 0, 0, 0, 0, 0], atol=1e-12)
        np.testing.assert_allclose(L1 @ _rigid(model, "ry"), [0, 0, 0, 0, 1, 0], atol=1e-12)
        np.testing.assert_allclose(L0 @ _rigid(model, "tz"), [0, 0, 1, 0, 0, 0], atol=1e-12)


def test_region_measures_are_those_of_the_body_of_revolution():
    from skfem import Basis, FacetBasis

    model = _tube()
    vol = AxisymmetricRegion.of(Basis(model.mesh, model.basis.elem, intorder=5))
    bore = AxisymmetricRegion.of(FacetBasis(model.mesh, model.basis.elem, facets=model.mesh.boundaries["bore"],
                                            intorder=5))
    L = Z1 - Z0
    assert vol.measure == pytest.approx(math.pi * (R1**2 - R0**2) * L, rel=1e-12)
    assert vol.first_z == pytest.approx(math.pi * (R1**2 - R0**2) * 0.5 * (Z1**2 - Z0**2), rel=1e-12)
    assert vol.second_xx == pytest.approx(0.25 * math.pi * (R1**4 - R0**4) * L, rel=1e-12)
    assert bore.measure == pytest.approx(2 * math.pi * R0 * L, rel=1e-12)
    assert bore.second_zz == pytest.approx(2 * math.pi * R0 * (Z1**3 - Z0**3) / 3, rel=1e-12)


def test_unit_responses_turn_x_into_y():
    mode1 = np.array([[1.0, 0.2], [0, 0], [0, 0], [0, 0], [0.3, 4.0], [0, 0]])
    mode0 = np.array([0, 0, 2.0, 0, 0, 0])
    R = unit_responses(mode1, mode0)  # columns F_x, F_y, F_z, M_x, M_y
    np.testing.assert_array_equal(R[:, 1], [0, 1.0, 0, -0.3, 0, 0])  # F_y: u_y, theta_x = -theta_y(F_x)
    np.testing.assert_array_equal(R[:, 3], [0, -0.2, 0, 4.0, 0, 0])  # M_x: theta_x = theta_y(M_y)
    np.testing.assert_array_equal(R[:, 2], mode0)


def test_lame_tube_mode_0_matches_the_closed_form():
    tube = LameTube()
    u_bore, u_out, _ = tube.solve_axisymmetric(0.01, 2)
    assert u_bore == pytest.approx(tube.radial_displacement(tube.inner_radius), rel=1e-4)
    assert u_out == pytest.approx(tube.radial_displacement(tube.outer_radius), rel=1e-4)


def test_tube_cantilever_mode_1_matches_timoshenko():
    """L/D = 10. Converged at -0.34 % (deflection) and -0.24 % (rotation): the clamped root
    is stiffer than beam theory's (as for the box cantilever of test_fe_verification)."""
    beam = TubeCantilever()
    w, phi, _ = beam.solve(0.01, 2)
    w_ref, phi_ref = beam.timoshenko()
    assert w == pytest.approx(w_ref, rel=0.006)
    assert phi == pytest.approx(phi_ref, rel=0.006)
    assert w < w_ref and phi < phi_ref


def test_revolved_3d_model_converges_to_the_axisymmetric_one(tmp_path):
    """The 3-D solver (its own loads, fit and assembly) on tetrahedra swept from the same
    section: its error against the axisymmetric hinge shrinks like 1/sectors^2 (faceting)."""
    import bearingsim.fe_model.identify as identify
    from bearingsim.meshes.housing import build_section_mesh
    from bearingsim.meshes.section import revolve_to_tets

    config = dataclasses.replace(FEConfig(), mesh_size=0.03, edge_refinement=1.0)
    ring = RingSeat()
    section = build_section_mesh(config.housing_geometry(ring), config.mesh_size, 1.0)
    axi = solve_perturbations(config, ring, tmp_path, lambda s, f: None)
    h_axi = fit_hinge(axi.loads, axi.responses, axi.groups)
    errors = []
    for sectors in (12, 24):
        tets = revolve_to_tets(section, sectors)
        original = identify.cached_housing_mesh
        identify.cached_housing_mesh = lambda *a, **k: (tets, tmp_path / "revolved.npz", False)
        try:
            solved = solve_perturbations(config, ring, tmp_path, lambda s, f: None, model="3d")
        finally:
            identify.cached_housing_mesh = original
        fit = fit_hinge(solved.loads, solved.responses, solved.groups)
        errors.append(np.r_[np.diag(fit.H_u) / np.diag(h_axi.H_u), fit.H_psi / h_axi.H_psi] - 1.0)
    coarse, fine = np.abs(errors[0]), np.abs(errors[1])
    assert np.all(fine < 0.02)
    assert np.all(fine < 0.5 * coarse)


def test_solid_shaft_ties_the_axis_and_stiffens_the_hinge(tmp_path):
    config = dataclasses.replace(FEConfig(), mesh_size=0.02, edge_refinement=0.1)
    hollow = solve_perturbations(config, RingSeat(), tmp_path, lambda s, f: None)
    solid = solve_perturbations(dataclasses.replace(config, shaft_inner_diameter=0.0), RingSeat(), tmp_path,
                                lambda s, f: None)
    h, s = (fit_hinge(x.loads, x.responses, x.groups) for x in (hollow, solid))
    assert np.all(np.linalg.eigvalsh(s.H_u) > 0) and np.all(s.H_psi > 0)
    assert np.all(np.diag(s.H_u) > np.diag(h.H_u)) and np.all(s.H_psi > h.H_psi)
    assert s.H_u[0, 0] < 1.2 * h.H_u[0, 0]  # the supports, not the shaft, set the radial stiffness


def test_solid_section_keeps_rigid_motions_strain_free():
    model = _tube(r0=0.0)
    assert model.axis_nodes().size > 0
    K, reduction = model.stiffness_upper(1, np.empty(0, dtype=np.int64))
    K = full_from_upper(K)
    for kind in ("tx", "ry"):
        x = _rigid(model, kind)
        x_reduced = np.linalg.lstsq(reduction.T.toarray(), x, rcond=None)[0]
        np.testing.assert_allclose(reduction.expand(x_reduced), x, atol=1e-12)  # satisfies the axis ties
        assert np.abs(K @ x_reduced).max() < 1e-10 * abs(K).max()
