"""Conformal rotation vector kinematics (docs/model.md M.4a–d).

References: Bauchau & Trainelli, Nonlinear Dyn. 32 (2003) 71–92 (CRV, rescaling
c* = -16 c/(c.c)); the rotation matrix of a rotation vector is Rodrigues' formula, taken
from scipy.spatial.transform.Rotation as an independent implementation.
"""

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from bearingsim.dynamics.multibody import crv

RNG = np.random.default_rng(20240601)


def random_rotation_vectors(n, max_angle=np.pi):
    axis = RNG.normal(size=(n, 3))
    axis /= np.linalg.norm(axis, axis=1)[:, None]
    return axis * RNG.uniform(0.0, max_angle, size=(n, 1))


def test_crv_matrix_matches_rodrigues():
    # R(c) of M.4b with c = 4 tan(phi/4) n must equal the rotation by phi about n.
    for theta in random_rotation_vectors(50):
        c = crv.crv_from_rotation_vector(theta)
        assert np.linalg.norm(c) <= 4.0 + 1e-12
        R_ref = Rotation.from_rotvec(theta).as_matrix()
        np.testing.assert_allclose(crv.crv_to_matrix(c), R_ref, atol=1e-14)
        np.testing.assert_allclose(crv.crv_to_matrix.py_func(c), R_ref, atol=1e-14)


def test_rotation_vector_round_trip_including_small_angles():
    for scale in (1e-9, 1e-5, 1e-3, 1.0, 3.0):
        for theta in random_rotation_vectors(10, max_angle=scale):
            back = crv.crv_to_rotation_vector(crv.crv_from_rotation_vector(theta))
            np.testing.assert_allclose(back, theta, rtol=1e-13, atol=1e-300)


def test_tangent_operator_by_finite_differences():
    # M.4c: the spatial angular velocity omega~ = R_dot R^T equals H(c) c_dot.
    for _ in range(20):
        c = RNG.normal(size=3) * 1.5
        c_dot = RNG.normal(size=3)
        eps = 1e-6
        R_dot = (crv.crv_to_matrix(c + eps * c_dot) - crv.crv_to_matrix(c - eps * c_dot)) / (
            2 * eps)
        W = R_dot @ crv.crv_to_matrix(c).T
        omega = np.array([W[2, 1], W[0, 2], W[1, 0]])
        np.testing.assert_allclose(crv.crv_H(c) @ c_dot, omega, atol=1e-8)
        # M.4d: material Omega = H^T c_dot = R^T omega, and H^-1 is the inverse of H.
        np.testing.assert_allclose(crv.crv_H(c).T @ c_dot, crv.crv_to_matrix(c).T @ omega,
                                   atol=1e-8)
        np.testing.assert_allclose(crv.crv_H_inv(c) @ crv.crv_H(c), np.eye(3), atol=1e-13)


def test_rescaling_keeps_rotation_and_maps_rate():
    # Beyond one half turn (|c| > 4) c* = -16 c/(c.c) is the same rotation (phi -> phi - 2 pi)
    # and the mapped rate gives the same angular velocity (Bauchau & Trainelli 2003, §6).
    for _ in range(20):
        n = RNG.normal(size=3)
        n /= np.linalg.norm(n)
        phi = RNG.uniform(np.pi + 0.1, 2 * np.pi - 0.1)
        c = 4 * np.tan(phi / 4) * n
        assert np.linalg.norm(c) > 4
        c_dot = RNG.normal(size=3)
        c_star, c_star_dot = crv.crv_rescale(c, c_dot)
        assert np.linalg.norm(c_star) < 4
        np.testing.assert_allclose(crv.crv_to_matrix(c_star), crv.crv_to_matrix(c), atol=1e-13)
        np.testing.assert_allclose(crv.crv_H(c_star) @ c_star_dot, crv.crv_H(c) @ c_dot,
                                   atol=1e-12)
        s2, s2_dot = crv.crv_rescale.py_func(c, c_dot)
        np.testing.assert_allclose(s2, c_star, rtol=1e-14)
        np.testing.assert_allclose(s2_dot, c_star_dot, rtol=1e-14)


def test_composition_is_matrix_product_and_stays_rescaled():
    for a, b in zip(random_rotation_vectors(30), random_rotation_vectors(30)):
        p, q = crv.crv_from_rotation_vector(a), crv.crv_from_rotation_vector(b)
        r = crv.crv_compose(p, q)
        assert np.linalg.norm(r) <= 4.0 + 1e-12
        np.testing.assert_allclose(crv.crv_to_matrix(r),
                                   crv.crv_to_matrix(p) @ crv.crv_to_matrix(q), atol=1e-14)
        np.testing.assert_allclose(crv.crv_compose.py_func(p, q), r, atol=1e-14)


@pytest.mark.parametrize("turns", [0.3, 7.7])
def test_multiplicative_update_over_many_turns(turns):
    # Composing N equal increments about one axis must give N times the rotation, with one
    # rescaling per turn: the CRV flips (c* = -c at |c| = 4) at phi = pi, 3 pi, 5 pi, ...
    n_steps = 2000
    axis = np.array([0.3, -0.5, 0.8]) / np.linalg.norm([0.3, -0.5, 0.8])
    dtheta = axis * 2 * np.pi * turns / n_steps
    q = np.zeros(3)
    out = np.empty(3)
    slots = np.array([0], dtype=np.int64)
    flips = 0
    for _ in range(n_steps):
        crv.update_configuration(q, dtheta, slots, out)
        flips += np.linalg.norm(out - q) > 1.0
        q = out.copy()
    R_ref = Rotation.from_rotvec(axis * 2 * np.pi * turns).as_matrix()
    np.testing.assert_allclose(crv.crv_to_matrix(q), R_ref, atol=1e-11)
    assert flips == int(np.floor(turns + 0.5))


def test_update_configuration_is_compose_of_the_increment_bit_for_bit():
    # update_configuration repeats crv_compose(q, crv_from_rotation_vector(dq)) on scalars (the
    # time loop runs without reference counting); the two must stay the same arithmetic, so
    # the comparison is exact. Increments from 1e-9 rad (the small-angle series) to 2 rad,
    # CRVs up to the rescaling limit |c| = 4.
    rng = np.random.default_rng(7)
    slots = np.array([3, 9], dtype=np.int64)
    for scale_q, scale_dq in [(1e-3, 1e-9), (0.5, 1e-5), (2.0, 1e-2), (3.9 / np.sqrt(3), 1.0)]:
        for _ in range(100):
            q = rng.uniform(-1, 1, 12) * scale_q
            dq = rng.normal(size=12) * scale_dq
            out = np.empty(12)
            crv.update_configuration(q, dq, slots, out)
            ref = q + dq
            for j in slots:
                ref[j:j + 3] = crv.crv_compose(q[j:j + 3], crv.crv_from_rotation_vector(dq[j:j + 3]))
            assert np.array_equal(out, ref)

