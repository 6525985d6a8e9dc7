"""Cage guidance on the outer ring's land, on the inner ring's land or by the balls, and ring
shoulders given per side of the groove (docs/model.md §7, §8; docs/scenes.md, *Ring shoulders*)."""

from __future__ import annotations

import math

import numpy as np
import pytest

import bearingsim
from bearingsim.dynamics.bearing import BearingModel, ModelOptions
from bearingsim.dynamics.bearing import layout
from bearingsim.dynamics.bearing.bundles import Body
from bearingsim.dynamics.bearing.cage_forces import journal_forces
from bearingsim.dynamics.bearing.run import initial_coordinates
from bearingsim.dynamics.contact.pocket import (P_OUT_DELTA, P_OUT_FORCE_BALL, P_OUT_IN_CONTACT, P_OUT_NORMAL,
                                                 pocket_contact, pocket_hertz_constant, pocket_parameters)
from bearingsim.dynamics.geometry import (BearingGeometry, CageGeometry, Material, contact_side,
                                          effective_modulus)
from bearingsim.dynamics.journal.short_bearing import J_OUT_FORCE, J_OUT_TORQUE, N_JOURNAL_OUT
from bearingsim.dynamics.journal.squeeze_film import N_SQUEEZE_OUT
from bearingsim.dynamics.quasistatic.solver import QuasiStaticError
from bearingsim.pipeline.quasistatic.solution import cage_screen, solve
from bearingsim.pipeline.scene.schema import SceneError
from bearingsim.pipeline.stages.simulate import build_model

from .test_bearing_model import _fd_tangents, forces

STEEL = Material(208e9, 0.3, 7850.0)  # docs/model.md §2 scene values


# --- shoulders per side -----------------------------------------------------------------
def _pair_overrides(scene_name: str) -> list[str]:
    """The scene's own shoulders written as [a, a] pairs."""
    table = bearingsim.load_scene(scene_name).raw["bearing"]
    return [f"bearing.{k}=[{table[k]}, {table[k]}]" for k in ("inner_shoulder_diameter", "outer_shoulder_diameter")
            if k in table]


@pytest.mark.parametrize("name", ["helicopter-b-given-hinge", "deep-groove-6205-ball-guided", "deep-groove-209"])
def test_an_equal_shoulder_pair_gives_exactly_the_scalar_forms_results(name):
    scalar, pair = bearingsim.load_scene(name), bearingsim.load_scene(name, _pair_overrides(name))
    assert pair.bearing.shoulders("inner") == scalar.bearing.shoulders("inner")
    a, b = solve(scalar), solve(pair)
    for field in ("inner_load", "outer_load", "inner_contact_angle", "outer_contact_angle", "stiffness",
                  "truncation_margin_inner", "truncation_margin_outer", "inner_displacement", "inner_tilt"):
        assert np.array_equal(getattr(a, field), getattr(b, field), equal_nan=True), field
    assert a.warnings == b.warnings
    if scalar.cage is None:
        return  # a quasi-static scene: no cage, no dynamic model
    assert cage_screen(scalar, a).to_json_dict() == cage_screen(pair, b).to_json_dict()
    (pa, _), (pb, _) = build_model(scalar), build_model(pair)
    for field in ("fp", "ip"):
        assert np.array_equal(getattr(pa, field), getattr(pb, field)), field
    assert pa.pocket == pb.pocket and pa.journal == pb.journal  # bundles of floats: equal to the bit


def test_the_inner_ring_carries_positive_thrust_on_its_minus_z_side():
    """An axial load on the inner race along +z pushes the inner groove's curvature centre past
    the ball's (docs/model.md §10): the inner contact then lies on the -z side of the ball centre,
    the outer one on its +z side (contact_side), as the quasi-static solution shows."""
    scene = bearingsim.load_scene("helicopter-b-given-hinge", ["load.moment=0"])
    r = solve(scene)
    z_ball, z_inner = r.ball_positions[:, 2], r.inner_displacement[2]
    assert np.all(r.inner_contact_angle > 0.0) and np.all(r.outer_contact_angle > 0.0)
    assert np.all(z_ball < z_inner) and np.all(z_ball > 0.0)  # inner contact below, outer above
    assert contact_side("inner", 0.4) == -1 and contact_side("outer", 0.4) == 1
    assert contact_side("inner", -0.4) == 1 and contact_side("outer", -0.4) == -1


