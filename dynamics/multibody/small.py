"""Small dense products (3x3, 2x3, 6x6) written as loops for the numba kernels.

numba compiles `A @ B` on float64 matrices to a BLAS call, whose call overhead (and a copy
when an operand is a transposed view) costs a 3x3 product several times what these loops
take, the result's allocation included. Any layout of the operands works.
"""

from __future__ import annotations

import numba
import numpy as np

from .._speed.compile_policy import KERNEL


@numba.njit(**KERNEL)
def mm(A, B):
    """A B for small matrices (n x k) (k x m)."""
    n, k = A.shape
    m = B.shape[1]
    C = np.zeros((n, m))
    for i in range(n):
        for l in range(k):
            a = A[i, l]
            for j in range(m):
                C[i, j] += a * B[l, j]
    return C


@numba.njit(**KERNEL)
def mv(A, x):
    """A x for a small matrix A (n x k) and vector x (k)."""
    y = np.zeros(A.shape[0])
    mv_into(A, x, y)
    return y


@numba.njit(**KERNEL)
def mv_into(A, x, y):
    """y = A x written into y (no allocation)."""
    n, k = A.shape
    for i in range(n):
        s = 0.0
        for l in range(k):
            s += A[i, l] * x[l]
        y[i] = s


@numba.njit(**KERNEL)
def mtv(A, x):
    """A^T x for a small matrix A (n x k) and vector x (n)."""
    y = np.zeros(A.shape[1])
    mtv_into(A, x, y)
    return y


@numba.njit(**KERNEL)
def mtv_into(A, x, y):
    """y = A^T x written into y (no allocation)."""
    n, k = A.shape
    for i in range(k):
        y[i] = 0.0
    for l in range(n):
        xl = x[l]
        for i in range(k):
            y[i] += A[l, i] * xl


@numba.njit(cache=True, inline="always")
def mtv3(A, x0, x1, x2):
    """A^T x as three scalars for a 3x3 A and x = (x0, x1, x2): no array, for kernels that the
    residual of every Newton iteration calls."""
    return (A[0, 0] * x0 + A[1, 0] * x1 + A[2, 0] * x2,
            A[0, 1] * x0 + A[1, 1] * x1 + A[2, 1] * x2,
            A[0, 2] * x0 + A[1, 2] * x1 + A[2, 2] * x2)


@numba.njit(**KERNEL)
def outer(a, b):
    """a b^T for small vectors a (n) and b (m): numba's `np.outer` is a library function of its
    own for every caller, compiled on a machine's first run (docs/performance.md)."""
    C = np.empty((a.shape[0], b.shape[0]))
    for i in range(a.shape[0]):
        for j in range(b.shape[0]):
            C[i, j] = a[i] * b[j]
    return C


@numba.njit(**KERNEL)
def add_into(M, A):
    """M += A elementwise for small matrices of one shape (M may be a view). As loops: numba's
    array-to-array slice assignment (`M[a:b, c:d] += A`) compiles a shape-mismatch error path with
    string formatting in every kernel that uses it, seconds of a machine's first run."""
    for i in range(A.shape[0]):
        for j in range(A.shape[1]):
            M[i, j] += A[i, j]


@numba.njit(**KERNEL)
def copy_into(M, A):
    """M = A elementwise for small matrices of one shape (M may be a view), for the reason of
    `add_into`."""
    for i in range(A.shape[0]):
        for j in range(A.shape[1]):
            M[i, j] = A[i, j]


@numba.njit(**KERNEL)
def eye3():
    """The 3x3 identity, without `np.eye`'s own library (see `outer`)."""
    I = np.zeros((3, 3))
    for i in range(3):
        I[i, i] = 1.0
    return I
