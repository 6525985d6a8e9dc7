"""Quasi-static bearing solver (docs/model.md §10): references, limits, invariants, contract."""

import json
import math
from dataclasses import replace

import numpy as np
import pytest
from scipy.optimize import brentq

from bearingsim.dynamics.geometry import BearingGeometry, Material, effective_modulus
from bearingsim.dynamics.contact.hertz import hertz_exact, race_curvature
from bearingsim.dynamics.operating_point import OperatingPoint
from bearingsim.dynamics.quasistatic.options import QuasiStaticOptions
from bearingsim.dynamics.quasistatic.solver import QuasiStaticError, solve_quasistatic
from bearingsim.dynamics.quasistatic.result import initial_state
from bearingsim.dynamics.contact.race import ball_race_contact

STEEL = Material(208e9, 0.3, 7850)
HELI = BearingGeometry(0.01905, 22, 0.1584, 0.1573, 0.009753, 0.009906,
                       inner_shoulder_diameter=0.150, outer_shoulder_diameter=0.166)  # docs/model.md §2
HELI_SPEED = 3060.0 * 2 * math.pi / 60  # rad/s

# ---------------------------------------------------------------------------------------
# Reference 1: MASTA (ISO/TS 16281 calculation) results quoted as test data in
# github.com/minzhun/ISO16281, Test_BallBearing.py (commit 1b0e9de): deep-groove bearing,
# Z = 7, D_w = 11.5 mm, D_pw = 43.5 mm, r_i = 0.52 D_w, r_e = 0.53 D_w, E = 210 GPa,
# ν = 0.3, radial operating clearance s_r (diametral) 0 or 0.01 mm, loads 1000 N / 1 N·m;
# displacements from the centred position ("Delta_a_MASTA" adds half the axial play).
MASTA_STEEL = Material(210e9, 0.3, 7850)


def _masta_bearing(clearance_mm):
    return BearingGeometry.from_catalogue(11.5e-3, 7, 43.5e-3, 0.52, 0.53, clearance_mm * 1e-3)


@pytest.mark.parametrize("clearance_mm, radial, axial, key, reference_um", [
    (0.0, 1000.0, 0.0, 0, 15.1101),   # Example 1: radial, zero clearance
    (0.0, 0.0, 1000.0, 2, 133.5381),  # Example 2: axial, zero clearance
    (0.01, 1000.0, 0.0, 0, 21.223),   # Example 3: radial, with clearance
    (0.01, 0.0, 1000.0, 2, 149.1717),  # Example 4: axial, with clearance
])
def test_masta_deep_groove_radial_and_axial(clearance_mm, radial, axial, key, reference_um):
    res = solve_quasistatic(_masta_bearing(clearance_mm), MASTA_STEEL, MASTA_STEEL,
                            OperatingPoint(radial=radial, axial=axial), QuasiStaticOptions(centrifugal=False))
    # measured: within 0.006 % (exact, α-dependent k_h)
    assert res.inner_displacement[key] * 1e6 == pytest.approx(reference_um, rel=1e-3)


def test_masta_combined_load_linear_kinematics():
    # Example 5: F_r = F_a = 1000 N, s_r = 0.01 mm, tilt free: δ_r = 19.5923 µm, δ_a = 146.4603 µm.
    # ISO/TS 16281 uses small-rotation kinematics, so compare with the same ("linear").
    res = solve_quasistatic(_masta_bearing(0.01), MASTA_STEEL, MASTA_STEEL, OperatingPoint(radial=1000.0, axial=1000.0),
                            QuasiStaticOptions(centrifugal=False, kinematics="linear"))
    assert res.inner_displacement[0] * 1e6 == pytest.approx(19.5923, rel=1e-3)
    assert res.inner_displacement[2] * 1e6 == pytest.approx(146.4603, rel=1e-3)