def _land_diameters(bearing: BearingGeometry, ring: str, angles_deg) -> list[float]:
    """Land diameters at which the groove of `ring` meets its land `angles_deg` from the groove
    plane (the inverse of the land angle: d = 2 (R_c -/+ r cos theta))."""
    if ring == "inner":
        rc, r, sign = 0.5 * bearing.inner_groove_center_diameter, bearing.inner_groove_radius, -1.0
    else:
        rc, r, sign = 0.5 * bearing.outer_groove_center_diameter, bearing.outer_groove_radius, 1.0
    return [2.0 * (rc + sign * r * math.cos(math.radians(a))) for a in angles_deg]


def _truncated(bearing, axial: float) -> list[str]:
    from bearingsim.dynamics.operating_point import OperatingPoint
    from bearingsim.dynamics.quasistatic.solver import solve_quasistatic

    return list(solve_quasistatic(bearing, STEEL, STEEL, OperatingPoint(axial=axial)).warnings)


def test_swapping_a_high_and_a_low_shoulder_moves_the_truncation_to_the_other_thrust():
    """A 40° bearing whose lands stand 49° up the groove on one side (a low shoulder: the ellipse
    of a ~42° contact reaches past it) and 75° on the other: thrust along +z loads the inner
    ring's -z side and the outer ring's +z side, so the warning follows the low shoulders."""
    base = BearingGeometry.from_catalogue(0.0127, 14, 0.070, 0.52, 0.53, 2.97e-4)
    inner_low, inner_high = _land_diameters(base, "inner", (49.0, 75.0))
    outer_low, outer_high = _land_diameters(base, "outer", (49.0, 75.0))
    import dataclasses

    # high shoulders where +z thrust presses: inner ring's -z side, outer ring's +z side
    plus_ready = dataclasses.replace(base, inner_shoulder_diameter=(inner_low, inner_high),
                                     outer_shoulder_diameter=(outer_high, outer_low))
    swapped = dataclasses.replace(base, inner_shoulder_diameter=(inner_high, inner_low),
                                  outer_shoulder_diameter=(outer_low, outer_high))
    load = 4000.0
    assert _truncated(plus_ready, +load) == []
    assert any("truncated" in w for w in _truncated(plus_ready, -load))
    assert any("truncated" in w for w in _truncated(swapped, +load))
    assert _truncated(swapped, -load) == []
    assert any("side toward -z" in w and "inner" in w for w in _truncated(swapped, +load))


def test_a_contact_past_the_low_shoulder_is_refused_naming_its_side():
    base = BearingGeometry.from_catalogue(0.0127, 14, 0.070, 0.52, 0.53, 2.97e-4)
    import dataclasses

    low, high = _land_diameters(base, "inner", (35.0, 75.0))
    bearing = dataclasses.replace(base, inner_shoulder_diameter=(high, low))  # the low one on -z
    with pytest.raises(QuasiStaticError, match="side toward -z"):
        _truncated(bearing, 4000.0)


def test_shoulder_pairs_are_validated_per_side():
    with pytest.raises(SceneError, match="expected a list of 2 values"):
        bearingsim.load_scene("helicopter-b-given-hinge", ["bearing.outer_shoulder_diameter=[0.166, 0.167, 0.168]"])
    with pytest.raises(SceneError, match="side toward -z is not on the outer ring's land"):
        bearingsim.load_scene("helicopter-b-given-hinge", ["bearing.outer_shoulder_diameter=[0.166, 0.19]"])


