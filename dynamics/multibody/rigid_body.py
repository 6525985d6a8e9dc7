"""Rigid-body force kernels in the integrator's coordinates (docs/model.md §4).

Coordinates of one free rigid body (6 slots, see `problem.py`):
position x [m] (3, global frame) and CRV c (3, M.4a); velocities x_dot [m/s] and the
*material* angular velocity Omega [rad/s] (M.4d); accelerations x_ddot and Omega_dot.
Rotation perturbations are material: R -> R exp(dTheta~). With the material inertia J
constant, the equations are Newton–Euler:

    m x_ddot = f,        J Omega_dot = tau - Omega x (J Omega)

so `M` is constant and the complementary inertia (gyroscopic) moment -Omega x J Omega is part
of `g` (paper eq. 8). Tangents returned here are derivatives of the *residual*
`r = M a - g`: K = -dg/dTheta, C = -dg/dOmega (paper eq. 9 sign).
"""

from __future__ import annotations

import numba
import numpy as np

from .._speed.compile_policy import KERNEL

from .crv import skew
from .small import mm, mtv, mv


@numba.njit(**KERNEL)
def gyroscopic_moment(J, Omega):
    """Complementary inertia moment g_gyr = -Omega x (J Omega) [N m] (material), and
    C_gyr = -dg_gyr/dOmega = Omega~ J - (J Omega)~ [N m s]."""
    JO = mv(J, Omega)
    g = -np.cross(Omega, JO)
    return g, gyroscopic_damping(J, Omega)


@numba.njit(**KERNEL)
def gyroscopic_damping(J, Omega):
    """C_gyr = Omega~ J - (J Omega)~ [N m s] of `gyroscopic_moment` alone, for tangents that need
    no moment (and so no `np.cross`, a library of its own on a machine's first run)."""
    return mm(skew(Omega), J) - skew(mv(J, Omega))


@numba.njit(**KERNEL)
def material_moment_of_spatial_moment(R, m_s):
    """Material moment tau = R^T m_s [N m] of a spatial moment held fixed in space, and
    K = -dtau/dTheta = -(R^T m_s)~ (R -> R exp(dTheta~) gives dtau = (R^T m_s)~ dTheta)."""
    tau = mtv(R, m_s)
    return tau, -skew(tau)


@numba.njit(**KERNEL)
def material_moment_of_spatial_force(R, rho, f_s):
    """Material moment tau = rho x (R^T f_s) [N m] of a spatial force f_s [N] held fixed in
    space, applied at the material point rho [m] (measured from the reference point), and
    K = -dtau/dTheta = -rho~ (R^T f_s)~ (dead loads such as gravity)."""
    fm = R.T @ f_s
    tau = np.cross(rho, fm)
    return tau, -(skew(rho) @ skew(fm))


@numba.njit(**KERNEL)
def kinetic_energy(m, J, x_dot, Omega):
    """T = m |x_dot|^2 / 2 + Omega^T J Omega / 2 [J]."""
    return 0.5 * m * (x_dot @ x_dot) + 0.5 * (Omega @ (J @ Omega))


def inertia_about_point(m: float, J_c: np.ndarray, rho: np.ndarray) -> np.ndarray:
    """Inertia about a point at -rho from the centre of mass (parallel axis theorem):
    J_O = J_c + m (|rho|^2 I - rho rho^T) [kg m^2], rho = centre of mass seen from O."""
    rho = np.asarray(rho, dtype=float)
    return np.asarray(J_c, dtype=float) + m * ((rho @ rho) * np.eye(3) - np.outer(rho, rho))