def test_masta_pure_moment_tilt():
    # Example 6: M = 1000 N·mm, zero clearance: misalignment 3.6957 mrad (measured 0.33 % off
    # with the exact kinematics; the linear form is 1.3 % off).
    res = solve_quasistatic(_masta_bearing(0.0), MASTA_STEEL, MASTA_STEEL, OperatingPoint(moment=1.0),
                            QuasiStaticOptions(centrifugal=False))
    assert abs(res.inner_tilt[1]) * 1e3 == pytest.approx(3.6957, rel=1e-2)


# ---------------------------------------------------------------------------------------
# Reference 2: angular-contact bearing under pure thrust. With no centrifugal force every
# ball carries Q = F_a/(Z sin α) and the load–deflection relation reduces to one equation
# (Harris & Kotzalas, "Rolling Bearing Analysis" 5th ed., vol. 1, ch. 7, thrust load):
#   F_a = Z K_n (L − A)^{3/2} sin α,  L = √((A cos α°)² + (A sin α° + δ_a)²),  sin α = (A sin α° + δ_a)/L
# with K_n = (k_i^{−2/3} + k_o^{−2/3})^{−3/2}. Solved here independently with brentq.
# Bearing: the 218 angular-contact bearing of Harris' examples (D = 22.23 mm, Z = 16,
# d_m = 125.3 mm, f_i = f_o = 0.5232, α° = 40°), with k_i, k_o fixed at α = 40°.
def test_angular_contact_thrust_against_closed_form():
    D, Z, d_m, f = 22.23e-3, 16, 125.3e-3, 0.5232
    A = (2 * f - 1) * D
    alpha0 = math.radians(40.0)
    geo = BearingGeometry.from_catalogue(D, Z, d_m, f, f, 2 * A * (1 - math.cos(alpha0)))
    assert geo.free_contact_angle == pytest.approx(alpha0, rel=1e-12)
    e_eff = effective_modulus(STEEL, STEEL)
    ks = [hertz_exact(*race_curvature(alpha0, D, d_m, f * D, outer), e_eff)[2] for outer in (False, True)]
    k_n = (ks[0] ** (-2 / 3) + ks[1] ** (-2 / 3)) ** -1.5
    for thrust in (2000.0, 22250.0, 80000.0):
        def equation(delta_a):
            length = math.hypot(A * math.cos(alpha0), A * math.sin(alpha0) + delta_a)
            return Z * k_n * (length - A) ** 1.5 * (A * math.sin(alpha0) + delta_a) / length - thrust

        delta_a = brentq(equation, 0.0, 1e-3, xtol=1e-16)
        alpha = math.asin((A * math.sin(alpha0) + delta_a) / math.hypot(A * math.cos(alpha0),
                                                                       A * math.sin(alpha0) + delta_a))
        res = solve_quasistatic(geo, STEEL, STEEL, OperatingPoint(axial=thrust),
                                QuasiStaticOptions(centrifugal=False, contact_constants=tuple(ks)))
        # the solver measures from the centred position: add the axial play A sin α°
        assert res.inner_displacement[2] == pytest.approx(A * math.sin(alpha0) + delta_a, rel=1e-8)
        assert res.inner_contact_angle == pytest.approx(alpha, rel=1e-8)
        assert res.inner_load == pytest.approx(thrust / (Z * math.sin(alpha)), rel=1e-8)


# ---------------------------------------------------------------------------------------
def test_pure_axial_load_is_shared_equally():
    res = solve_quasistatic(HELI, STEEL, STEEL, OperatingPoint(axial=34000.0, inner_speed=HELI_SPEED))
    assert np.ptp(res.inner_load) <= 1e-9 * res.inner_load.mean()
    assert np.ptp(res.outer_contact_angle) <= 1e-9
    assert res.inner_tilt == pytest.approx(0.0, abs=1e-15)
    # centrifugal force m ω_c² r loads the outer contacts more (docs/model.md §10)
    f_c = HELI.ball_mass(STEEL) * res.cage_speed**2 * np.hypot(*res.ball_positions[0, :2])
    assert np.all(res.outer_load > res.inner_load)
    q_o = res.outer_load[0] * np.array([math.cos(res.outer_contact_angle[0]), math.sin(res.outer_contact_angle[0])])
    q_i = res.inner_load[0] * np.array([math.cos(res.inner_contact_angle[0]), math.sin(res.inner_contact_angle[0])])
    assert q_o - q_i == pytest.approx([f_c, 0.0], abs=1e-6 * res.inner_load[0])


