"""Rigid bodies with CRV orientation in the HHT-α integrator (docs/model.md §4, §5, §9).

Orientation is a CRV updated multiplicatively with material angular velocities (the
"equivalent choice" of §4); `test_equivalent_to_paper_crv_coordinates` checks it against the
paper's coordinates (c, c_dot = H^-T Omega, M.4c–d) integrated by an independent method.
"""

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.spatial.transform import Rotation

from bearingsim.dynamics.multibody import HHTSettings, HingeStiffness, integrate
from bearingsim.dynamics.multibody.crv import (crv_from_rotation_vector, crv_H_inv, crv_rescale,
                                    crv_to_matrix)
from bearingsim.dynamics.multibody.example_problems import RigidBody
from bearingsim.dynamics.multibody.rigid_body import (gyroscopic_moment,
                                           material_moment_of_spatial_force,
                                           material_moment_of_spatial_moment)

RNG = np.random.default_rng(5)


def rot(theta):
    return Rotation.from_rotvec(theta).as_matrix()


def fixed(h, alpha=0.0, tol=1e-8):
    return HHTSettings(alpha=alpha, first_step=h, min_step=h, max_step=h, adaptive=False,
                       atol=1e-6, rtol=0.0, newton_tol=tol)


def test_kernel_tangents_by_finite_differences():
    L = RNG.normal(size=(3, 3))
    J = L @ L.T + np.eye(3)
    Om, R, rho, f = RNG.normal(size=3), rot(RNG.normal(size=3)), RNG.normal(size=3), \
        RNG.normal(size=3)
    _, C = gyroscopic_moment(J, Om)
    _, K_f = material_moment_of_spatial_force(R, rho, f)
    _, K_m = material_moment_of_spatial_moment(R, f)
    C_fd, Kf_fd, Km_fd = (np.empty((3, 3)) for _ in range(3))
    eps = 1e-6
    for j in range(3):
        e = np.eye(3)[j] * eps
        C_fd[:, j] = -(gyroscopic_moment(J, Om + e)[0] - gyroscopic_moment(J, Om - e)[0]) / (
            2 * eps)
        Kf_fd[:, j] = -(material_moment_of_spatial_force(R @ rot(e), rho, f)[0]
                        - material_moment_of_spatial_force(R @ rot(-e), rho, f)[0]) / (2 * eps)
        Km_fd[:, j] = -(material_moment_of_spatial_moment(R @ rot(e), f)[0]
                        - material_moment_of_spatial_moment(R @ rot(-e), f)[0]) / (2 * eps)
    for a, b in ((C, C_fd), (K_f, Kf_fd), (K_m, Km_fd)):
        np.testing.assert_allclose(a, b, atol=1e-8)
    np.testing.assert_allclose(gyroscopic_moment.py_func(J, Om)[1], C, rtol=1e-14)


def run_free_body(J, Omega0, T, n, c0=np.zeros(3), alpha=0.0):
    body = RigidBody(1.0, J, radius=0.1)
    q0 = np.concatenate([np.zeros(3), c0])
    v0 = np.concatenate([np.zeros(3), Omega0])
    trace = []
    sol = integrate(body, 0.0, T, q0, v0, fixed(T / n, alpha),
                    on_step=lambda t, q, v, a: trace.append((t, q.copy(), v.copy())))
    return body, sol, trace


def test_torque_free_asymmetric_body_conserves_energy_and_momentum():
    J = np.diag([1.0, 2.0, 3.0])
    Omega0 = np.array([0.2, 3.0, 0.3])  # near the unstable middle axis: a hard case
    body, sol, trace = run_free_body(J, Omega0, 20.0, 8000)
    T0 = 0.5 * Omega0 @ J @ Omega0
    L0 = J @ Omega0
    T_err = max(abs(body.kinetic_energy(v) - T0) for _, _, v in trace) / T0
    L_err = max(np.linalg.norm(body.angular_momentum(q, v) - L0) for _, q, v in trace)
    # Lie-group trapezoidal rule: invariants kept to O(h^2) (bounded, no drift)
    assert T_err < 1e-4 and L_err / np.linalg.norm(L0) < 1e-4, (T_err, L_err)
    # the body really tumbles (flips its middle axis), so the check is not trivial
    assert min(v[4] for _, _, v in trace) < -2.5


