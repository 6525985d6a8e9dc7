"""Ball–race torus–sphere contact geometry and kinematics (docs/model.md §6.1)."""

import math

import numpy as np
import pytest

from bearingsim.dynamics.contact.race import (CONTACT_OUT_SIZE, ball_race_contact, ball_race_contact_kernel,
                                   ball_race_contact_reference)

D = 0.01905
D_I, R_I = 0.1584, 0.009753  # docs/model.md §2 inner race
D_O, R_O = 0.1573, 0.009906  # outer race


def _rotation(rng):
    q, r = np.linalg.qr(rng.normal(size=(3, 3)))
    q = q * np.sign(np.diag(r))
    return q if np.linalg.det(q) > 0 else -q


def _random_case(rng, outer):
    rot = _rotation(rng)
    x_r = rng.normal(scale=1e-3, size=3)
    psi = rng.uniform(0, 2 * math.pi)
    rho = 0.079 + rng.normal(scale=2e-4)
    z = rng.normal(scale=2e-4)
    x_b = x_r + rot @ np.array([rho * math.cos(psi), rho * math.sin(psi), z])
    d, r = (D_O, R_O) if outer else (D_I, R_I)
    return (x_b, rng.normal(size=3), rng.normal(scale=300, size=3), x_r, rot, rng.normal(size=3),
            rng.normal(scale=300, size=3), d, r, D, outer)


@pytest.mark.parametrize("outer", [False, True])
def test_kernel_matches_reference_twin_on_random_inputs(outer):
    rng = np.random.default_rng(10 + outer)
    for _ in range(200):
        case = _random_case(rng, outer)
        fast, slow = ball_race_contact(*case), ball_race_contact_reference(*case)
        for key, value in slow.items():
            assert np.allclose(fast[key], value, rtol=1e-9, atol=1e-12), key


def test_kernel_py_func_agrees():
    rng = np.random.default_rng(4)
    case = _random_case(rng, False)
    a, b = np.empty(CONTACT_OUT_SIZE), np.empty(CONTACT_OUT_SIZE)
    args = tuple(np.ascontiguousarray(c, dtype=float) if isinstance(c, np.ndarray) else c for c in case)
    ball_race_contact_kernel(*args, a)
    ball_race_contact_kernel.py_func(*args, b)
    assert np.allclose(a, b, rtol=1e-14, atol=1e-15)


def test_hand_computed_inner_contact():
    # Ball centre at radius 79.0 mm, 0.2 mm below the groove plane; race centred, unrotated.
    # By hand: d_i/2 − ρ = 0.2 mm, Ẑ = −0.2 mm → s = 0.2√2 mm, δ = s + D/2 − r_i,
    # α = atan2(−Ẑ, d_i/2 − ρ) = +45°, n = (cos45°, 0, sin45°) (towards the curvature centre).
    x_b = np.array([0.0790, 0.0, -0.0002])
    out = ball_race_contact(x_b, np.zeros(3), np.zeros(3), np.zeros(3), np.eye(3), np.zeros(3), np.zeros(3),
                            D_I, R_I, D, False)
    s = 0.0002 * math.sqrt(2)
    assert out["delta"] == pytest.approx(s + D / 2 - R_I, abs=1e-15)
    assert out["alpha"] == pytest.approx(math.pi / 4, abs=1e-12)
    assert out["normal"] == pytest.approx([math.sqrt(0.5), 0.0, math.sqrt(0.5)], abs=1e-12)
    assert out["point"] == pytest.approx(x_b - (D / 2 - out["delta"] / 2) * out["normal"], abs=1e-15)
    # the outer race sees the same ball at +z of its groove plane mirrored: α_o > 0 when the
    # ball centre is above the outer curvature centre (load line carries +z thrust on the inner race)
    x_b2 = np.array([0.0790, 0.0, 0.0002])
    out_o = ball_race_contact(x_b2, np.zeros(3), np.zeros(3), np.zeros(3), np.eye(3), np.zeros(3), np.zeros(3),
                              D_O, R_O, D, True)
    assert out_o["alpha"] == pytest.approx(math.atan2(0.0002, 0.0790 - D_O / 2), abs=1e-12)
    assert out_o["normal"][0] < 0 and out_o["normal"][2] < 0