def test_stribeck_limit_zero_clearance_many_balls():
    # Stribeck (1901): Q_max ≈ 4.37 F_r / Z for a zero-clearance radial ball bearing
    # (NSK technical report CAT. E728g, §5.1 eq. 4; Harris & Kotzalas vol. 1 ch. 7).
    geo = BearingGeometry.from_catalogue(0.01, 30, 0.1, 0.52, 0.52, 0.0)
    res = solve_quasistatic(geo, STEEL, STEEL, OperatingPoint(radial=10000.0), QuasiStaticOptions(centrifugal=False))
    assert res.inner_load.max() == pytest.approx(4.37 * 10000.0 / 30, rel=0.03)


def test_moment_sign_convention():
    # +M_y tilts the inner race so its groove at ψ = 0 (+x) moves to −z: with +z thrust the
    # balls on the −x side (ψ = π) close up and carry the most (derivation in quasistatic_result).
    res = solve_quasistatic(HELI, STEEL, STEEL, OperatingPoint(axial=34000.0, moment=430.0, inner_speed=HELI_SPEED))
    assert res.inner_tilt[1] > 0.0
    assert res.azimuth[np.argmax(res.inner_load)] == pytest.approx(math.pi)
    plus_x = np.cos(res.azimuth) > 0.0
    assert res.inner_load[plus_x].sum() < res.inner_load[~plus_x].sum()
    assert np.argmax(res.inner_contact_angle) == np.argmax(res.inner_load)
    assert np.all(res.inner_contact_angle > 0.0)


@pytest.mark.parametrize("kinematics", ["linear", "exact"])
def test_stiffness_is_symmetric_with_constant_hertz_constants(kinematics):
    ks = (4.8e10, 4.15e10)
    res = solve_quasistatic(HELI, STEEL, STEEL, OperatingPoint(axial=34000.0, moment=430.0, radial=2000.0),
                            QuasiStaticOptions(centrifugal=False, contact_constants=ks, kinematics=kinematics))
    k = res.stiffness
    scale = np.sqrt(np.abs(np.outer(np.diag(k), np.diag(k))))
    assert np.max(np.abs(k - k.T) / scale) < 1e-9
    assert np.all(np.linalg.eigvalsh(0.5 * (k + k.T)) > 0.0)


def test_stiffness_matches_finite_differences_of_the_solution():
    base = OperatingPoint(axial=34000.0, moment=430.0, radial=1000.0, inner_speed=HELI_SPEED)
    res = solve_quasistatic(HELI, STEEL, STEEL, base)
    compliance = np.linalg.inv(res.stiffness)
    steps = [("radial", 0, 20.0), ("axial", 2, 50.0), ("moment", 4, 1.0)]
    for name, column, h in steps:
        plus = solve_quasistatic(HELI, STEEL, STEEL, replace(base, **{name: getattr(base, name) + h}))
        minus = solve_quasistatic(HELI, STEEL, STEEL, replace(base, **{name: getattr(base, name) - h}))
        dq = np.concatenate([plus.inner_displacement - minus.inner_displacement,
                             plus.inner_tilt - minus.inner_tilt]) / (2 * h)
        assert dq == pytest.approx(compliance[:, column], rel=1e-4, abs=1e-4 * np.abs(compliance[:, column]).max())