def test_equivalent_to_paper_crv_coordinates():
    # Reference: the paper's coordinates (M.4c–d), c_dot = H^-T Omega with Euler's equations,
    # integrated by DOP853 (rtol 1e-12); rescaled by c* = -16c/(c.c) whenever |c| reaches 4.
    J = np.diag([1.0, 2.0, 3.0])
    Omega0 = np.array([1.0, 0.5, 2.0])
    T = 6.0

    def rhs(t, y):
        c, Om = y[:3], y[3:]
        return np.concatenate([crv_H_inv(c).T @ Om, np.linalg.solve(J, -np.cross(Om, J @ Om))])

    def past_half_turn(t, y):
        return y[:3] @ y[:3] - 16.0

    past_half_turn.terminal, past_half_turn.direction = True, 1
    t, y, rescalings = 0.0, np.concatenate([np.zeros(3), Omega0]), 0
    while t < T:
        r = solve_ivp(rhs, (t, T), y, method="DOP853", rtol=1e-12, atol=1e-12,
                      events=past_half_turn)
        t, y = r.t[-1], r.y[:, -1].copy()
        if r.status == 1:
            c_dot = crv_H_inv(y[:3]).T @ y[3:]
            y[:3], _ = crv_rescale(y[:3] * (1 + 1e-12), c_dot)
            rescalings += 1
    assert rescalings >= 1
    errs = []
    for n in (1500, 3000):
        _, sol, _ = run_free_body(J, Omega0, T, n)
        errs.append(np.abs(crv_to_matrix(sol.q[3:]) - crv_to_matrix(y[:3])).max())
        np.testing.assert_allclose(sol.v[3:], y[3:], atol=3e-3)
    assert errs[1] < 1e-3 and errs[0] / errs[1] > 3.5  # second order, same solution


def test_spinning_rotor_passes_many_rescalings_smoothly():
    # Torque-free symmetric body (Landau & Lifshitz, Mechanics §33): Omega_3 constant, the
    # transverse Omega turns at lambda = (I3 - I1) Omega_3 / I1 in the body, and
    # R(t) = Rot(L/|L|, |L| t / I1) R0 Rot(e3, -lambda t).
    I1, I3 = 1.0, 2.0
    J = np.diag([I1, I1, I3])
    Omega0 = np.array([0.3, 0.0, 20.0])
    T, n = 10.0, 10000  # 32 turns
    _, sol, trace = run_free_body(J, Omega0, T, n)
    L = J @ Omega0
    lam = (I3 - I1) * Omega0[2] / I1
    flips, R_err, jumps = 0, 0.0, []
    R_prev, c_prev, v_prev = np.eye(3), np.zeros(3), Omega0
    for t, q, v in trace:
        R = crv_to_matrix(q[3:])
        R_ref = rot(L / np.linalg.norm(L) * np.linalg.norm(L) * t / I1) @ rot([0, 0, -lam * t])
        R_err = max(R_err, np.abs(R - R_ref).max())
        flips += np.linalg.norm(q[3:] - c_prev) > 1.0
        jumps.append((np.abs(R - R_prev).max(), np.abs(v[3:] - v_prev).max()))
        R_prev, c_prev, v_prev = R, q[3:].copy(), v[3:]
    jumps = np.array(jumps)
    assert flips >= 30  # one CRV rescaling per turn
    # no step changes R or Omega by more than the motion in one step allows
    assert jumps[:, 0].max() < 1.05 * np.linalg.norm(Omega0) * T / n * np.sqrt(2)
    assert jumps[:, 1].max() < 1.05 * lam * np.hypot(*Omega0[:2]) * T / n
    assert abs(sol.v[5] - Omega0[2]) < 1e-10
    assert R_err < 2e-3


def test_heavy_symmetric_top_precession_rate():
    # Uniform precession of a heavy symmetric top (Goldstein, Poole & Safko, Classical
    # Mechanics 3rd ed., §5.7): M g l = phi_dot (I3 omega3 - I1 phi_dot cos theta), the slow
    # root; I1 about the pivot.
    m, l, I1c, I3, grav = 1.0, 0.1, 0.002, 0.004, 9.81
    I1 = I1c + m * l * l
    theta, omega3 = 0.5, 100.0
    ct = np.cos(theta)
    phi_dot = (I3 * omega3 - np.sqrt((I3 * omega3) ** 2 - 4 * I1 * ct * m * grav * l)) / (
        2 * I1 * ct)
    top = RigidBody(m, np.diag([I1, I1, I3]), pivot=True, rho=(0, 0, l),
                    gravity=(0, 0, -grav), radius=l)
    R0 = rot([theta, 0, 0])
    Omega0 = phi_dot * R0.T @ [0, 0, 1.0] + (omega3 - phi_dot * ct) * np.array([0, 0, 1.0])
    ts, az, tilt = [], [], []

    def log(t, q, v, a):
        axis = crv_to_matrix(q)[:, 2]
        ts.append(t)
        az.append(np.arctan2(axis[1], axis[0]))
        tilt.append(np.arccos(axis[2]))

    T = 2.5  # about one precession turn and 40 spin turns
    integrate(top, 0.0, T, crv_from_rotation_vector(np.array([theta, 0, 0])), Omega0,
              fixed(T / 10000), on_step=log)
    rate = np.polyfit(ts, np.unwrap(az), 1)[0]
    assert rate == pytest.approx(phi_dot, rel=5e-4)
    assert np.ptp(tilt) < 2e-5  # no nutation appears


