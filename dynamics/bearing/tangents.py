"""Assembly of approximate tangents in block-arrow form (docs/model.md §9).

Every contact term has the same shape: a generalised force T (k components) acting through
maps G_A (k x 6) on the ball and G_B (k x 6) on a border body, and depending on the
relative motion s = G_A W_A - G_B W_B, where W are the bodies' generalised velocities (or
position increments). With J = -dT/ds the residual tangents are

    ball-ball  G_A^T J G_A      ball-border  -G_A^T J G_B
    border-ball -G_B^T J G_A    border-border G_B^T J G_B

Body maps: a ball's W = (v, omega) (spatial); a border body's W = (v, Omega) with Omega
material, so its rotation columns are multiplied by its rotation matrix R.
"""

from __future__ import annotations

import numba
import numpy as np

from .._speed.compile_policy import KERNEL


@numba.njit(**KERNEL)
def point_map(r, R, out):
    """out (3x6) = [I, -r~ R]: velocity of the material point at offset r [m] of a body
    with material angular velocity (R = I for spatial)."""
    out[:, :3] = 0.0
    for i in range(3):
        out[i, i] = 1.0
    # -r~ R, row by row: -r~ = [[0, r2, -r1], [-r2, 0, r0], [r1, -r0, 0]]
    for j in range(3):
        out[0, 3 + j] = r[2] * R[1, j] - r[1] * R[2, j]
        out[1, 3 + j] = r[0] * R[2, j] - r[2] * R[0, j]
        out[2, 3 + j] = r[1] * R[0, j] - r[0] * R[1, j]


@numba.njit(**KERNEL)
def slip_map(ex, ey, n, r, R, out):
    """out (3x6): rows d(du0, dv0, w_s)/dW of a body at contact offset r: e_x^T [I, -r~R],
    e_y^T [I, -r~R], [0, n^T R]."""
    pm = np.empty((3, 6))
    point_map(r, R, pm)
    for j in range(6):
        out[0, j] = ex[0] * pm[0, j] + ex[1] * pm[1, j] + ex[2] * pm[2, j]
        out[1, j] = ey[0] * pm[0, j] + ey[1] * pm[1, j] + ey[2] * pm[2, j]
        out[2, j] = 0.0
    for j in range(3):
        out[2, 3 + j] = n[0] * R[0, j] + n[1] * R[1, j] + n[2] * R[2, j]


@numba.njit(**KERNEL)
def add_congruent(out, A, J, B, sign):
    """out += sign A^T J B for small dense A (k x na), J (k x k), B (k x nb), out (na x nb).

    Loops without allocation: as numba's `@` each product of these 3 x 6 maps is a BLAS call
    with a fresh result, and a tangent evaluation of the reference bearing makes ~700 of them
    (`python -m benchmarks.contacts`)."""
    k, na = A.shape
    nb = B.shape[1]
    for j in range(nb):
        for p in range(k):
            t = 0.0
            for q in range(k):
                t += J[p, q] * B[q, j]
            t *= sign
            for i in range(na):
                out[i, j] += A[p, i] * t


@numba.njit(**KERNEL)
def add_pair(k, off, J, GA, GB, M):
    """Add the four blocks above to the block-arrow matrix M (`linear_solvers.Blocks`) for
    ball k and the border body at border offset `off` (off < 0: the other body is fixed,
    only the ball block is added)."""
    add_congruent(M.D[k], GA, J, GA, 1.0)
    if off < 0:
        return
    nb = GB.shape[1]
    add_congruent(M.E[k, :, off:off + nb], GA, J, GB, -1.0)
    add_congruent(M.F[k, off:off + nb, :], GB, J, GA, -1.0)
    add_congruent(M.B[off:off + nb, off:off + nb], GB, J, GB, 1.0)