def test_the_tighter_land_guides_and_equal_lands_guide_together():
    scene = bearingsim.load_scene("helicopter-b-given-hinge", ["bearing.outer_shoulder_diameter=[0.166, 0.168]"])
    both = bearingsim.load_scene("helicopter-b-given-hinge")
    b, c = scene.operating.bearing, scene.operating.cage  # what the model computes with
    b2, c2 = both.operating.bearing, both.operating.cage
    assert c.guide_sides(b) == (1,) and c2.guide_sides(b2) == (1, -1)
    assert c.guide_clearance(b) == pytest.approx(c2.guide_clearance(b2), rel=1e-12)
    assert c.guide_land_length(b) == pytest.approx(0.5 * c2.guide_land_length(b2), rel=1e-12)
    params, _ = build_model(scene)

    assert params.journal.lands == 1.0 and params.journal.length == pytest.approx(c.guide_land_length(b))


# --- the inner ring's land ----------------------------------------------------------------
def _body(x, R, v, w):
    return Body(np.asarray(x, float), np.asarray(R, float), np.asarray(v, float), np.asarray(w, float))


def test_an_inner_land_reacts_on_the_inner_race_with_the_opposite_force_and_moment():
    """Action and reaction (docs/model.md §8): the race takes -F and the moment about its own
    centre that balances the cage's torque and the force's lever, and the pair's power is what
    the film and the line contact take out of it (relative motion only)."""
    scene = bearingsim.load_scene("acbb-7210-inner-guided")
    params, _ = build_model(scene)
    C = params.guide_clearance
    cage = _body([0.9 * C, 0.3 * C, 3e-4], np.eye(3), [0.01, -0.02, 0.0], [0.0, 0.0, 270.0])
    race = _body([2e-5, -1e-5, 1e-4], np.eye(3), [0.001, 0.002, 0.0], [0.0, 0.0, 628.0])
    g = np.zeros(12)
    F_r, M_r = np.zeros(3), np.zeros(3)
    jres = np.zeros(N_JOURNAL_OUT)
    power = journal_forces(cage, race, params.journal, jres, np.zeros(N_SQUEEZE_OUT), g, 0, F_r, M_r)
    F, T = jres[J_OUT_FORCE:J_OUT_FORCE + 3], jres[J_OUT_TORQUE]
    assert np.abs(F).max() > 1e-3  # the film carries load at 0.95 C
    np.testing.assert_allclose(F_r, -F, rtol=0, atol=1e-15)
    d = cage.x - race.x
    np.testing.assert_allclose(M_r + np.array([0.0, 0.0, T]) + np.cross(d, F), 0.0, atol=1e-12 * max(abs(T), 1e-9))
    total = F @ cage.v + T * cage.w[2] + F_r @ race.v + M_r @ race.w  # power on the pair of bodies
    assert power == pytest.approx(total, rel=1e-12)
    assert power < 0.0  # the film dissipates


@pytest.fixture(scope="module")
def inner_guided():
    scene = bearingsim.load_scene("acbb-7210-inner-guided")
    params, start = build_model(scene)
    model = BearingModel(params)
    q, v = initial_coordinates(params, start)
    Z = params.ball_count
    c, o = layout.cage_offset(Z, True), layout.inner_offset(Z)
    # the cage off the inner race's centre into the film, and moving: the journal is loaded
    q[c:c + 2] = q[o:o + 2] + np.array([0.8, -0.45]) * params.guide_clearance
    v[c:c + 2] = [0.02, 0.01]
    return params, model, q, v


def _tangents(model, q, v, cols):
    n = model.n_dof
    K = model.jacobian(0.0, q, v, np.zeros(n), 0.0, 0.0, 1.0).to_dense()[:, cols]
    C = model.jacobian(0.0, q, v, np.zeros(n), 0.0, 1.0, 0.0).to_dense()[:, cols]
    return K, C


