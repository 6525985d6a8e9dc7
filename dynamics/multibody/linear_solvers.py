"""Linear solvers for the Newton iteration matrix S = c_m M + c_v C_t + c_q K_t (docs/model.md §9).

Two structures:

* dense: a (n, n) float64 array; `DenseSolver` (LU with partial pivoting, numba).
* block-arrow: `BlockArrowMatrix` for "many small bodies each coupled only to a few large
  ones". Unknowns are ordered [small body 0 (m), ..., small body Z-1 (m), border (nb)]:

      [ D_0            E_0     ] [x_0   ]   [b_0   ]
      [      ...       ...     ] [...   ] = [...   ]
      [           D_Z-1 E_Z-1  ] [x_Z-1 ]   [b_Z-1 ]
      [ F_0 ... F_Z-1   B      ] [x_b   ]   [b_b   ]

  D (Z, m, m) small diagonal blocks, E (Z, m, nb) small-row/border-column couplings,
  F (Z, nb, m) border-row/small-column couplings, B (nb, nb) border block. No symmetry is
  assumed (gyroscopic and friction tangents are not symmetric). `BlockArrowSolver` factors
  each D_k, forms the Schur complement S = B - sum_k F_k D_k^-1 E_k, factors it, and solves
  by forward elimination and back-substitution: O(Z m^2 (m + nb) + nb^3) work.

A solver's `factor(matrix)` returns False when a pivot is zero or not finite (the step is
then rejected); `solve(rhs, out)` writes the solution into `out`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

import numba
import numpy as np

from .._speed.compile_policy import KERNEL, NO_REFCOUNT, WITH_REFCOUNT

from .small import copy_into


@numba.njit(**KERNEL)
def lu_factor_inplace(A, piv):
    """LU factorisation with partial pivoting, in place (L unit lower, U upper).

    Returns False when a pivot is zero or not finite (singular or NaN matrix).
    """
    n = A.shape[0]
    for k in range(n):
        p = k
        big = abs(A[k, k])
        for i in range(k + 1, n):
            if abs(A[i, k]) > big:
                big = abs(A[i, k])
                p = i
        piv[k] = p
        if not (big > 0.0) or not np.isfinite(big):
            return False
        if p != k:
            for j in range(n):
                tmp = A[k, j]
                A[k, j] = A[p, j]
                A[p, j] = tmp
        inv = 1.0 / A[k, k]
        for i in range(k + 1, n):
            A[i, k] *= inv
            lik = A[i, k]
            if lik != 0.0:
                for j in range(k + 1, n):
                    A[i, j] -= lik * A[k, j]
    return True


@numba.njit(**NO_REFCOUNT)
def lu_solve_inplace(LU, piv, b):
    """Solve (LU) x = b in place in the vector b."""
    n = LU.shape[0]
    for k in range(n):
        p = piv[k]
        if p != k:
            tmp = b[k]
            b[k] = b[p]
            b[p] = tmp
    for i in range(n):
        for j in range(i):
            b[i] -= LU[i, j] * b[j]
    for i in range(n - 1, -1, -1):
        for j in range(i + 1, n):
            b[i] -= LU[i, j] * b[j]
        b[i] /= LU[i, i]


@numba.njit(**KERNEL)
def lu_solve_columns_inplace(LU, piv, B):
    """Solve (LU) X = B in place in the (n, k) matrix B."""
    n = LU.shape[0]
    k_cols = B.shape[1]
    for k in range(n):
        p = piv[k]
        if p != k:
            for c in range(k_cols):
                tmp = B[k, c]
                B[k, c] = B[p, c]
                B[p, c] = tmp
    for c in range(k_cols):
        for i in range(n):
            for j in range(i):
                B[i, c] -= LU[i, j] * B[j, c]
        for i in range(n - 1, -1, -1):
            for j in range(i + 1, n):
                B[i, c] -= LU[i, j] * B[j, c]
            B[i, c] /= LU[i, i]


@numba.njit(**WITH_REFCOUNT)
def block_arrow_factor(D, E, F, B, LU_D, piv_D, Dinv_T, F_T, DinvE_T, S, piv_S):
    """Factor a block-arrow matrix for `block_arrow_solve`: LU of each D_k (LU_D, piv_D: the
    factorisation's own workspace), the transposes of D_k^-1, F_k and D_k^-1 E_k (Dinv_T
    (Z, m, m), F_T (Z, m, nb), DinvE_T (Z, nb, m)), and the LU of the Schur complement
    S = B - sum_k F_k D_k^-1 E_k. Returns False if any pivot vanishes."""
    Z, m, nb = E.shape[0], E.shape[1], E.shape[2]
    copy_into(S, B)
    DinvE = np.empty((m, nb))
    for k in range(Z):
        copy_into(LU_D[k], D[k])
        if not lu_factor_inplace(LU_D[k], piv_D[k]):
            return False
        copy_into(DinvE, E[k])
        lu_solve_columns_inplace(LU_D[k], piv_D[k], DinvE)
        S -= F[k] @ DinvE
        inv = Dinv_T[k]
        inv[:, :] = 0.0
        for i in range(m):
            inv[i, i] = 1.0
        lu_solve_columns_inplace(LU_D[k], piv_D[k], inv)  # D_k^-1, transposed below
        for i in range(m):
            for j in range(i + 1, m):
                inv[i, j], inv[j, i] = inv[j, i], inv[i, j]
        for i in range(nb):
            for j in range(m):
                F_T[k, j, i] = F[k, i, j]
                DinvE_T[k, i, j] = DinvE[j, i]
    return lu_factor_inplace(S, piv_S)


RIGID_BODY_BLOCK = 6  # the unknowns of one rigid body (3 translations, 3 rotations)


@numba.njit(**NO_REFCOUNT)
def block_arrow_solve(Dinv_T, F_T, DinvE_T, S, piv_S, rhs, x):
    """Solve with a factored block-arrow matrix (`block_arrow_factor`); rhs and x are global
    vectors (Z m + nb), and must not be the same array.

    x_k = D_k^-1 b_k, x_b = S^-1 (b_b - sum_k F_k x_k), x_k -= (D_k^-1 E_k) x_b, each product
    as a sum of columns over the transposed blocks: the inner loops then run over a contiguous
    row with independent sums that vectorise, where dot products of 6 or 12 terms were chains
    of dependent additions (numba's `@` allocates and calls BLAS per block, which costs more
    still). Blocks of one rigid body (m = 6) take a copy of the loops compiled with m known,
    which LLVM unrolls without remainder loops: the same sums in the same order, so the same
    bits, in less time (benchmarks/block_arrow.py, docs/performance.md).
    """
    if Dinv_T.shape[1] == RIGID_BODY_BLOCK:
        _block_arrow_solve_m(Dinv_T, F_T, DinvE_T, S, piv_S, rhs, x, RIGID_BODY_BLOCK)
    else:
        _block_arrow_solve_m(Dinv_T, F_T, DinvE_T, S, piv_S, rhs, x, Dinv_T.shape[1])


@numba.njit(inline="always")
def _block_arrow_solve_m(Dinv_T, F_T, DinvE_T, S, piv_S, rhs, x, m):
    """`block_arrow_solve` with the block size m as an argument: inlined in numba's IR, a
    literal m becomes a constant of the compiled loops."""
    Z = Dinv_T.shape[0]
    nb = S.shape[0]
    n_small = Z * m
    xb = x[n_small:]
    for i in range(nb):
        xb[i] = rhs[n_small + i]
    for k in range(Z):
        xk = x[k * m:(k + 1) * m]
        for i in range(m):
            xk[i] = 0.0
        for j in range(m):
            r = rhs[k * m + j]
            for i in range(m):
                xk[i] += Dinv_T[k, j, i] * r
        for j in range(m):
            y = xk[j]
            for i in range(nb):
                xb[i] -= F_T[k, j, i] * y
    lu_solve_inplace(S, piv_S, xb)
    for k in range(Z):
        for j in range(nb):
            xbj = xb[j]
            for i in range(m):
                x[k * m + i] -= DinvE_T[k, j, i] * xbj


class Blocks(NamedTuple):
    """The four arrays of a block-arrow matrix as one kernel argument (`BlockArrowMatrix.blocks`)."""

    D: np.ndarray  # (Z, m, m)
    E: np.ndarray  # (Z, m, nb)
    F: np.ndarray  # (Z, nb, m)
    B: np.ndarray  # (nb, nb)


@dataclass
class BlockArrowMatrix:
    """Block-arrow matrix data (see module docstring); fill the arrays in place."""

    D: np.ndarray  # (Z, m, m)
    E: np.ndarray  # (Z, m, nb)
    F: np.ndarray  # (Z, nb, m)
    B: np.ndarray  # (nb, nb)

    @classmethod
    def zeros(cls, n_small: int, block: int, n_border: int) -> "BlockArrowMatrix":
        return cls(
            D=np.zeros((n_small, block, block)),
            E=np.zeros((n_small, block, n_border)),
            F=np.zeros((n_small, n_border, block)),
            B=np.zeros((n_border, n_border)),
        )

    def blocks(self) -> Blocks:
        """The arrays (views, not copies) as a bundle for numba kernels that fill them."""
        return Blocks(self.D, self.E, self.F, self.B)

    @property
    def shape(self) -> tuple[int, int]:
        n = self.D.shape[0] * self.D.shape[1] + self.B.shape[0]
        return n, n

    def fill_zero(self) -> None:
        self.D[...] = 0.0
        self.E[...] = 0.0
        self.F[...] = 0.0
        self.B[...] = 0.0

    def to_dense(self) -> np.ndarray:
        """Dense (n, n) copy, for tests and small models."""
        Z, m, nb = self.E.shape
        A = np.zeros(self.shape)
        for k in range(Z):
            s = slice(k * m, (k + 1) * m)
            A[s, s] = self.D[k]
            A[s, Z * m:] = self.E[k]
            A[Z * m:, s] = self.F[k]
        A[Z * m:, Z * m:] = self.B
        return A


class DenseSolver:
    """LU with partial pivoting of a dense (n, n) iteration matrix (numba kernels)."""

    def __init__(self) -> None:
        self._lu = np.zeros((0, 0))
        self._piv = np.zeros(0, dtype=np.int64)

    def factor(self, matrix: np.ndarray) -> bool:
        n = matrix.shape[0]
        if self._lu.shape != (n, n):
            self._lu = np.empty((n, n))
            self._piv = np.empty(n, dtype=np.int64)
        self._lu[...] = matrix
        return bool(lu_factor_inplace(self._lu, self._piv))

    def solve(self, rhs: np.ndarray, out: np.ndarray) -> None:
        out[:] = rhs
        lu_solve_inplace(self._lu, self._piv, out)


class BlockArrowSolver:
    """Schur-complement solver for a `BlockArrowMatrix` with Z blocks of size m, border nb."""

    def __init__(self, n_small: int, block: int, n_border: int) -> None:
        if n_small < 1 or block < 1 or n_border < 0:
            raise ValueError(
                f"block-arrow layout needs n_small >= 1, block >= 1, n_border >= 0; got "
                f"({n_small}, {block}, {n_border})"
            )
        Z, m, nb = n_small, block, n_border
        self._lu_D = np.zeros((Z, m, m))
        self._piv_D = np.zeros((Z, m), dtype=np.int64)
        self._Dinv_T = np.zeros((Z, m, m))
        self._F_T = np.zeros((Z, m, nb))
        self._DinvE_T = np.zeros((Z, nb, m))
        self._S = np.zeros((nb, nb))
        self._piv_S = np.zeros(nb, dtype=np.int64)

    def factor(self, matrix: BlockArrowMatrix) -> bool:
        if matrix.D.shape != self._lu_D.shape or matrix.B.shape != self._S.shape:
            raise ValueError(
                f"block-arrow matrix with D {matrix.D.shape}, B {matrix.B.shape} does not "
                f"match the solver layout D {self._lu_D.shape}, B {self._S.shape}"
            )
        # the factors keep their own F_k^T: the model may overwrite its buffers before solve
        return bool(block_arrow_factor(matrix.D, matrix.E, matrix.F, matrix.B, self._lu_D, self._piv_D,
                                       self._Dinv_T, self._F_T, self._DinvE_T, self._S, self._piv_S))

    def solve(self, rhs: np.ndarray, out: np.ndarray) -> None:
        if np.may_share_memory(rhs, out):
            raise ValueError("BlockArrowSolver.solve: rhs and out must be different arrays (out is written "
                             "before rhs is read through)")
        block_arrow_solve(self._Dinv_T, self._F_T, self._DinvE_T, self._S, self._piv_S, rhs, out)


@numba.njit(**KERNEL)
def assemble_iteration_blocks(K, C, mass, c_m, c_v, c_q, S):
    """S = c_m diag(mass) + c_v C + c_q K on block-arrow `Blocks` (mass: the diagonal of M,
    in the global order of the unknowns)."""
    Z, m, nb = K.E.shape
    for k in range(Z):
        for i in range(m):
            for j in range(m):
                S.D[k, i, j] = c_v * C.D[k, i, j] + c_q * K.D[k, i, j]
            S.D[k, i, i] += c_m * mass[k * m + i]
            for j in range(nb):
                S.E[k, i, j] = c_v * C.E[k, i, j] + c_q * K.E[k, i, j]
        for i in range(nb):
            for j in range(m):
                S.F[k, i, j] = c_v * C.F[k, i, j] + c_q * K.F[k, i, j]
    for i in range(nb):
        for j in range(nb):
            S.B[i, j] = c_v * C.B[i, j] + c_q * K.B[i, j]
        S.B[i, i] += c_m * mass[Z * m + i]
