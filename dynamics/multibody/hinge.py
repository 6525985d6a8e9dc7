"""Viscoelastic hinge joint between a fixed frame A and a body B, docs/model.md §5 (M.15–M.20).

Strains (M.15–M.16), with mu_i = R_A e_i the triad of A and xi_3 = R_B e_3 the axis of B:

    u = R_A^T (x_B - x_A),   psi = (-mu_2^T xi_3, mu_1^T xi_3) = -P xi_3,   P = [mu_2^T; -mu_1^T]
    u_dot = R_A^T x_B_dot,   psi_dot = P R_B (e_3 x Omega_B) = B_psi Omega_B,  B_psi = P R_B e_3~

(the same as M.16: (mu_2~ xi_3)^T omega = mu_2^T (xi_3 x omega)). Energy (M.17)
V = u^T H_u u / 2 + psi^T H_psi psi / 2; viscous forces from (M.18) with G = c_G H.
Generalised forces (M.19–M.20) in the integrator's coordinates (force on x_B, *material*
moment on B — the `T_B^T R_B^T` of M.19 maps the spatial moment onto CRV rates; with
material rotation increments it is just `R_B^T`):

    f   = -R_A (H_u u + G_u u_dot)                          [N]
    tau = -B_psi^T (H_psi psi + G_psi psi_dot)              [N m]

Rotation about the axis e_3 of B is free (B_psi e_3 = 0): it carries the prescribed spin.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numba
import numpy as np

from .._speed.compile_policy import KERNEL

from .crv import skew
from .small import add_into, copy_into, mm, mtv, mtv3, mv, outer


@numba.njit(**KERNEL)
def _hinge_psi_terms(R_A, R_B, Omega_B):
    """P (2x3), psi (2) [rad], B_psi (2x3) and psi_dot (2) [rad/s] of M.15–M.16."""
    P = np.empty((2, 3))
    for j in range(3):
        P[0, j] = R_A[j, 1]
        P[1, j] = -R_A[j, 0]
    psi = -mv(P, R_B[:, 2])
    e3t = np.zeros((3, 3))
    e3t[0, 1] = -1.0
    e3t[1, 0] = 1.0
    B_psi = mm(mm(P, R_B), e3t)
    return P, psi, B_psi, mv(B_psi, Omega_B)


@numba.njit(**KERNEL)
def hinge_forces(x_B, R_B, x_B_dot, Omega_B, x_A, R_A, H_u, H_psi, G_u, G_psi):
    """Viscoelastic hinge generalised force g (6) and residual tangents K, C (6x6).

    g = (f [N], tau [N m]) of (M.19)+(M.20) on (x_B, material rotation of B).
    K = -dg/d(x_B, Theta_B), C = -dg/d(x_B_dot, Omega_B), with material perturbations
    R_B -> R_B exp(dTheta~). H_u, G_u: 3x3 [N/m], [N s/m]; H_psi, G_psi: 2 [N m/rad],
    [N m s/rad].
    """
    u = mtv(R_A, x_B - x_A)
    u_dot = mtv(R_A, x_B_dot)
    P, psi, B_psi, psi_dot = _hinge_psi_terms(R_A, R_B, Omega_B)
    f_psi = H_psi * psi + G_psi * psi_dot
    # element by element, not slice assignments (`small.add_into`)
    g = np.zeros(6)
    f = mv(R_A, mv(H_u, u) + mv(G_u, u_dot))
    tau = mtv(B_psi, f_psi)
    for i in range(3):
        g[i] = -f[i]
        g[3 + i] = -tau[i]
    K = np.zeros((6, 6))
    C = np.zeros((6, 6))
    copy_into(K[:3, :3], mm(mm(R_A, H_u), R_A.T))
    copy_into(C[:3, :3], mm(mm(R_A, G_u), R_A.T))
    # tau = e3~ R^T P^T f_psi; d/dTheta of R^T w is (R^T w)~, of psi is B_psi, of psi_dot is
    # -P R (e3~ Omega)~.
    e3t = np.zeros((3, 3))
    e3t[0, 1] = -1.0
    e3t[1, 0] = 1.0
    RtPt = mm(R_B.T, P.T)
    dpsi_dot = -mm(mm(P, R_B), skew(mv(e3t, Omega_B)))
    df = np.empty((2, 3))
    for i in range(2):
        for j in range(3):
            df[i, j] = H_psi[i] * B_psi[i, j] + G_psi[i] * dpsi_dot[i, j]
    copy_into(K[3:, 3:], -mm(e3t, skew(mv(RtPt, f_psi)) + mm(RtPt, df)))
    for i in range(2):
        add_into(C[3:, 3:], G_psi[i] * outer(B_psi[i, :], B_psi[i, :]))
    return g, K, C


@numba.njit(**KERNEL)
def add_hinge_force(x_B, R_B, x_B_dot, Omega_B, x_A, R_A, H_u, H_psi, G_u, G_psi, g, off):
    """The generalised force of `hinge_forces` added to g[off:off + 6], without its tangents;
    returns the power the viscous part dissipates [W], u_dot^T G_u u_dot + sum G_psi psi_dot^2
    (= v^T C v of `hinge_forces`). Scalar code without temporaries: a residual-only evaluation
    calls it every Newton iteration, where the tangents and their ~25 small arrays would cost
    forty times as much."""
    # u = R_A^T (x_B - x_A), u_dot = R_A^T x_B_dot; f = -R_A (H_u u + G_u u_dot)
    u0, u1, u2 = mtv3(R_A, x_B[0] - x_A[0], x_B[1] - x_A[1], x_B[2] - x_A[2])
    w0, w1, w2 = mtv3(R_A, x_B_dot[0], x_B_dot[1], x_B_dot[2])
    s0 = H_u[0, 0] * u0 + G_u[0, 0] * w0 + (H_u[0, 1] * u1 + G_u[0, 1] * w1) + (H_u[0, 2] * u2 + G_u[0, 2] * w2)
    s1 = H_u[1, 0] * u0 + G_u[1, 0] * w0 + (H_u[1, 1] * u1 + G_u[1, 1] * w1) + (H_u[1, 2] * u2 + G_u[1, 2] * w2)
    s2 = H_u[2, 0] * u0 + G_u[2, 0] * w0 + (H_u[2, 1] * u1 + G_u[2, 1] * w1) + (H_u[2, 2] * u2 + G_u[2, 2] * w2)
    power = (w0 * (G_u[0, 0] * w0 + G_u[0, 1] * w1 + G_u[0, 2] * w2)
             + w1 * (G_u[1, 0] * w0 + G_u[1, 1] * w1 + G_u[1, 2] * w2)
             + w2 * (G_u[2, 0] * w0 + G_u[2, 1] * w1 + G_u[2, 2] * w2))
    for i in range(3):
        g[off + i] -= R_A[i, 0] * s0 + R_A[i, 1] * s1 + R_A[i, 2] * s2
    # psi_i = -P_i . xi_3 with P_0 = mu_2, P_1 = -mu_1; B_psi rows (P_i . R_B[:, 1], -P_i . R_B[:, 0], 0)
    for i in range(2):
        sign = 1.0 if i == 0 else -1.0
        col = 1 if i == 0 else 0
        p_xi = sign * (R_A[0, col] * R_B[0, 2] + R_A[1, col] * R_B[1, 2] + R_A[2, col] * R_B[2, 2])
        b0 = sign * (R_A[0, col] * R_B[0, 1] + R_A[1, col] * R_B[1, 1] + R_A[2, col] * R_B[2, 1])
        b1 = -sign * (R_A[0, col] * R_B[0, 0] + R_A[1, col] * R_B[1, 0] + R_A[2, col] * R_B[2, 0])
        psi_dot = b0 * Omega_B[0] + b1 * Omega_B[1]
        f_psi = -H_psi[i] * p_xi + G_psi[i] * psi_dot
        g[off + 3] -= b0 * f_psi
        g[off + 4] -= b1 * f_psi
        power += G_psi[i] * psi_dot * psi_dot
    return power


@numba.njit(**KERNEL)
def hinge_energy(x_B, R_B, x_A, R_A, H_u, H_psi):
    """Strain energy V = u^T H_u u / 2 + psi^T H_psi psi / 2 [J] (M.17). Scalar code without
    temporaries: the residual of every Newton iteration writes it into the diagnostics."""
    u0, u1, u2 = mtv3(R_A, x_B[0] - x_A[0], x_B[1] - x_A[1], x_B[2] - x_A[2])
    strain = 0.0
    for i, ui in enumerate((u0, u1, u2)):
        strain += ui * (H_u[i, 0] * u0 + H_u[i, 1] * u1 + H_u[i, 2] * u2)
    psi0 = -(R_A[0, 1] * R_B[0, 2] + R_A[1, 1] * R_B[1, 2] + R_A[2, 1] * R_B[2, 2])
    psi1 = R_A[0, 0] * R_B[0, 2] + R_A[1, 0] * R_B[1, 2] + R_A[2, 0] * R_B[2, 2]
    return 0.5 * strain + 0.5 * (H_psi[0] * psi0 ** 2 + H_psi[1] * psi1 ** 2)


@numba.njit(**KERNEL)
def hinge_strains(x_B, R_B, x_B_dot, Omega_B, x_A, R_A):
    """(u [m], psi [rad], u_dot [m/s], psi_dot [rad/s]) of M.15–M.16."""
    P, psi, B_psi, psi_dot = _hinge_psi_terms(R_A, R_B, Omega_B)
    return R_A.T @ (x_B - x_A), psi, R_A.T @ x_B_dot, psi_dot


@dataclass(frozen=True)
class HingeStiffness:
    """Hinge parameters (docs/model.md §5): H_u (3x3 SPD), H_psi (2, diagonal), G = c_G H."""

    H_u: np.ndarray = field(metadata={"unit": "N/m"})
    H_psi: np.ndarray = field(metadata={"unit": "N m/rad"})
    c_G: float = field(default=1e-6, metadata={"unit": "s", "ge": 0.0})

    def __post_init__(self) -> None:
        H_u = np.ascontiguousarray(self.H_u, dtype=float)
        H_psi = np.ascontiguousarray(self.H_psi, dtype=float)
        if H_u.shape != (3, 3) or not np.allclose(H_u, H_u.T, rtol=1e-12, atol=0.0):
            raise ValueError(f"hinge H_u must be a symmetric 3x3 matrix [N/m], got {H_u!r}")
        if np.linalg.eigvalsh(H_u).min() <= 0.0:
            raise ValueError(
                f"hinge H_u must be positive definite [N/m]; eigenvalues "
                f"{np.linalg.eigvalsh(H_u)}. Check the identified stiffness or give it by hand."
            )
        if H_psi.shape != (2,) or np.any(H_psi <= 0.0):
            raise ValueError(f"hinge H_psi must be 2 positive values [N m/rad], got {H_psi!r}")
        if not self.c_G >= 0.0:
            raise ValueError(f"hinge damping time c_G must be >= 0 s, got {self.c_G}")
        object.__setattr__(self, "H_u", H_u)
        object.__setattr__(self, "H_psi", H_psi)

    @property
    def G_u(self) -> np.ndarray:
        return self.c_G * self.H_u

    @property
    def G_psi(self) -> np.ndarray:
        return self.c_G * self.H_psi