def test_inner_guided_border_tangents_agree_with_finite_differences(inner_guided):
    """The journal ties the cage to the inner race (cage_forces.journal_race_tangent): what the
    journal adds to the tangents, against what it adds to central differences of g (the model
    with the journal less the model without), in the race's force rows and the cage's force and
    spin rows, as the model's other tangents are checked (tests/test_bearing_model.py)."""
    params, model, q, v = inner_guided
    Z = params.ball_count
    c, o = layout.cage_offset(Z, True), layout.inner_offset(Z)
    cols = [o, o + 1, o + 5, c, c + 1, c + 5]
    without = BearingModel(params.without("journal"))
    (K1, C1), (K0, C0) = _tangents(model, q, v, cols), _tangents(without, q, v, cols)
    (Kf1, Cf1), (Kf0, Cf0) = _fd_tangents(model, q, v, cols), _fd_tangents(without, q, v, cols)
    rows = [o, o + 1, c, c + 1, c + 5]  # the race's force rows, the cage's force and spin rows
    assert np.abs((Kf1 - Kf0)[rows]).max() > 0.0 and np.abs((Cf1 - Cf0)[rows]).max() > 0.0
    for name, model_t, fd in (("K", K1 - K0, Kf1 - Kf0), ("C", C1 - C0, Cf1 - Cf0)):
        floor = 1e-3 * np.abs(fd[rows]).max()
        for i, col in enumerate(cols):
            scale = np.abs(fd[rows, i]).max()
            err = np.abs(model_t[rows, i] - fd[rows, i]).max()
            assert err <= 0.05 * scale + floor, f"{name} column {col}: error {err:.3e} of scale {scale:.3e}"


def test_the_inner_land_force_acts_on_the_inner_race(inner_guided):
    """g of the inner race changes by the land's reaction when the journal is on: momentum is
    exchanged between cage and inner race, not with the fixed outer race."""
    params, model, q, v = inner_guided
    Z = params.ball_count
    c, o = layout.cage_offset(Z, True), layout.inner_offset(Z)
    without = BearingModel(params.without("journal"))
    dg = forces(model, q, v) - forces(without, q, v)
    assert np.abs(dg[c:c + 2]).max() > 1e-3
    np.testing.assert_allclose(dg[o:o + 2], -dg[c:c + 2], rtol=1e-9, atol=1e-12)


# --- ball guidance --------------------------------------------------------------------------
def test_a_spherical_pocket_holds_the_ball_in_every_direction():
    """A ball displaced radially in its pocket: the cylindrical pocket (radial axis) lets it slide,
    the spherical one touches it along the displacement (docs/model.md §7)."""
    D, d_p, r_p = 0.0127, 0.01305, 0.035
    e = effective_modulus(STEEL, STEEL)
    common = dict(ball_diameter=D, pocket_diameter=d_p, pitch_radius=r_p, effective_modulus=e, restitution=0.7,
                  friction_coefficient=0.1)
    ball = np.array([r_p + 0.5 * (d_p - D) + 2e-6, 0.0, 0.0])  # 2 µm past the radial play
    zero = np.zeros(3)
    out_cyl = pocket_contact(ball, zero, zero, zero, np.eye(3), zero, zero, 0.0, 0.0,
                             pocket_parameters(**common, shape="cylindrical"))
    out_sph = pocket_contact(ball, zero, zero, zero, np.eye(3), zero, zero, 0.0, 0.0,
                             pocket_parameters(**common, shape="spherical"))
    assert out_cyl[P_OUT_IN_CONTACT] == 0.0
    assert out_sph[P_OUT_IN_CONTACT] == 1.0 and out_sph[P_OUT_DELTA] == pytest.approx(2e-6, rel=1e-6)
    np.testing.assert_allclose(out_sph[P_OUT_NORMAL:P_OUT_NORMAL + 3], [1.0, 0.0, 0.0], atol=1e-12)
    assert out_sph[P_OUT_FORCE_BALL] < 0.0  # pushed back towards the pocket centre


def test_the_spherical_pocket_constant_is_hertz_for_a_ball_in_a_socket():
    """Johnson, Contact Mechanics (1985) §4.2, eq. (4.23): F = (4/3) E* R^1/2 delta^3/2 with
    1/R = 1/R_ball - 1/R_socket and 1/E* = 2/E'."""
    D, d_p = 0.0127, 0.01305
    e = effective_modulus(STEEL, Material(8e9, 0.35, 1350.0))
    kappa, k_h = pocket_hertz_constant(D, d_p, e, "spherical")
    R = 1.0 / (2.0 / D - 2.0 / d_p)
    assert kappa == 1.0
    assert k_h == pytest.approx(4.0 / 3.0 * (0.5 * e) * math.sqrt(R), rel=1e-12)


