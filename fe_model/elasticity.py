"""Static linear elasticity on tetrahedra, multi-material, P1 or P2 displacements.

Assembly uses skfem for the shape-function gradients (its scalar `Basis`) and a numba
kernel for the element matrices; only the upper triangle is formed because the matrix
is symmetric positive definite and MKL PARDISO (mtype 2) reads the upper triangle.
Global dof numbering is skfem's `ElementVector` one: 3 * scalar dof + component.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from .kernels import csr_from_triplets, element_stiffness_upper, upper_triplet_indices


def lame_fields(mesh, materials: dict[str, tuple[float, float]], what: str) -> tuple[np.ndarray, np.ndarray]:
    """Lamé parameters (lambda, mu) [Pa] per element from `materials` (subdomain name ->
    (E [Pa], nu [-])); every element needs one. `what` names a subdomain in messages."""
    lam = np.full(mesh.nelements, np.nan)
    mu = np.full(mesh.nelements, np.nan)
    for name, (E, nu) in materials.items():
        if name not in mesh.subdomains:
            raise ValueError(f"no {what} {name!r} in the mesh (have {sorted(mesh.subdomains)})")
        lam[mesh.subdomains[name]], mu[mesh.subdomains[name]] = lame_parameters(E, nu)
    if np.isnan(lam).any():
        raise ValueError(f"{int(np.isnan(lam).sum())} elements have no material; {what}s given: {sorted(materials)}")
    return lam, mu


def lame_parameters(youngs_modulus: float, poisson_ratio: float) -> tuple[float, float]:
    """(lambda, mu) [Pa] from E [Pa] and nu [-]."""
    E, nu = youngs_modulus, poisson_ratio
    return E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)), E / (2.0 * (1.0 + nu))


def scalar_element(order: int, cell: str = "tet"):
    """Lagrange element of `order` on tetrahedra ("tet") or triangles ("tri", a meridian section)."""
    from skfem import ElementTetP1, ElementTetP2, ElementTriP1, ElementTriP2

    if order not in (1, 2):
        raise ValueError(f"element_order = {order!r}: allowed 1 (preview) or 2 (accurate)")
    p1, p2 = {"tet": (ElementTetP1, ElementTetP2), "tri": (ElementTriP1, ElementTriP2)}[cell]
    return p2() if order == 2 else p1()


@dataclass
class VectorFieldModel:
    """A meshed body with three displacement components per scalar node: skfem mesh, scalar
    basis, Lamé field per element [Pa]. Its vector dofs are 3 a + i (node a, component i:
    x, y, z in 3-D; U_r, U_theta, U_z of a Fourier mode on a meridian section)."""

    mesh: object
    basis: object
    lam: np.ndarray
    mu: np.ndarray

    @property
    def n_dofs(self) -> int:
        return 3 * self.basis.N

    def vector_dofs(self) -> np.ndarray:
        """(E, 3A) global vector dofs of each element, local order 3a + i."""
        scalar = self.basis.element_dofs.T.astype(np.int64)
        return (3 * scalar[:, :, None] + np.arange(3)).reshape(scalar.shape[0], -1)

    def boundary_dofs(self, group: str, components=(0, 1, 2)) -> np.ndarray:
        """Vector dofs of `components` on boundary group `group`."""
        if group not in self.mesh.boundaries:
            raise ValueError(f"no boundary group {group!r} in the mesh (have {sorted(self.mesh.boundaries)})")
        scalar = self.basis.get_dofs(self.mesh.boundaries[group]).all()
        return np.sort((3 * scalar[:, None] + np.asarray(components)).ravel())


class ElasticModel(VectorFieldModel):
    """A meshed 3-D body ready to assemble (tetrahedra, components x, y, z)."""

    @classmethod
    def build(cls, mesh, order: int, materials: dict[str, tuple[float, float]]) -> "ElasticModel":
        """`materials` maps a subdomain name to (E [Pa], nu [-]); every element needs one."""
        from skfem import Basis

        lam, mu = lame_fields(mesh, materials, "volume group")
        # gradients of P2 are linear on straight tets: the degree-2 rule integrates K exactly
        basis = Basis(mesh, scalar_element(order), intorder=2 * (order - 1))
        return cls(mesh, basis, lam, mu)

    def stiffness_upper(self, fixed: np.ndarray | None = None) -> tuple[sp.csr_matrix, np.ndarray]:
        """Upper triangle of K on the free dofs, and the free-dof index array.

        Fixed (clamped, zero-displacement) dofs are eliminated while assembling, which is
        cheaper than slicing a large matrix afterwards.
        """
        free_map = np.arange(self.n_dofs, dtype=np.int64)
        if fixed is not None and len(fixed):
            keep = np.ones(self.n_dofs, dtype=bool)
            keep[fixed] = False
            free_map = np.where(keep, np.cumsum(keep) - 1, -1)
        free = np.flatnonzero(free_map >= 0)
        grads = np.ascontiguousarray(
            np.stack([np.moveaxis(phi[0].grad, 0, -1) for phi in self.basis.basis], axis=2)
        )
        values = element_stiffness_upper(grads, np.ascontiguousarray(self.basis.dx), self.lam, self.mu)
        del grads
        rows, cols = upper_triplet_indices(np.ascontiguousarray(free_map[self.vector_dofs()]))
        indptr, indices, data = csr_from_triplets(rows, cols, values.ravel(), free.size)
        K = sp.csr_matrix((data, indices, indptr), shape=(free.size, free.size))
        K.has_canonical_format = True  # sorted, no duplicates (csr_from_triplets)
        return K, free


def full_from_upper(K_upper: sp.csr_matrix) -> sp.csr_matrix:
    """Symmetric matrix from its upper triangle."""
    return (K_upper + sp.triu(K_upper, k=1).T).tocsr()
