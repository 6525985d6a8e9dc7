"""RBE3-like load distribution and least-squares rigid-body fit over a region (docs/model.md §3).

Both are linear maps built from the same integrals of the shape functions phi_n over
a region (a volume or a set of facets) with r = x - c about the ring centre c:
m0[n] = int phi_n, m1[n] = int r phi_n, plus the region's measure, first and second
moments. Both are continuous (area/volume weighted) rather than per-node, so they do
not depend on how densely the mesh happens to place nodes.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

# Levi-Civita symbol: (a x b)_i = eps[i, j, k] a_j b_k
EPS = np.zeros((3, 3, 3))
EPS[0, 1, 2] = EPS[1, 2, 0] = EPS[2, 0, 1] = 1.0
EPS[0, 2, 1] = EPS[2, 1, 0] = EPS[1, 0, 2] = -1.0


@dataclass(frozen=True)
class RegionMoments:
    """Shape-function and geometric moments of a region about `centre` [SI]."""

    centre: np.ndarray  # (3,) m
    m0: np.ndarray  # (N,) int phi_n [m^k]
    m1: np.ndarray  # (N, 3) int r phi_n [m^(k+1)]
    measure: float  # int 1 [m^k], k = 2 (surface) or 3 (volume)
    first: np.ndarray  # (3,) int r
    second: np.ndarray  # (3, 3) int r r^T

    @classmethod
    def of(cls, basis, centre=(0.0, 0.0, 0.0)) -> "RegionMoments":
        """From a scalar skfem basis restricted to the region (Basis(elements=...) or
        FacetBasis(facets=...)); its quadrature must integrate degree order + 2."""
        from skfem import Functional, LinearForm

        c = np.asarray(centre, dtype=float)
        m0 = LinearForm(lambda v, w: v).assemble(basis)
        m1 = np.column_stack(
            [LinearForm(lambda v, w, i=i: (w.x[i] - c[i]) * v).assemble(basis) for i in range(3)]
        )
        measure = Functional(lambda w: 1.0 + 0.0 * w.x[0]).assemble(basis)
        first = np.array([Functional(lambda w, i=i: w.x[i] - c[i]).assemble(basis) for i in range(3)])
        second = np.array(
            [[Functional(lambda w, i=i, j=j: (w.x[i] - c[i]) * (w.x[j] - c[j])).assemble(basis)
              for j in range(3)] for i in range(3)]
        )
        return cls(c, m0, m1, float(measure), first, second)


def distributed_load_matrix(region: RegionMoments) -> np.ndarray:
    """(3N, 6) nodal loads of the traction field carrying a unit resultant [F; M].

    Column k is for the k-th unit generalised load (F_x, F_y, F_z, M_x, M_y, M_z) applied
    at the centre c. The traction t(x) = F/A + a x (x - x_bar) (RBE3 with area weights)
    has resultant F and, with a = J^-1 (M - d x F), moment M about c, where
    d = x_bar - c and J = int (|r'|^2 I - r' r'^T), r' = x - x_bar (docs/model.md §3).
    The consistent nodal load is f_n = int t phi_n.
    """
    A = region.measure
    d = region.first / A
    second_bar = region.second - A * np.outer(d, d)
    J = np.trace(second_bar) * np.eye(3) - second_bar
    m1_bar = region.m1 - np.outer(region.m0, d)  # int (x - x_bar) phi_n
    out = np.zeros((region.m0.size, 3, 6))
    for k in range(6):
        F = np.eye(3)[k] if k < 3 else np.zeros(3)
        M = np.eye(3)[k - 3] if k >= 3 else np.zeros(3)
        a = np.linalg.solve(J, M - np.cross(d, F))
        out[:, :, k] = np.outer(region.m0, F / A) + np.cross(a, m1_bar)
    return out.reshape(-1, 6)


def rigid_fit_operator(region: RegionMoments) -> np.ndarray:
    """(6, 3N) matrix L with [t; theta] = L u: the least-squares rigid motion of a region.

    Minimises int |u - t - theta x r|^2 over the region (the "average mean displacement
    element" of docs/model.md §3): t is the mean translation at the centre c, theta the mean
    (small) rotation. Normal equations G q = B^T u with G the Gram matrix of the six
    rigid modes and B^T u = [int u; int r x u].
    """
    A, R1, S = region.measure, region.first, region.second
    G = np.zeros((6, 6))
    G[:3, :3] = A * np.eye(3)
    G[:3, 3:] = np.einsum("cjb,b->cj", EPS, R1)  # int (e_j x r)_c
    G[3:, :3] = G[:3, 3:].T
    G[3:, 3:] = np.trace(S) * np.eye(3) - S
    Bt = np.zeros((6, region.m0.size, 3))
    for c in range(3):
        Bt[c, :, c] = region.m0
    Bt[3:] = np.einsum("jkl,nk->jnl", EPS, region.m1)  # (r x u)_j = eps_jkl r_k u_l
    return np.linalg.solve(G, Bt.reshape(6, -1))