def test_a_ball_guided_cage_has_no_land_and_needs_spherical_pockets():
    scene = bearingsim.load_scene("deep-groove-6205-ball-guided")
    assert scene.cage.guide_ring is None and scene.cage.pocket_form == "spherical"
    params, _ = build_model(scene)
    from bearingsim.dynamics.bearing.params import IP_JOURNAL

    assert params.ip[IP_JOURNAL] == 0
    op = scene.operating
    assert params.guide_clearance == pytest.approx(0.5 * (op.cage.pocket_diameter - op.bearing.ball_diameter))
    with pytest.raises(SceneError, match="cannot hold the cage radially"):
        bearingsim.load_scene("deep-groove-6205-ball-guided", ["cage.pocket_shape=cylindrical"])


def test_the_cage_geometry_names_what_guides_it():
    b = BearingGeometry(0.01905, 22, 0.1584, 0.1573, 0.009753, 0.009906, inner_shoulder_diameter=0.150,
                        outer_shoulder_diameter=0.166)
    cage = dict(mean_diameter=0.158, pocket_diameter=0.02023, radial_thickness=0.00742, width=0.0254)
    outer, inner, ball = (CageGeometry(**cage, guidance=g) for g in ("outer", "inner", "ball"))
    assert outer.guide_clearance(b) == pytest.approx(0.5 * (0.166 - 0.16542))
    assert inner.guide_clearance(b) == pytest.approx(0.5 * (0.15058 - 0.150))
    assert ball.guide_clearance(b) == pytest.approx(0.5 * (0.02023 - 0.01905))
    assert outer.non_guiding_clearance(b) == pytest.approx(inner.guide_clearance(b))
    assert ball.non_guiding_clearance(b) == pytest.approx(min(inner.guide_clearance(b), outer.guide_clearance(b)))


# --- the physically expected sense -----------------------------------------------------------
OUTER_VARIANT = ["cage.guidance=outer", "cage.mean_diameter=0.07145"]  # the same cage, OD 0.25 mm off the outer land


def _land_torque(tmp_path, overrides):
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # 40 ms is far too short to settle, and says so
        run = bearingsim.run("acbb-7210-inner-guided", tmp_path, ["simulate"],
                             overrides=["solver.duration=0.04", "output.figures=false", *overrides])
    scene = bearingsim.load_scene("acbb-7210-inner-guided", overrides)
    series = run.timeseries(["cage_race/torque", "cage/speed"])
    t = run.timeseries("time")["time"].values
    return scene, t, series["cage_race/torque"].values, series["cage/speed"].values


def test_an_inner_land_drives_the_cage_and_an_outer_land_brakes_it(tmp_path):
    """The land film's shear torque on the cage opposes its speed relative to the land (M.85): the
    inner ring turns faster than the cage and drags it forward, the fixed outer ring holds it back.
    Each mean over 25–40 ms of a run lies between the concentric (Petroff) torque
    2 pi mu |omega_cage - omega_land| R^3 L / C' and three times it (the film's eccentricity factor
    (2 + eps)/((1 + eps) sqrt(1 - eps^2)) / 2 is 2.2 at eps 0.8)."""
    results = {}
    for name, overrides in (("inner", []), ("outer", OUTER_VARIANT)):
        scene, t, torque, speed = _land_torque(tmp_path / name, overrides)
        late = t >= 0.025  # past the start-up (its torque peaks at five times the settled one)
        c, b = scene.operating.cage, scene.operating.bearing
        land_speed = scene.speed.inner if name == "inner" else 0.0
        petroff = (2 * math.pi * scene.lubricant.eta0 * abs(np.mean(speed[late]) - land_speed)
                   * (0.5 * c.guide_land_diameter(b)) ** 3 * c.guide_land_length(b)
                   / (c.guide_clearance(b) * (1 + scene.physics.cage_race_boundary)))
        results[name] = (float(np.mean(torque[late])), petroff, torque)
    inner, outer = results["inner"], results["outer"]
    assert np.all(inner[2] > 0.0) and np.all(outer[2] < 0.0)
    for mean, petroff, _ in (inner, outer):
        assert petroff < abs(mean) < 3.0 * petroff, (mean, petroff)
