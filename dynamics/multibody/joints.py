"""Joints to ground, docs/model.md §4.

* Ideal hinge to ground with zero speed (the fixed outer race): eliminated — the body has no
  coordinates; models use its constant position and orientation directly. A spherical joint
  to ground (heavy top) is eliminated the same way: keep only the rotation triple and use
  the inertia about the pivot (`rigid_body.inertia_about_point`).
* Prescribed speed about a body's own axis (inner race, paper eq. 5–6): the non-holonomic
  constraint Phi_nh = Omega_i - Omega_target(t) = 0 with B_nh = e_i acts only on equation i,
  so the constraint force B_nh^T lambda only enters row i. Eliminating lambda is therefore
  exact: row i of the residual is *replaced* by the constraint,

      M_i. a = 0,   g_i = -p (v_i - Omega_target(t))

  so the HHT row reads (1 - alpha) p (v_{n+1,i} - Omega_{n+1}) + alpha p (v_{n,i} - Omega_n)
  = 0, which holds exactly at every step once it holds at the start (no penalty error: there
  is no other term in the row). Row i of the iteration matrix becomes c_v p e_i^T. The value
  of p only scales the row (any p > 0 gives the same solution). The drive moment that keeps
  the speed, lambda = (M a - g)_i of the original row, is returned for reporting.
  Give the row error weight 0 or any weight (its error is zero when the speed is constant).
"""

from __future__ import annotations

import numba

from .._speed.compile_policy import KERNEL

from .linear_solvers import BlockArrowMatrix


@numba.njit(**KERNEL)
def prescribe_velocity_residual(i, v, target, p, ma, g):
    """Replace row i of (M a, g) by the velocity constraint v_i = target [rad/s or m/s].

    Returns the drive force/moment (M a - g)_i of the replaced row [N or N m].
    """
    drive = ma[i] - g[i]
    ma[i] = 0.0
    g[i] = -p * (v[i] - target)
    return drive


@numba.njit(**KERNEL)
def prescribe_velocity_dense(S, i, c_m, c_v, p):
    """Row i of a dense iteration matrix for the replaced row: c_v p on the diagonal
    (c_m when c_v = 0, i.e. in the initial-acceleration solve, giving a_i = 0)."""
    S[i, :] = 0.0
    S[i, i] = c_v * p if c_v > 0.0 else c_m


@numba.njit(**KERNEL)
def prescribe_velocity_blocks(S, i, c_m, c_v, p):
    """Same as `prescribe_velocity_dense` for global index i of block-arrow `Blocks` S."""
    Z, m = S.E.shape[0], S.E.shape[1]
    diag = c_v * p if c_v > 0.0 else c_m
    if i >= Z * m:
        j = i - Z * m
        S.B[j, :] = 0.0
        S.F[:, j, :] = 0.0
        S.B[j, j] = diag
    else:
        k, j = divmod(i, m)
        S.D[k, j, :] = 0.0
        S.E[k, j, :] = 0.0
        S.D[k, j, j] = diag


def prescribe_velocity_block_arrow(S: BlockArrowMatrix, i: int, c_m: float, c_v: float,
                                   p: float) -> None:
    """`prescribe_velocity_blocks` on a `BlockArrowMatrix`."""
    prescribe_velocity_blocks(S.blocks(), i, c_m, c_v, p)
