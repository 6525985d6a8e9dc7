"""Small example models implementing the residual protocol (`problem.py`).

They serve the tests and the benchmark and show the bearing model how to write one:
a plane pendulum, an elastic (spring) pendulum, one rigid body (free, on a pivot, or held by
the viscoelastic hinge with a prescribed spin), and an "arrow" system of many small
bodies tied to one large body, assembled in the block-arrow structure.
"""

from __future__ import annotations

import math

import numpy as np

from .crv import crv_to_matrix
from .hinge import HingeStiffness, hinge_forces
from .joints import prescribe_velocity_dense, prescribe_velocity_residual
from .rigid_body import gyroscopic_moment, material_moment_of_spatial_force


class Pendulum:
    """theta'' = -omega0^2 sin(theta) - zeta theta' (per unit m L^2); q = theta [rad]."""

    rotation_slots = np.zeros(0, dtype=np.int64)

    def __init__(self, omega0: float, damping: float = 0.0) -> None:
        self.n_dof = 1
        self.omega0, self.damping = omega0, damping
        self.error_weights = np.ones(1)
        self._S = np.zeros((1, 1))

    def evaluate(self, t, q, v, a, ma_out, g_out):
        ma_out[0] = a[0]
        g_out[0] = -self.omega0**2 * math.sin(q[0]) - self.damping * v[0]

    def jacobian(self, t, q, v, a, c_m, c_v, c_q):
        self._S[0, 0] = c_m + c_v * self.damping + c_q * self.omega0**2 * math.cos(q[0])
        return self._S

    def energy(self, q, v):
        return 0.5 * v[0] ** 2 + self.omega0**2 * (1.0 - np.cos(q[0]))


class ElasticPendulum:
    """Point mass m on a linear spring (k, free length L0) to the origin, gravity -y.

    q = (x, y) [m]; conservative and nonlinear (spring pendulum)."""

    rotation_slots = np.zeros(0, dtype=np.int64)

    def __init__(self, m: float, k: float, L0: float, grav: float = 9.81) -> None:
        self.n_dof = 2
        self.m, self.k, self.L0, self.grav = m, k, L0, grav
        self.error_weights = np.ones(2)
        self._S = np.zeros((2, 2))

    def evaluate(self, t, q, v, a, ma_out, g_out):
        x, y = q[0], q[1]
        r = math.sqrt(x * x + y * y)
        f = -self.k * (r - self.L0) / r
        ma_out[0] = self.m * a[0]
        ma_out[1] = self.m * a[1]
        g_out[0] = f * x
        g_out[1] = f * y - self.m * self.grav

    def jacobian(self, t, q, v, a, c_m, c_v, c_q):
        x, y = q[0], q[1]
        r = math.sqrt(x * x + y * y)
        s, S = self.L0 / r, self._S
        ex, ey = x / r, y / r
        kd = self.k * (1.0 - s)
        S[0, 0] = c_m * self.m + c_q * (kd + self.k * s * ex * ex)
        S[1, 1] = c_m * self.m + c_q * (kd + self.k * s * ey * ey)
        S[0, 1] = S[1, 0] = c_q * self.k * s * ex * ey
        return S

    def energy(self, q, v):
        r = np.hypot(q[0], q[1])
        potential = 0.5 * self.k * (r - self.L0) ** 2 + self.m * self.grav * q[1]
        return 0.5 * self.m * (v @ v) + potential


