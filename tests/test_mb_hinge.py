"""Viscoelastic hinge joint (docs/model.md §5, M.15–M.20): forces are -grad V (finite
differences), damping dissipates, tangents match finite differences, and the literal M.16
strain rates agree with the kernel's form."""

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from bearingsim.dynamics.multibody.crv import skew
from bearingsim.dynamics.multibody.hinge import (HingeStiffness, add_hinge_force, hinge_energy,
                                                 hinge_forces, hinge_strains)

RNG = np.random.default_rng(11)


def rot(theta):
    return Rotation.from_rotvec(theta).as_matrix()


def random_case():
    R_A = rot(RNG.normal(size=3))
    x_A = RNG.normal(size=3) * 0.01
    # B tilted up to ~0.1 rad off A, spun arbitrarily about its own axis.
    R_B = R_A @ rot(RNG.normal(size=3) * 0.05) @ rot([0, 0, RNG.uniform(0, 2 * np.pi)])
    x_B = x_A + RNG.normal(size=3) * 1e-4
    L = RNG.normal(size=(3, 3))
    H_u = 1e9 * (L @ L.T + 3 * np.eye(3))
    H_psi = 1e5 * RNG.uniform(0.5, 2.0, size=2)
    c_G = 1e-4
    x_dot = RNG.normal(size=3) * 0.1
    Omega = RNG.normal(size=3) * 5.0
    return x_B, R_B, x_dot, Omega, x_A, R_A, H_u, H_psi, c_G * H_u, c_G * H_psi


def g_of(case, dx=np.zeros(3), dth=np.zeros(3), dxd=np.zeros(3), dOm=np.zeros(3)):
    x_B, R_B, x_dot, Omega, x_A, R_A, H_u, H_psi, G_u, G_psi = case
    return hinge_forces(x_B + dx, R_B @ rot(dth), x_dot + dxd, Omega + dOm, x_A, R_A, H_u,
                        H_psi, G_u, G_psi)[0]


def test_elastic_forces_are_minus_energy_gradient():
    for _ in range(10):
        case = random_case()
        x_B, R_B, _, _, x_A, R_A, H_u, H_psi, G_u, G_psi = case
        g = hinge_forces(x_B, R_B, np.zeros(3), np.zeros(3), x_A, R_A, H_u, H_psi, G_u,
                         G_psi)[0]
        grad = np.empty(6)
        for j in range(3):
            e = np.zeros(3)
            e[j] = 1e-7
            grad[j] = (hinge_energy(x_B + e, R_B, x_A, R_A, H_u, H_psi)
                       - hinge_energy(x_B - e, R_B, x_A, R_A, H_u, H_psi)) / 2e-7
            e[j] = 1e-6
            grad[3 + j] = (hinge_energy(x_B, R_B @ rot(e), x_A, R_A, H_u, H_psi)
                           - hinge_energy(x_B, R_B @ rot(-e), x_A, R_A, H_u, H_psi)) / 2e-6
        np.testing.assert_allclose(g, -grad, rtol=1e-6, atol=1e-6 * np.abs(grad).max())


def test_damping_dissipates_and_matches_S16_rates():
    for _ in range(20):
        case = random_case()
        x_B, R_B, x_dot, Omega, x_A, R_A, H_u, H_psi, G_u, G_psi = case
        g_all = hinge_forces(*case)[0]
        g_el = hinge_forces(x_B, R_B, 0 * x_dot, 0 * Omega, x_A, R_A, H_u, H_psi, G_u,
                            G_psi)[0]
        g_nc = g_all - g_el
        power = g_nc @ np.concatenate([x_dot, Omega])
        # M.16 literally: psi_dot = ((mu2~ xi3)^T R_B Omega, -(mu1~ xi3)^T R_B Omega)
        mu1, mu2, xi3 = R_A[:, 0], R_A[:, 1], R_B[:, 2]
        psi_dot = np.array([(skew(mu2) @ xi3) @ (R_B @ Omega),
                            -(skew(mu1) @ xi3) @ (R_B @ Omega)])
        u_dot = R_A.T @ x_dot
        expected = -(u_dot @ (G_u @ u_dot)) - psi_dot @ (G_psi * psi_dot)
        assert power < 0.0
        np.testing.assert_allclose(power, expected, rtol=1e-10)
        np.testing.assert_allclose(hinge_strains(x_B, R_B, x_dot, Omega, x_A, R_A)[3],
                                   psi_dot, rtol=1e-10, atol=1e-14)