def test_helicopter_cases_converge_within_the_hertz_ellipse():
    """Both reference moments converge without warnings, every contact ellipse stays on its
    race (positive truncation margin), and the peak pressures are of bearing steel's working
    range. (Its run time is measured by `python -m benchmarks.quasistatic`, not here.)"""
    for moment in (100.0, 430.0):
        res = solve_quasistatic(HELI, STEEL, STEEL, OperatingPoint(axial=34000.0, moment=moment, inner_speed=HELI_SPEED))
        assert res.converged and not res.warnings
        assert np.all(res.truncation_margin_inner > 0) and np.all(res.truncation_margin_outer > 0)
        assert 1.0e9 < res.max_pressure_inner.max() < 3.0e9


def test_preload_and_zero_load():
    preloaded = BearingGeometry.from_catalogue(0.01905, 22, 0.158, 0.512, 0.52, -2e-5)
    res = solve_quasistatic(preloaded, STEEL, STEEL)
    assert res.inner_displacement == pytest.approx(0.0, abs=1e-12)
    assert np.ptp(res.inner_load) < 1e-9 * res.inner_load.mean() and res.inner_load.mean() > 0
    free = solve_quasistatic(HELI, STEEL, STEEL)
    assert not free.inner_load.any()


def test_gyroscopic_friction_changes_loads_slightly():
    loads = OperatingPoint(axial=34000.0, moment=430.0, inner_speed=HELI_SPEED)
    plain = solve_quasistatic(HELI, STEEL, STEEL, loads)
    gyro = solve_quasistatic(HELI, STEEL, STEEL, loads, QuasiStaticOptions(gyroscopic=True))
    change = np.abs(gyro.outer_load - plain.outer_load).max() / plain.outer_load.max()
    assert 1e-6 < change < 0.05


def test_riding_over_the_shoulder_is_an_error():
    shallow = BearingGeometry(0.01905, 22, 0.1584, 0.1573, 0.009753, 0.009906, inner_shoulder_diameter=0.144)
    with pytest.raises(QuasiStaticError, match="shoulder"):
        solve_quasistatic(shallow, STEEL, STEEL, OperatingPoint(axial=34000.0, moment=3000.0, inner_speed=HELI_SPEED))


def test_json_contract_and_initial_state_rolls():
    res = solve_quasistatic(HELI, STEEL, STEEL, OperatingPoint(axial=34000.0, inner_speed=HELI_SPEED))
    doc = json.loads(json.dumps(res.to_json_dict()))
    assert set(doc) >= {"inner_race", "balls", "stiffness", "converged"}
    assert len(doc["balls"]) == 22 and len(doc["inner_race"]["tilt"]) == 2
    assert set(doc["balls"][0]) >= {"azimuth", "inner_load", "outer_load", "inner_contact_angle",
                                    "outer_contact_angle"}
    state = initial_state(res)
    # velocities from pure rolling: the controlling (outer) contact has no sliding and the
    # inner one slides only by the spin the race control implies (≪ the rolling speed)
    k = 3
    args = (state["ball_positions"][k], state["ball_velocities"][k], state["ball_angular_velocities"][k])
    outer = ball_race_contact(*args, np.zeros(3), np.eye(3), np.zeros(3), np.zeros(3),
                              HELI.outer_groove_center_diameter, HELI.outer_groove_radius, HELI.ball_diameter, True)
    inner = ball_race_contact(*args, np.append(res.inner_displacement[:2], res.inner_displacement[2]),
                              state["inner_race_rotation"], np.zeros(3), state["inner_race_angular_velocity"],
                              HELI.inner_groove_center_diameter, HELI.inner_groove_radius, HELI.ball_diameter, False)
    for contact in (outer, inner):
        assert contact["slide_roll_ratio"] < 2e-3  # contact point at D/2 − δ/2 vs D/2 in the kinematics
    assert abs(outer["spin"]) < 1e-6 * np.linalg.norm(state["ball_angular_velocities"][k])
    assert state["cage_angular_speed"] == pytest.approx(0.5 * HELI_SPEED * (1 - 0.01905 * math.cos(
        res.inner_contact_angle[0]) / HELI.pitch_diameter), rel=2e-3)
