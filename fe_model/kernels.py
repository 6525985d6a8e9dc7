"""Numba kernels of the elasticity assembly (pure functions of arrays, SI units)."""

from __future__ import annotations

import numba
import numpy as np


@numba.njit(cache=True)
def element_stiffness_upper(grads, dx, lam, mu):
    """Upper triangles of the element stiffness matrices of isotropic linear elasticity.

    K_e[3a+i, 3b+j] = sum_q dx_q (lam g_ai g_bj + mu g_aj g_bi + mu (g_a . g_b) delta_ij),
    the weak form a(u, v) = int lam div u div v + 2 mu eps(u):eps(v) dV (docs/model.md §3
    stage 1, static linear elasticity), with g_a the gradient of scalar shape function a.

    grads: (E, Q, A, 3) shape-function gradients [1/m] at the quadrature points;
    dx: (E, Q) quadrature weights times |det J| [m^3]; lam, mu: (E,) Lamé parameters [Pa].
    Returns (E, n(n+1)/2) [N/m], n = 3A, entries (p, q) with p <= q in row-major order;
    local dof p = 3a + i (node-interleaved components, as skfem's ElementVector).
    """
    n_el, n_q, n_a, _ = grads.shape
    n = 3 * n_a
    out = np.zeros((n_el, n * (n + 1) // 2))
    block = np.empty((n, n))
    for e in range(n_el):
        block[:, :] = 0.0
        for q in range(n_q):
            w = dx[e, q]
            wl = w * lam[e]
            wm = w * mu[e]
            for a in range(n_a):
                ga0, ga1, ga2 = grads[e, q, a, 0], grads[e, q, a, 1], grads[e, q, a, 2]
                for b in range(a, n_a):
                    gb0, gb1, gb2 = grads[e, q, b, 0], grads[e, q, b, 1], grads[e, q, b, 2]
                    dot = wm * (ga0 * gb0 + ga1 * gb1 + ga2 * gb2)
                    ga = (ga0, ga1, ga2)
                    gb = (gb0, gb1, gb2)
                    for i in range(3):
                        for j in range(3):
                            v = wl * ga[i] * gb[j] + wm * ga[j] * gb[i]
                            if i == j:
                                v += dot
                            block[3 * a + i, 3 * b + j] += v
        k = 0
        for p in range(n):
            for r in range(p, n):
                out[e, k] = block[p, r]  # r >= p: node of r >= node of p, block formed
                k += 1
    return out


@numba.njit(cache=True)
def harmonic_stiffness_upper(phi, grads, r, dx, lam, mu, n, c_cos, c_sin):
    """Upper triangles of the element matrices of one Fourier mode of an axisymmetric body.

    The displacement u_r = U_r cos n theta, u_theta = U_theta sin n theta, u_z = U_z cos n
    theta has the engineering strains (docs/model.md §3, Zienkiewicz & Taylor, The Finite
    Element Method, vol. 1, 6th ed., §9.4)
        eps_rr = U_r,r c,  eps_tt = (U_r + n U_t)/r c,  eps_zz = U_z,z c,
        g_rz = (U_r,z + U_z,r) c,  g_rt = (U_t,r - (n U_r + U_t)/r) s,  g_tz = (U_t,z - n U_z/r) s,
    c = cos n theta, s = sin n theta; integrating lam tr(eps)^2 + 2 mu eps:eps round the axis
    gives the weight c_cos to the terms in c^2 and c_sin to those in s^2 (pi and pi for
    n >= 1; 2 pi and 0 for n = 0, where U_theta is torsion and decouples).

    phi: (E, Q, A) scalar shape functions, grads: (E, Q, A, 2) their (r, z) gradients [1/m],
    r: (E, Q) radius of the quadrature points [m], dx: (E, Q) weights times |det J| [m^2],
    lam, mu: (E,) [Pa]. Returns (E, n(n+1)/2) [N/m], n = 3A, local dof 3a + (0: U_r, 1: U_theta,
    2: U_z), entries (p, q) with p <= q in row-major order, as element_stiffness_upper.
    """
    n_el, n_q, n_a = phi.shape
    m = 3 * n_a
    out = np.zeros((n_el, m * (m + 1) // 2))
    B = np.zeros((6, m))
    block = np.empty((m, m))
    for e in range(n_el):
        block[:, :] = 0.0
        for q in range(n_q):
            rq = r[e, q]
            for a in range(n_a):
                f = phi[e, q, a] / rq
                fr = grads[e, q, a, 0]
                fz = grads[e, q, a, 1]
                i = 3 * a
                B[0, i] = fr
                B[1, i] = f
                B[1, i + 1] = n * f
                B[2, i + 2] = fz
                B[3, i] = fz
                B[3, i + 2] = fr
                B[4, i] = -n * f
                B[4, i + 1] = fr - f
                B[5, i + 1] = fz
                B[5, i + 2] = -n * f
            w = dx[e, q] * rq
            wl = w * c_cos * lam[e]
            wm = w * c_cos * mu[e]
            ws = w * c_sin * mu[e]
            for p in range(m):
                tp = B[0, p] + B[1, p] + B[2, p]
                for s in range(p, m):
                    ts = B[0, s] + B[1, s] + B[2, s]
                    block[p, s] += (wl * tp * ts
                                    + 2.0 * wm * (B[0, p] * B[0, s] + B[1, p] * B[1, s] + B[2, p] * B[2, s])
                                    + wm * B[3, p] * B[3, s]
                                    + ws * (B[4, p] * B[4, s] + B[5, p] * B[5, s]))
        k = 0
        for p in range(m):
            for s in range(p, m):
                out[e, k] = block[p, s]
                k += 1
    return out


@numba.njit(cache=True)
def upper_triplet_indices(dofs):
    """Global (row, col) of every upper-triangle element entry, swapped so row <= col.

    dofs: (E, n) int64 global dof of each local dof (-1 = eliminated by a Dirichlet
    condition). Returns int32 rows, cols with -1 where either dof is eliminated.
    """
    n_el, n = dofs.shape
    m = n * (n + 1) // 2
    rows = np.empty(n_el * m, dtype=np.int32)
    cols = np.empty(n_el * m, dtype=np.int32)
    for e in range(n_el):
        k = e * m
        for p in range(n):
            dp = dofs[e, p]
            for r in range(p, n):
                dr = dofs[e, r]
                if dp < 0 or dr < 0:
                    rows[k] = -1
                    cols[k] = -1
                elif dp <= dr:
                    rows[k] = dp
                    cols[k] = dr
                else:
                    rows[k] = dr
                    cols[k] = dp
                k += 1
    return rows, cols


@numba.njit(cache=True)
def csr_from_triplets(rows, cols, values, n):
    """Sum (row, col, value) triplets into a canonical CSR matrix of shape (n, n).

    Entries with row < 0 are skipped (eliminated dofs). Counting sort by row, then a
    sort and merge of duplicates within each row: O(nnz) plus short per-row sorts,
    about three times faster than scipy's COO -> CSR for element matrices, and without
    the boolean-mask copies. Returns (indptr int64, indices int32, data float64).
    """
    counts = np.zeros(n + 1, dtype=np.int64)
    for k in range(rows.size):
        if rows[k] >= 0:
            counts[rows[k] + 1] += 1
    start = np.cumsum(counts)
    fill = start[:-1].copy()
    bucket_cols = np.empty(start[-1], dtype=np.int32)
    bucket_vals = np.empty(start[-1], dtype=np.float64)
    for k in range(rows.size):
        r = rows[k]
        if r >= 0:
            bucket_cols[fill[r]] = cols[k]
            bucket_vals[fill[r]] = values[k]
            fill[r] += 1
    indptr = np.zeros(n + 1, dtype=np.int64)
    out = 0
    for r in range(n):
        lo, hi = start[r], start[r + 1]
        row_cols = bucket_cols[lo:hi].copy()  # copies: the merged row is written in place
        row_vals = bucket_vals[lo:hi].copy()
        order = np.argsort(row_cols, kind="mergesort")
        last = -1
        for idx in order:
            c = row_cols[idx]
            if c == last:
                bucket_vals[out - 1] += row_vals[idx]
            else:
                bucket_cols[out] = c
                bucket_vals[out] = row_vals[idx]
                out += 1
                last = c
        indptr[r + 1] = out
    return indptr, bucket_cols[:out].copy(), bucket_vals[:out].copy()
