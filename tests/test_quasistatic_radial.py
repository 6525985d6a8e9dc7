"""Quasi-static solver under mostly radial loads on a free inner race (docs/model.md §10, M.119).

An inner race free to tilt under a mostly radial load with a light axial load pivots about its
loaded zone with almost no stiffness: zero moment needs the first harmonic of the axial ball forces
to vanish, so the balls opposite the load must take up part of the axial load, at a tilt of a few
mrad. Newton from the rigid-ring start used to stall on the way there (a stationary point of
|residual|², not an equilibrium) and `quasistatic` exited 1. Here: the issue's command, the
equilibrium against independent routes, the force and moment balance of the reported ball loads
(computed from the result alone), Stribeck's radial load distribution, and a load grid on which
every case converges or is refused at a land (exit 2), never "Newton diverged" (exit 1).
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from scipy.optimize import root
from scipy.spatial.transform import Rotation
from typer.testing import CliRunner

from bearingsim.dynamics.geometry import BearingGeometry, Material
from bearingsim.dynamics.quasistatic import solver
from bearingsim.dynamics.operating_point import OperatingPoint
from bearingsim.dynamics.quasistatic.options import QuasiStaticOptions
from bearingsim.dynamics.quasistatic.solver import QuasiStaticError, solve_quasistatic
from bearingsim.pipeline.cli.commands import app

STEEL = Material(208e9, 0.3, 7850)
HELI = BearingGeometry(0.01905, 22, 0.1584, 0.1573, 0.009753, 0.009906,
                       inner_shoulder_diameter=0.150, outer_shoulder_diameter=0.166)  # docs/model.md §2
HELI_SPEED = 3060.0 * 2 * math.pi / 60  # rad/s, the helicopter scenes' inner-ring speed
DEEP_GROOVE_209 = BearingGeometry.from_catalogue(0.0127, 9, 0.065, 0.52, 0.52, 1.5e-5)
ISSUE_ARGS = ["--set", "load.axial=1106", "--set", "load.radial=15217", "--set", "load.moment=0"]


def balance_error(displacement, tilt, azimuth, inner_load, inner_angle, applied, inner_centre_radius):
    """(force error [N], moment error [N·m], load scale [N]) of the inner race from the reported
    ball loads alone. Each inner contact force Q n acts on the race along the line through its
    groove's curvature centre C_i = R(θ) (d_i/2) e_r(ψ) (relative to the race centre, where the
    applied force acts), n = (cos α e_r + sin α e_z) in the ball's azimuth plane."""
    psi, q, a = np.asarray(azimuth), np.asarray(inner_load), np.asarray(inner_angle)
    e_r = np.column_stack([np.cos(psi), np.sin(psi), np.zeros_like(psi)])
    force = -q[:, None] * (np.cos(a)[:, None] * e_r + np.sin(a)[:, None] * np.array([0.0, 0.0, 1.0]))
    arms = Rotation.from_rotvec([tilt[0], tilt[1], 0.0]).apply(inner_centre_radius * e_r)
    moment = np.cross(arms, force).sum(axis=0)
    f_err = np.max(np.abs(np.asarray(applied[:3]) + force.sum(axis=0)))
    m_err = np.max(np.abs(np.asarray(applied[3:]) + moment[:2]))
    scale = max(np.max(np.abs(applied[:3])), np.max(np.abs(applied[3:])) / inner_centre_radius, q.sum(), 1.0)
    return f_err, m_err, scale


def assert_balanced(res, geometry, rel=1e-7):
    f_err, m_err, scale = balance_error(res.inner_displacement, res.inner_tilt, res.azimuth, res.inner_load,
                                        res.inner_contact_angle, res.applied_load,
                                        0.5 * geometry.inner_groove_center_diameter)
    assert f_err <= rel * scale, (f_err, scale)
    assert m_err <= rel * scale * 0.5 * geometry.inner_groove_center_diameter, (m_err, scale)