def test_tangents_match_finite_differences():
    for _ in range(10):
        case = random_case()
        _, K, C = hinge_forces(*case)
        K_fd, C_fd = np.empty((6, 6)), np.empty((6, 6))
        for j in range(6):
            e = np.zeros(3)
            e[j % 3] = 1e-7 if j < 3 else 1e-6
            s = e[j % 3]
            kw = ("dx", "dth")[j // 3]
            K_fd[:, j] = -(g_of(case, **{kw: e}) - g_of(case, **{kw: -e})) / (2 * s)
            kw = ("dxd", "dOm")[j // 3]
            C_fd[:, j] = -(g_of(case, **{kw: e}) - g_of(case, **{kw: -e})) / (2 * s)
        np.testing.assert_allclose(K, K_fd, rtol=1e-5, atol=1e-6 * np.abs(K).max())
        np.testing.assert_allclose(C, C_fd, rtol=1e-5, atol=1e-6 * np.abs(C).max())
        # slow twin: the plain-Python kernel gives the same numbers
        for a, b in zip(hinge_forces.py_func(*case), hinge_forces(*case)):
            np.testing.assert_allclose(a, b, rtol=1e-13, atol=1e-300)


def test_static_frame_is_force_free_and_axis_rotation_is_free():
    case = random_case()
    x_B, R_B, x_dot, Omega, x_A, R_A, H_u, H_psi, G_u, G_psi = case
    R_spin = R_A @ rot([0, 0, 1.234])
    g, _, _ = hinge_forces(x_A, R_spin, np.zeros(3), np.array([0, 0, 300.0]), x_A, R_A,
                           H_u, H_psi, G_u, G_psi)
    np.testing.assert_allclose(g, 0.0, atol=1e-9)
    g1 = hinge_forces(*case)[0]
    # same spatial state seen from a body frame turned by 0.7 rad about its own axis:
    # only the material components of the moment (and of Omega) change
    spin = rot([0, 0, 0.7])
    g2 = hinge_forces(x_B, R_B @ spin, x_dot, spin.T @ Omega, x_A, R_A, H_u, H_psi, G_u,
                      G_psi)[0]
    np.testing.assert_allclose(g1[:3], g2[:3], rtol=1e-12)
    np.testing.assert_allclose(R_B @ g1[3:], (R_B @ spin) @ g2[3:], rtol=1e-10)


def test_hinge_stiffness_validation_speaks_to_user():
    import pytest
    with pytest.raises(ValueError, match="positive definite"):
        HingeStiffness(H_u=-np.eye(3), H_psi=[1e5, 1e5])
    with pytest.raises(ValueError, match="H_psi"):
        HingeStiffness(H_u=np.eye(3), H_psi=[1e5, -1.0])


def test_residual_only_force_is_the_full_one():
    """`add_hinge_force` (no tangents, the Newton iteration's call) against `hinge_forces`: the
    same wrench, and as power the quadratic form v^T C v of its damping tangent."""
    for _ in range(20):
        case = random_case()
        x_B, R_B, x_dot, Omega, x_A, R_A, H_u, H_psi, G_u, G_psi = case
        g_full, _, C = hinge_forces(*case)
        g = np.full(9, 7.0)  # a wrench is added at an offset, the rest untouched
        power = add_hinge_force(x_B, R_B, x_dot, Omega, x_A, R_A, H_u, H_psi, G_u, G_psi, g, 2)
        np.testing.assert_allclose(g[2:8] - 7.0, g_full, rtol=1e-12, atol=1e-12 * np.abs(g_full).max())
        assert g[0] == g[1] == g[8] == 7.0
        v = np.concatenate([x_dot, Omega])
        assert power == pytest.approx(v @ C @ v, rel=1e-12)
        assert power >= 0.0