class RigidBody:
    """One rigid body; coordinates (see problem.py):

    * free (`pivot=False`): q = (x [m], c), v = (x_dot, Omega), rotation slot 3;
      J about the centre of mass; gravity acts at the centre of mass.
    * on a fixed pivot (`pivot=True`, spherical joint to ground eliminated): q = c,
      v = Omega, rotation slot 0; J about the pivot, centre of mass at material `rho`.

    Options: viscoelastic `hinge` to the static frame A = (origin, identity) (free body only);
    prescribed material spin `spin` [rad/s] about e_3 (row replaced, joints.py), whose drive
    moment is stored in `self.drive_moment` after each evaluation.
    """

    def __init__(self, mass: float, J, *, pivot: bool = False, rho=(0.0, 0.0, 0.0),
                 gravity=(0.0, 0.0, 0.0), hinge: HingeStiffness | None = None,
                 spin: float | None = None, radius: float = 1.0) -> None:
        self.pivot = pivot
        self.n_dof = 3 if pivot else 6
        self.r0 = 0 if pivot else 3  # first rotation index
        self.rotation_slots = np.array([self.r0], dtype=np.int64)
        self.mass, self.J = mass, np.ascontiguousarray(J, dtype=float)
        self.rho = np.asarray(rho, dtype=float)
        self.weight = mass * np.asarray(gravity, dtype=float)  # spatial force [N]
        self.hinge, self.spin = hinge, spin
        if hinge is not None and pivot:
            raise ValueError("a hinge needs the free body (pivot=False)")
        self.error_weights = np.ones(self.n_dof)
        self.error_weights[self.r0:] = radius  # rotation errors read as arc lengths [m]
        self.drive_moment = 0.0
        self._S = np.zeros((self.n_dof, self.n_dof))
        self._zero3, self._I3 = np.zeros(3), np.eye(3)

    def _spin_row(self) -> int:
        return self.r0 + 2

    def evaluate(self, t, q, v, a, ma_out, g_out):
        r0 = self.r0
        R = crv_to_matrix(q[r0:r0 + 3])
        Om = v[r0:r0 + 3]
        ma_out[r0:] = self.J @ a[r0:]
        g_out[r0:], _ = gyroscopic_moment(self.J, Om)
        if self.pivot:
            tau, _ = material_moment_of_spatial_force(R, self.rho, self.weight)
            g_out[:] += tau
        else:
            ma_out[:3] = self.mass * a[:3]
            g_out[:3] = self.weight
        if self.hinge is not None:
            h = self.hinge
            gh, _, _ = hinge_forces(q[:3], R, v[:3], Om, self._zero3, self._I3, h.H_u,
                                    h.H_psi, h.G_u, h.G_psi)
            g_out[:] += gh
        if self.spin is not None:
            self.drive_moment = prescribe_velocity_residual(self._spin_row(), v, self.spin,
                                                            1.0, ma_out, g_out)

    def jacobian(self, t, q, v, a, c_m, c_v, c_q):
        r0, S = self.r0, self._S
        R = crv_to_matrix(q[r0:r0 + 3])
        Om = v[r0:r0 + 3]
        S[:] = 0.0
        _, C_gyr = gyroscopic_moment(self.J, Om)
        S[r0:, r0:] = c_m * self.J + c_v * C_gyr
        if self.pivot:
            _, K = material_moment_of_spatial_force(R, self.rho, self.weight)
            S[:, :] += c_q * K
        else:
            S[:3, :3] = c_m * self.mass * self._I3
        if self.hinge is not None:
            h = self.hinge
            _, K, C = hinge_forces(q[:3], R, v[:3], Om, self._zero3, self._I3, h.H_u,
                                   h.H_psi, h.G_u, h.G_psi)
            S += c_v * C + c_q * K
        if self.spin is not None:
            prescribe_velocity_dense(S, self._spin_row(), c_m, c_v, 1.0)
        return S

    def kinetic_energy(self, v) -> float:
        r0 = self.r0
        T = 0.5 * v[r0:] @ (self.J @ v[r0:])
        return T if self.pivot else T + 0.5 * self.mass * (v[:3] @ v[:3])

    def angular_momentum(self, q, v) -> np.ndarray:
        """Spatial angular momentum about the pivot / centre of mass [N m s]."""
        r0 = self.r0
        return crv_to_matrix(q[r0:r0 + 3]) @ (self.J @ v[r0:])

    def potential_energy(self, q) -> float:
        if self.pivot:
            R = crv_to_matrix(q[:3])
            return -self.weight @ (R @ self.rho)
        return -self.weight @ q[:3]


class ArrowSprings:
    """Z small point masses, each tied by a hardening spring-damper to one large body and by a
    linear spring to ground; the large body is tied to ground. Each small body couples only
    to the large one, so the iteration matrix is block-arrow (Z blocks of 3, border of 3).

    Spring law on the separation d (from rest) [m]: f = -(k + k3 |d|^2) d - c d_dot.
    Coordinates: [x_0 (3), ..., x_{Z-1} (3), X (3)]. `structure` = "block" returns a
    BlockArrowMatrix from `jacobian`, "dense" a dense array (same numbers).
    """

    rotation_slots = np.zeros(0, dtype=np.int64)

    def __init__(self, Z: int, structure: str = "block", m_small: float = 0.03,
                 m_large: float = 1.0, k: float = 1e6, k3: float = 1e13, c: float = 5.0,
                 k_ground: float = 2e5, K_large: float = 5e6, seed: int = 0) -> None:
        from .linear_solvers import BlockArrowMatrix
        self.Z, self.n_dof, self.structure = Z, 3 * Z + 3, structure
        self.m_small, self.m_large = m_small, m_large
        self.k, self.k3, self.c, self.k_ground, self.K_large = k, k3, c, k_ground, K_large
        self.error_weights = np.ones(self.n_dof)
        self._S_block = BlockArrowMatrix.zeros(Z, 3, 3)
        self._S_dense = np.zeros((self.n_dof, self.n_dof))
        self._I3 = np.eye(3)

    def _links(self, q, v):
        x = q[:-3].reshape(self.Z, 3)
        d = x - q[-3:]
        d_dot = v[:-3].reshape(self.Z, 3) - v[-3:]
        return x, d, d_dot

    def evaluate(self, t, q, v, a, ma_out, g_out):
        x, d, d_dot = self._links(q, v)
        f = -(self.k + self.k3 * np.sum(d * d, axis=1))[:, None] * d - self.c * d_dot
        ma_out[:-3] = self.m_small * a[:-3]
        ma_out[-3:] = self.m_large * a[-3:]
        g_out[:-3] = (f - self.k_ground * x).ravel()
        g_out[-3:] = -f.sum(axis=0) - self.K_large * q[-3:]

    def jacobian(self, t, q, v, a, c_m, c_v, c_q):
        x, d, d_dot = self._links(q, v)
        dd = np.sum(d * d, axis=1)
        # link tangent: -df/dd = (k + k3|d|^2) I + 2 k3 d d^T
        Kl = (self.k + self.k3 * dd)[:, None, None] * self._I3 + 2 * self.k3 * (
            d[:, :, None] * d[:, None, :])
        L = c_q * Kl + c_v * self.c * self._I3  # residual tangent of one link
        S = self._S_block
        S.D[:] = L + (c_m * self.m_small + c_q * self.k_ground) * self._I3
        S.E[:] = -L
        S.F[:] = -L
        S.B[:] = L.sum(axis=0) + (c_m * self.m_large + c_q * self.K_large) * self._I3
        if self.structure == "block":
            return S
        self._S_dense[:] = S.to_dense()
        return self._S_dense