def test_issue_command_exits_0_with_a_balanced_result(tmp_path):
    """`bearingsim quasistatic helicopter-b-given-hinge` at 1106 N axial, 15217 N radial, no moment."""
    result = CliRunner().invoke(app, ["quasistatic", "helicopter-b-given-hinge", "--json", "--out",
                                      str(tmp_path / "run"), *ISSUE_ARGS])
    assert result.exit_code == 0, result.output
    payload = json.loads(result.stdout)
    balls = payload["balls"]
    azimuth = [b["azimuth"] for b in balls]
    loads = np.array([b["inner_load"] for b in balls])
    angles = np.array([b["inner_contact_angle"] for b in balls])
    u, tilt = payload["inner_race"]["displacement"], payload["inner_race"]["tilt"]
    f_err, m_err, scale = balance_error(u, tilt, azimuth, loads, angles, [15217.0, 0.0, 1106.0, 0.0, 0.0], 0.0792)
    assert f_err <= 1e-7 * scale and m_err <= 1e-7 * scale * 0.0792, (f_err, m_err, scale)
    # the physics of the free race: thrust along +z, tilted so that the balls opposite the radial
    # load (ψ = 180°) take up part of the axial load; every contact inside its land (64.49°)
    assert u[2] > 1e-4 and tilt[1] > 1e-3
    opposite = int(np.argmin(np.abs(np.cos(azimuth) + 1.0)))
    assert loads[opposite] > 100.0 and 0.5 < angles[opposite] < math.radians(64.49)
    assert loads[0] == pytest.approx(loads.max()) and payload["converged"]


def _issue_problem():
    return solver._make_problem(HELI, STEEL, STEEL), np.array([15217.0, 0.0, 1106.0, 0.0, 0.0])


def test_issue_equilibrium_matches_continuation_and_an_independent_root_finder():
    """Three routes to the same equilibrium (balls at rest): the solver, the continuation from the
    axial load alone (M.119 fallback), and scipy's hybrid Powell method from a generic start."""
    res = solve_quasistatic(HELI, STEEL, STEEL, OperatingPoint(axial=1106.0, radial=15217.0),
                            QuasiStaticOptions(centrifugal=False))
    assert_balanced(res, HELI)
    q_solver = np.concatenate([res.inner_displacement, res.inner_tilt])
    problem, load = _issue_problem()
    q_path, _, _ = solver._continuation(problem, load, 1e-10, 50, 0)
    sc = solver._scale(problem)
    found = root(lambda x: (load + problem.contact(x * sc, warm=False)[0]) * sc, np.array([1e-4, 0, 1e-4, 0, 1e-4]),
                 jac=lambda x: -problem.contact(x * sc, warm=False)[1] * sc[:, None] * sc[None, :], method="hybr")
    assert found.success
    for q in (q_path, found.x * sc):
        assert np.max(np.abs((q - q_solver) / sc)) < 1e-9  # metres (tilts times d_i/2)
    # ~ (101, 0, 214) µm and 2.65 mrad: the race seats axially and pivots about the loaded zone
    assert q_solver[0] == pytest.approx(1.0095e-4, rel=1e-3) and q_solver[4] == pytest.approx(2.651e-3, rel=1e-3)


def test_rigid_ring_start_is_left_by_the_energy_line_search():
    """From the rigid-ring start (no tilt, 7 µm axial) the tangent is nearly singular along the
    pivot about the loaded zone; Newton on the energy gets through it within the iteration limit."""
    problem, load = _issue_problem()
    start = solver._initial_guess(problem, load)
    assert abs(start[4]) < 1e-9 and start[2] < 2e-5
    q, iters, ok, _ = solver._newton(problem, load, start, 1e-10, 50)
    assert ok and iters < 30 and q[4] > 2e-3