def test_prescribed_spin_holds_speed_and_costs_no_torque_on_a_symmetric_top():
    # For a symmetric top omega3 is constant anyway (Goldstein §5.7), so prescribing it must
    # leave the motion unchanged with zero drive moment; on an asymmetric body it is held.
    m, l, grav = 1.0, 0.1, 9.81
    J = np.diag([0.012, 0.012, 0.004])
    Omega0 = np.array([0.5, -0.3, 60.0])
    q0 = crv_from_rotation_vector(np.array([0.4, 0.1, 0.0]))
    args = dict(pivot=True, rho=(0, 0, l), gravity=(0, 0, -grav), radius=l)
    free = integrate(RigidBody(m, J, **args), 0.0, 1.0, q0, Omega0, fixed(1e-4))
    drives = []
    driven = RigidBody(m, J, spin=60.0, **args)
    forced = integrate(driven, 0.0, 1.0, q0, Omega0, fixed(1e-4),
                       on_step=lambda t, q, v, a: drives.append(driven.drive_moment))
    np.testing.assert_allclose(forced.q, free.q, atol=1e-8)
    assert np.abs(drives).max() < 1e-8 * m * grav * l * 1e3
    J_asym = np.diag([0.010, 0.014, 0.004])
    body = RigidBody(m, J_asym, spin=60.0, **args)
    sol = integrate(body, 0.0, 1.0, q0, Omega0, fixed(1e-4))
    assert sol.v[2] == pytest.approx(60.0, abs=1e-9)
    assert abs(body.drive_moment) > 1e-4  # here the drive does work


def test_hinged_rotor_forward_whirl_frequency():
    # Rigid rotor on the viscoelastic hinge with prescribed spin Omega: small tilt whirl
    # frequencies solve J_t w^2 -/+ J_p Omega w - k_psi = 0 (Genta, Dynamics of Rotating
    # Systems, Springer 2005, §4.3, rigid rotor on an angular spring); forward whirl:
    # w_f = (J_p Omega + sqrt((J_p Omega)^2 + 4 J_t k_psi)) / (2 J_t).
    m, J_t, J_p, k_psi, spin = 2.0, 0.004, 0.007, 1e3, 300.0
    w_f = (J_p * spin + np.sqrt((J_p * spin) ** 2 + 4 * J_t * k_psi)) / (2 * J_t)
    hinge = HingeStiffness(H_u=1e7 * np.eye(3), H_psi=[k_psi, k_psi], c_G=0.0)
    body = RigidBody(m, np.diag([J_t, J_t, J_p]), hinge=hinge, spin=spin, radius=0.05)
    eps = 1e-4  # tilt [rad]: linear regime
    q0 = np.concatenate([np.zeros(3), crv_from_rotation_vector(np.array([eps, 0, 0]))])
    R0 = rot([eps, 0, 0])
    # circular forward whirl: the axis tip moves along +phi at eps * w_f
    axis0 = R0[:, 2]
    tip_vel = w_f * np.cross([0, 0, 1.0], axis0)
    omega_s = np.cross(axis0, tip_vel) + spin * axis0
    v0 = np.concatenate([np.zeros(3), R0.T @ omega_s])
    v0[5] = spin
    ts, az = [], []

    def log(t, q, v, a):
        axis = crv_to_matrix(q[3:])[:, 2]
        ts.append(t)
        az.append(np.arctan2(axis[1], axis[0]))

    T = 4 * 2 * np.pi / w_f
    integrate(body, 0.0, T, q0, v0, fixed(T / 4000), on_step=log)
    rate = np.polyfit(ts, np.unwrap(az), 1)[0]
    assert rate == pytest.approx(w_f, rel=1e-4)
    # the gyroscopic split is resolved: the non-spinning frequency is far off
    assert abs(rate / np.sqrt(k_psi / J_t) - 1) > 0.5
