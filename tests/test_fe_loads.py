"""RBE3-like load distribution, rigid-body fit and von Mises output."""

import numpy as np
import pytest
from skfem import Basis, FacetBasis, MeshTet

from bearingsim.fe_model.artefacts import von_mises
from bearingsim.fe_model.elasticity import ElasticModel, scalar_element
from bearingsim.fe_model.loads import RegionMoments, distributed_load_matrix, rigid_fit_operator

CENTRE = np.array([0.3, 0.05, -0.02])


def _model(order=2):
    """A box mesh without gmsh, one material (lambda = 1e11, mu = 8e10 Pa)."""
    x = np.linspace(0.0, 0.2, 4)
    mesh = MeshTet.init_tensor(x, 0.5 * x, x)
    mesh = mesh.with_boundaries({"end": lambda c: np.isclose(c[0], 0.2)})
    basis = Basis(mesh, scalar_element(order), intorder=2)
    return ElasticModel(mesh, basis, np.full(mesh.nelements, 1e11), np.full(mesh.nelements, 8e10))


@pytest.mark.parametrize("order", [1, 2])
def test_distributed_load_has_the_applied_resultant_force_and_moment(order):
    model = _model(order)
    mesh = model.mesh
    facets = FacetBasis(mesh, model.basis.elem, facets=mesh.boundaries["end"], intorder=order + 2)
    P = distributed_load_matrix(RegionMoments.of(facets, CENTRE))
    nodes = model.basis.doflocs.T
    for k in range(6):
        f = P[:, k].reshape(-1, 3)
        resultant = np.r_[f.sum(axis=0), np.cross(nodes - CENTRE, f).sum(axis=0)]
        # shape functions reproduce x exactly, so nodal sums are the traction integrals
        np.testing.assert_allclose(resultant, np.eye(6)[k], atol=1e-10)


@pytest.mark.parametrize("region", ["volume", "facets"])
def test_rigid_fit_recovers_a_rigid_motion_exactly(region):
    model = _model(2)
    mesh = model.mesh
    if region == "volume":
        basis = Basis(mesh, model.basis.elem, elements=np.arange(0, mesh.nelements, 3), intorder=4)
    else:
        basis = FacetBasis(mesh, model.basis.elem, facets=mesh.boundaries["end"], intorder=4)
    L = rigid_fit_operator(RegionMoments.of(basis, CENTRE))
    rng = np.random.default_rng(3)
    t, theta = rng.normal(size=3) * 1e-5, rng.normal(size=3) * 1e-4
    nodes = model.basis.doflocs.T
    u = (t + np.cross(theta, nodes - CENTRE)).ravel()
    np.testing.assert_allclose(L @ u, np.r_[t, theta], rtol=1e-9, atol=1e-16)


def test_von_mises_of_uniaxial_strain_is_two_mu_eps():
    """u = eps0 x e_x: sigma_xx = (lam + 2 mu) eps0, sigma_yy = sigma_zz = lam eps0, so
    sigma_vm = |sigma_xx - sigma_yy| = 2 mu eps0 (von Mises definition, e.g. Timoshenko &
    Goodier §§ on yield criteria)."""
    model = _model(2)
    eps0 = 1e-4
    nodes = model.basis.doflocs.T
    u = np.column_stack([eps0 * nodes[:, 0], 0 * nodes[:, 0], 0 * nodes[:, 0]]).ravel()
    np.testing.assert_allclose(von_mises(model, u), 2.0 * 8e10 * eps0, rtol=1e-10)