def test_stribeck_distribution_of_a_radial_load():
    """Zero clearance, pure radial load, rigid rings: ball loads Q(ψ) = Q_max cos^{3/2} ψ and
    F_r = Q_max Σ cos^{5/2} ψ_k (Stribeck 1901; Harris & Kotzalas, Rolling Bearing Analysis, 5th ed.,
    vol. 1, ch. 7), so Q_max = 4.385 F_r/Z for Z = 9 — below Stribeck's design value 5 F_r/(Z cos α)."""
    geometry = BearingGeometry.from_catalogue(0.0127, 9, 0.065, 0.52, 0.52, 0.0)
    radial = 8900.0
    res = solve_quasistatic(geometry, STEEL, STEEL, OperatingPoint(radial=radial), QuasiStaticOptions(centrifugal=False))
    assert_balanced(res, geometry)
    cos = np.clip(np.cos(res.azimuth), 0.0, None)
    q_max = radial / np.sum(cos ** 2.5)
    assert res.inner_load.max() == pytest.approx(q_max, rel=1e-6)
    assert res.inner_load == pytest.approx(q_max * cos ** 1.5, rel=1e-6, abs=1e-6 * q_max)
    assert res.inner_load.max() < 5.0 * radial / geometry.ball_count


GRID = [(axial, radial, moment) for axial in (0.0, 100.0, -1000.0, 5000.0, -20000.0)
        for radial in (0.0, 100.0, 5000.0, 30000.0) for moment in (0.0, 10.0, -100.0, 1000.0)]


@pytest.mark.parametrize("name, geometry, speed", [("helicopter", HELI, HELI_SPEED), ("helicopter at rest", HELI, 0.0),
                                                  ("deep-groove-209", DEEP_GROOVE_209, 0.0)])
def test_load_grid_converges_balanced_or_stops_at_a_land(name, geometry, speed):
    """Axial 0 to ±20 kN, radial 0 to 30 kN, moment 0 to 1000 N·m: each load converges with its
    ball loads in balance, or is refused because a loaded contact reaches a land (exit 2 in the
    command line) — never a Newton failure."""
    outcomes = []
    for axial, radial, moment in GRID:
        try:
            res = solve_quasistatic(geometry, STEEL, STEEL,
                                    OperatingPoint(axial=axial, radial=radial, moment=moment, inner_speed=speed),
                                    QuasiStaticOptions(gyroscopic=speed != 0.0))
        except QuasiStaticError as exc:
            assert "rides over the shoulder" in str(exc), (name, axial, radial, moment, str(exc))
            outcomes.append("land")
            continue
        assert_balanced(res, geometry, rel=1e-6)  # the gyroscopic friction acts at the outer race
        outcomes.append("ok")
    assert outcomes.count("ok") >= 0.9 * len(GRID), outcomes


def test_why_the_continuation_stopped_is_told_apart():
    """A continuation state with a loaded contact past the land is a load limit (the message the
    command line maps to exit 2); one inside the lands is a solver failure."""
    problem = solver._make_problem(HELI, STEEL, STEEL)
    q_past, _, _ = solver._solve_load(problem, np.array([400000.0, 0.0, 34000.0, 0.0, 0.0]), None, 1e-10, 50)
    message = str(solver._no_equilibrium(problem, q_past, 0.5, 1.0))
    assert "rides over the shoulder" in message and "50.0 % of the radial load" in message
    assert "inner land at 64.49°" in message
    problem, load = _issue_problem()
    q_inside, _, _ = solver._solve_load(problem, load, None, 1e-10, 50)
    assert "Newton diverged" in str(solver._no_equilibrium(problem, q_inside, 0.5, 1.0))


@pytest.mark.slow
def test_a_radial_load_past_the_land_exits_2_naming_the_loads(tmp_path):
    """2.4 MN radial (22 times the static rating) on the helicopter bearing: the continuation stops
    where a ball has passed the inner land; exit 2 naming the loads (about 15 s)."""
    result = CliRunner().invoke(app, ["quasistatic", "helicopter-b-given-hinge", "--json", "--out", str(tmp_path / "r"),
                                      "--set", "load.radial=2388610", "--set", "load.moment=-1.80431"])
    assert result.exit_code == 2, result.output
    assert "load.radial" in result.stderr and "load.axial" in result.stderr and "load.moment" in result.stderr
    assert "past its land" in result.stderr and "Newton diverged" not in result.stderr
