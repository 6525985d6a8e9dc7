"""Elasticity assembly: numba kernels against skfem's own assembly (their slow twin)."""

import numpy as np
import pytest
import scipy.sparse as sp
from skfem import Basis, BilinearForm, ElementVector, MeshTet, asm
from skfem.helpers import ddot, eye, sym_grad, trace

from bearingsim.fe_model.elasticity import ElasticModel, full_from_upper, lame_parameters, scalar_element
from bearingsim.fe_model.kernels import csr_from_triplets


def _cube_mesh(n: int = 3) -> MeshTet:
    x = np.linspace(0.0, 0.2, n + 1)
    mesh = MeshTet.init_tensor(x, 0.5 * x, x).with_subdomains(
        {"hard": lambda c: c[0] < 0.1, "soft": lambda c: c[0] >= 0.1}
    )
    return mesh


@pytest.mark.parametrize("order", [1, 2])
def test_stiffness_matches_skfem_linear_elasticity_with_random_lame_fields(order):
    rng = np.random.default_rng(order)
    mesh = _cube_mesh()
    model = ElasticModel.build(mesh, order, {"hard": (200e9, 0.3), "soft": (70e9, 0.33)})
    model.lam = rng.uniform(1e10, 1e11, mesh.nelements)  # random per-element fields
    model.mu = rng.uniform(1e10, 1e11, mesh.nelements)
    K_upper, free = model.stiffness_upper()
    vector_basis = Basis(mesh, ElementVector(scalar_element(order)), intorder=2)

    @BilinearForm
    def elasticity(u, v, w):
        strain = sym_grad(u)
        stress = 2.0 * w.mu * strain + w.lam * eye(trace(strain), 3)
        return ddot(stress, sym_grad(v))

    nq = vector_basis.X.shape[1]
    K_ref = asm(elasticity, vector_basis, lam=np.repeat(model.lam[:, None], nq, 1),
                mu=np.repeat(model.mu[:, None], nq, 1))
    K = full_from_upper(K_upper)
    assert free.size == model.n_dofs == K_ref.shape[0]
    assert abs(K - K_ref).max() <= 1e-13 * abs(K_ref).max()


def test_rigid_body_motions_are_stress_free():
    """Invariant: K annihilates the six rigid modes (translations, small rotations)."""
    mesh = _cube_mesh()
    model = ElasticModel.build(mesh, 2, {"hard": (200e9, 0.3), "soft": (70e9, 0.33)})
    K = full_from_upper(model.stiffness_upper()[0])
    nodes = model.basis.doflocs.T  # (N, 3)
    for theta in np.eye(3):
        u = np.cross(theta, nodes).ravel()
        assert np.abs(K @ u).max() <= 1e-9 * abs(K).max() * np.abs(u).max()
    for t in np.eye(3):
        u = np.tile(t, nodes.shape[0])
        assert np.abs(K @ u).max() <= 1e-9 * abs(K).max()


def test_eliminated_dofs_equal_slicing_the_full_matrix():
    mesh = _cube_mesh()
    model = ElasticModel.build(mesh, 2, {"hard": (200e9, 0.3), "soft": (70e9, 0.33)})
    fixed = np.arange(0, model.n_dofs, 7)
    K_free, free = model.stiffness_upper(fixed)
    K_all, _ = model.stiffness_upper()
    sliced = sp.triu(full_from_upper(K_all)[free][:, free])
    assert abs(K_free - sliced).max() == 0.0


def test_csr_from_triplets_matches_scipy_on_random_triplets():
    rng = np.random.default_rng(7)
    n, m = 50, 4000
    rows = rng.integers(-1, n, m).astype(np.int32)  # -1 = eliminated, must be skipped
    cols = rng.integers(0, n, m).astype(np.int32)
    vals = rng.normal(size=m)
    indptr, indices, data = csr_from_triplets(rows, cols, vals, n)
    ours = sp.csr_matrix((data, indices, indptr), shape=(n, n))
    keep = rows >= 0
    ref = sp.coo_matrix((vals[keep], (rows[keep], cols[keep])), shape=(n, n)).tocsr()
    assert abs(ours - ref).max() < 1e-12
    for r in range(n):  # canonical: sorted and unique within each row
        row = indices[indptr[r]:indptr[r + 1]]
        assert np.all(np.diff(row) > 0)
    py = csr_from_triplets.py_func(rows, cols, vals, n)
    assert all(np.allclose(a, b) for a, b in zip(py, (indptr, indices, data)))


def test_lame_parameters_textbook_values():
    # steel E = 200 GPa, nu = 0.3: lambda = E nu/((1+nu)(1-2nu)) = 115.38 GPa, mu = 76.92 GPa
    # (definitions: Timoshenko & Goodier, Theory of Elasticity, 3rd ed., §6)
    lam, mu = lame_parameters(200e9, 0.3)
    assert lam == pytest.approx(115.3846e9, rel=1e-5)
    assert mu == pytest.approx(76.9231e9, rel=1e-5)


def test_material_missing_for_some_elements_is_an_error():
    with pytest.raises(ValueError, match="no material"):
        ElasticModel.build(_cube_mesh(), 1, {"hard": (200e9, 0.3)})