def test_pure_rolling_in_a_centred_bearing_has_no_sliding():
    # Zero-clearance grooves touching a ball at the pitch radius (α = 0). Epicyclic pure
    # rolling (Harris & Kotzalas vol. 1 ch. 8): ω_m = Ω_i (1 − D/d_m)/2, ball spin
    # ω_b = −2 ω_m ρ / D e_z (no slip at the fixed outer race). Then both contacts have zero
    # sliding; entrainment speeds relative to the contact are (Ω_i − ω_m)(ρ − D/2) (inner)
    # and ω_m (ρ + D/2) (outer), the classical rolling speeds.
    omega_i, d_m = 320.0, 0.158
    rho = 0.5 * d_m
    d_i, d_o = d_m + 2 * (R_I - D / 2), d_m - 2 * (R_O - D / 2)
    omega_m = 0.5 * omega_i * (1 - D / d_m)
    w_b = np.array([0.0, 0.0, -2 * omega_m * rho / D])
    for psi in np.linspace(0, 2 * math.pi, 7):
        e_r = np.array([math.cos(psi), math.sin(psi), 0.0])
        e_t = np.array([-math.sin(psi), math.cos(psi), 0.0])
        x_b = rho * e_r
        v_b = omega_m * rho * e_t
        inner = ball_race_contact(x_b, v_b, w_b, np.zeros(3), np.eye(3), np.zeros(3), [0, 0, omega_i],
                                  d_i, R_I, D, False)
        outer = ball_race_contact(x_b, v_b, w_b, np.zeros(3), np.eye(3), np.zeros(3), np.zeros(3),
                                  d_o, R_O, D, True)
        for out in (inner, outer):
            assert abs(out["delta"]) < 1e-15 and abs(out["alpha"]) < 1e-12
            assert np.linalg.norm(out["sliding_velocity"]) < 1e-10 * out["u_sum"]
            assert out["slide_roll_ratio"] < 1e-10
        assert inner["u_sum"] == pytest.approx(2 * (omega_i - omega_m) * (rho - D / 2), rel=1e-12)
        assert outer["u_sum"] == pytest.approx(2 * omega_m * (rho + D / 2), rel=1e-12)
        assert inner["e_x"] == pytest.approx(e_t, abs=1e-12)  # inner surfaces run ahead of the contact
        assert outer["e_x"] == pytest.approx(-e_t, abs=1e-12)
        assert inner["spin"] == pytest.approx((w_b[2] - omega_i) * inner["normal"][2], abs=1e-9)


def test_sliding_is_the_relative_surface_velocity():
    # A ball held still (v = ω = 0) against a spinning inner race slides at Ω_i × p.
    omega_i = 100.0
    x_b = np.array([0.079, 0.0, -1e-4])
    out = ball_race_contact(x_b, np.zeros(3), np.zeros(3), np.zeros(3), np.eye(3), np.zeros(3),
                            [0, 0, omega_i], D_I, R_I, D, False)
    race_velocity = np.cross([0, 0, omega_i], out["point"])
    tangential = race_velocity - (race_velocity @ out["normal"]) * out["normal"]
    assert out["sliding_velocity"] == pytest.approx(-tangential, rel=1e-12)
    assert out["slide_roll_ratio"] == pytest.approx(2.0, rel=1e-12)


def test_spin_and_frame_are_orthonormal():
    rng = np.random.default_rng(7)
    for outer in (False, True):
        out = ball_race_contact(*_random_case(rng, outer))
        frame = np.array([out["e_x"], out["e_y"], out["normal"]])
        assert np.allclose(frame @ frame.T, np.eye(3), atol=1e-12)
        assert abs(out["sliding_velocity"] @ out["normal"]) < 1e-9
