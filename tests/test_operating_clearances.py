"""Operating geometry (docs/model.md §2.1, M.120–M.122), cage run-out in the screen (M.123) and in
the pocket contact, and the non-guiding gap."""

from __future__ import annotations

import math

import numpy as np
import pytest

from bearingsim.dynamics.quasistatic.crush_screen import CageClearances, required_offset
from bearingsim.pipeline.scene.load import load_scene

# Expansion coefficients typed from their sources (not read from the code under test):
# AISI 52100, 11.9e-6 1/K over 0–100 °C (ASM data as tabulated for the alloy); silicon bronze
# C65500, 18.0e-6 1/K (Copper Development Association data sheet).
ALPHA_STEEL, ALPHA_BRONZE = 11.9e-6, 18.0e-6
# Table 1 of the reference paper (docs/model.md §2): outer land 166 mm, cage OD 158 + 7.42 mm,
# pocket 20.23 mm, ball 19.05 mm, inner land 150 mm, cage bore 158 - 7.42 mm.
LAND_O, CAGE_OD, POCKET, BALL, LAND_I, CAGE_BORE = 0.166, 0.16542, 0.02023, 0.01905, 0.150, 0.15058


def _clearances(scene):
    b, c = scene.operating.bearing, scene.operating.cage
    return c.guide_clearance(b), c.pocket_diameter - b.ball_diameter, c.non_guiding_clearance(b)


def test_guide_and_pocket_clearance_follow_the_closed_forms():
    """Every part at the oil's 100 °C against drawings at 20 °C: Delta C = 1/2 (alpha_race d_land
    - alpha_cage d_cage) Delta T (M.121), Delta c_p = (alpha_cage d_p - alpha_ball D) Delta T (M.122);
    the non-guiding gap by the mirror of M.121."""
    hot = load_scene("helicopter-b-given-hinge")
    cold = load_scene("helicopter-b-given-hinge", ["thermal.parts_degC=20"])
    assert hot.lubricant.temperature_degC == 100.0 and hot.temperatures.cage == 100.0
    dT = 80.0
    (C_h, cp_h, Cn_h), (C_c, cp_c, Cn_c) = _clearances(hot), _clearances(cold)
    assert C_c == pytest.approx(0.29e-3, rel=1e-9) and cp_c == pytest.approx(1.18e-3, rel=1e-9)
    assert C_h - C_c == pytest.approx(0.5 * (ALPHA_STEEL * LAND_O - ALPHA_BRONZE * CAGE_OD) * dT, rel=1e-9)
    assert cp_h - cp_c == pytest.approx((ALPHA_BRONZE * POCKET - ALPHA_STEEL * BALL) * dT, rel=1e-9)
    assert Cn_h - Cn_c == pytest.approx(0.5 * (ALPHA_BRONZE * CAGE_BORE - ALPHA_STEEL * LAND_I) * dT, rel=1e-9)
    # the guide clearance closes by 35–40 µm, the pocket clearance opens by about 10 µm
    assert -42e-6 < C_h - C_c < -35e-6 and 9e-6 < cp_h - cp_c < 12e-6


def test_a_hotter_cage_closes_the_guide_clearance_further():
    base = _clearances(load_scene("helicopter-b-given-hinge"))[0]
    hot_cage = _clearances(load_scene("helicopter-b-given-hinge", ["thermal.cage_degC=120"]))[0]
    assert hot_cage - base == pytest.approx(-0.5 * ALPHA_BRONZE * CAGE_OD * 20.0, rel=1e-9)


def test_growth_conserves_the_masses():
    hot = load_scene("helicopter-b-given-hinge")
    cold = load_scene("helicopter-b-given-hinge", ["thermal.parts_degC=20"])
    hot, cold = hot.operating, cold.operating
    assert hot.bearing.ball_mass(hot.materials.ball) == pytest.approx(cold.bearing.ball_mass(cold.materials.ball), rel=1e-12)
    assert hot.cage.mass(hot.materials.cage, hot.bearing) == pytest.approx(
        cold.cage.mass(cold.materials.cage, cold.bearing), rel=1e-12)


def test_a_scene_without_lubricant_stays_at_the_reference_temperature():
    scene = load_scene("deep-groove-209")
    assert scene.lubricant is None and scene.temperatures.inner_ring == scene.temperatures.reference
    assert scene.operating.bearing == scene.bearing


def test_bad_thermal_keys_name_key_range_and_unit():
    from bearingsim.pipeline.scene.schema import SceneError

    with pytest.raises(SceneError, match=r"thermal.cage_degC.*allowed.*degC"):
        load_scene("helicopter-b-given-hinge", ["thermal.cage_degC=900"])
    with pytest.raises(SceneError, match=r"materials.cage.thermal_expansion.*1/K"):
        load_scene("helicopter-b-given-hinge", ["materials.cage.thermal_expansion=0.5"])
    # the parts take the oil's temperature when thermal.parts_degC is not given: the same bound
    with pytest.raises(SceneError, match=r"lubricant.temperature_degC: 373 .*take the oil's temperature.*<= 350"):
        load_scene("helicopter-b-given-hinge", ["lubricant.temperature_degC=373"])
    assert load_scene("helicopter-b-given-hinge", ["lubricant.temperature_degC=373",
                                                   "thermal.parts_degC=100"]).temperatures.cage == 100.0


# --- run-out ------------------------------------------------------------------------------------
def test_run_out_swings_the_required_offset_by_its_eccentricity():
    """A pocket circle e_r off the guiding surface's centre turns with the cage: over a cage
    revolution the required offset swings between s1 - e_r - c_p/2 and s1 + e_r - c_p/2 (M.123)."""
    s1, cp, e_r = 0.73e-3, 1.18e-3, 20e-6
    clear = CageClearances(pocket=cp, guide=0.29e-3, pocket_circle_eccentricity=e_r)
    theta = np.linspace(0.0, 2 * math.pi, 721)
    e_req, _ = required_offset(s1, 2 * s1, clear, cage_angle=theta)
    assert 0.5 * (e_req.max() - e_req.min()) == pytest.approx(e_r, rel=1e-6)
    assert e_req.max() == pytest.approx(s1 + e_r - cp / 2, rel=1e-9)
    (best, worst), _ = required_offset(s1, 2 * s1, clear)
    assert (best, worst) == pytest.approx((s1 - e_r - cp / 2, s1 + e_r - cp / 2), rel=1e-9)


def test_run_out_lowers_the_screen_margin_of_case_b():
    from bearingsim.pipeline.stages.quasistatic import cage_screen, solve

    base = load_scene("helicopter-b-given-hinge")
    result = solve(base)
    plain = cage_screen(base, result)
    e_r = 30e-6
    eccentric = load_scene("helicopter-b-given-hinge", [f"cage.pocket_circle_eccentricity={e_r}"])
    e_r_hot = eccentric.operating.cage.pocket_circle_eccentricity  # grown with the cage
    screen = cage_screen(eccentric, result)
    assert screen.required_eccentricity - plain.required_eccentricity == pytest.approx(e_r_hot, rel=1e-9)
    assert plain.required_eccentricity - screen.required_eccentricity_min == pytest.approx(e_r_hot, rel=1e-9)
    assert screen.crush_margin == pytest.approx(plain.crush_margin - e_r_hot / plain.guide_clearance, rel=1e-9)


def test_pitch_errors_take_their_spread_off_the_pocket_clearance():
    from bearingsim.pipeline.stages.quasistatic import cage_screen, solve

    base = load_scene("helicopter-b-given-hinge", ["thermal.parts_degC=20"])
    errors = [0.0] * 22
    errors[3], errors[14] = 15e-6, -10e-6
    pitched = load_scene("helicopter-b-given-hinge", ["thermal.parts_degC=20", f"cage.pocket_index_errors={errors}"])
    result = solve(base)
    plain, screen = cage_screen(base, result), cage_screen(pitched, result)
    assert screen.required_eccentricity - plain.required_eccentricity == pytest.approx(12.5e-6, rel=1e-9)


def test_pitch_errors_need_one_value_a_pocket():
    from bearingsim.pipeline.scene.schema import SceneError

    with pytest.raises(SceneError, match="one per pocket"):
        load_scene("helicopter-b-given-hinge", ["cage.pocket_index_errors=[1e-6, 2e-6]"])


def test_pocket_contact_sees_the_eccentric_pocket_circle():
    """With the pocket circle e off the cage centre towards pocket 0, a ball at the shifted pocket
    centre sits on the pocket axis (delta = -(r_p - r_b)); at the nominal centre it is e off it."""
    from bearingsim.dynamics.contact.pocket import P_OUT_DELTA, pocket_contact, pocket_parameters

    r_p, e, D, dp = 0.079, 40e-6, 0.01905, 0.02023
    params = pocket_parameters(ball_diameter=D, pocket_diameter=dp, pitch_radius=r_p, effective_modulus=1.4e11,
                               restitution=0.7, friction_coefficient=0.1, pocket_circle_eccentricity=e)
    zero, eye = np.zeros(3), np.eye(3)
    for psi, centre in ((0.0, (r_p + e, 0.0, 0.0)), (0.5 * math.pi, (e, r_p, 0.0))):
        out = pocket_contact(np.array(centre), zero, zero, zero, eye, zero, zero, psi, 0.0, params)
        assert out[P_OUT_DELTA] == pytest.approx(-(dp - D) / 2, abs=1e-12)
    off = pocket_contact(np.array((e, r_p, 0.0)) - np.array((e, 0.0, 0.0)), zero, zero, zero, eye, zero, zero,
                         0.5 * math.pi, 0.0, params)
    assert off[P_OUT_DELTA] == pytest.approx(-(dp - D) / 2 + e, abs=1e-12)


# --- the non-guiding gap ------------------------------------------------------------------------
def test_screen_reports_a_cage_pushed_onto_the_inner_land():
    """A cage bore 0.1 mm larger than the inner land (radial gap 0.05 mm, 0.09 mm hot) pressed 0.13 mm off
    centre: the screen reports the inner land touching (negative gap)."""
    from bearingsim.pipeline.stages.quasistatic import cage_screen, solve

    # keep the outside diameter (158 + 7.42 mm) while the bore moves: mean and thickness together
    bore = 0.150 + 0.0001
    od = 0.16542
    scene = load_scene("helicopter-b-given-hinge", [f"cage.mean_diameter={(od + bore) / 2}",
                                                    f"cage.radial_thickness={(od - bore) / 2}"])
    result = solve(scene)
    screen = cage_screen(scene, result)
    assert screen.regime == "pressed"
    # the inner ring's land at the cage's ends z = -+w_c/2: its centre u + (theta_y, -theta_x) z
    # (small tilt); the cage sits e_req along the push direction; the gap is what is left of C_n
    ux, uy, _ = result.inner_displacement
    tx, ty = result.inner_tilt
    p = np.array([math.cos(screen.push_azimuth), math.sin(screen.push_azimuth)])
    half = 0.5 * scene.cage.width
    ends = [np.array([ux + ty * z, uy - tx * z]) for z in (-half, half)]
    C_n = 0.5 * (bore - 0.150) + 0.5 * (ALPHA_BRONZE * bore - ALPHA_STEEL * 0.150) * 80.0
    expected = C_n - max(np.linalg.norm(screen.required_eccentricity * p - c) for c in ends)
    assert screen.non_guiding_gap == pytest.approx(expected, abs=1e-7)
    assert screen.non_guiding_gap < 0.0


def test_dynamic_gap_detects_a_cage_forced_across_its_clearance():
    """A cage forced 0.35 mm off centre against a 0.29 mm non-guiding gap touches the inner land;
    the inner ring's tilt brings its land closer at the cage's ends by tilt times half the width."""
    from bearingsim.pipeline.results.non_guiding import non_guiding_gap, non_guiding_summary

    n = 5
    t = np.linspace(0.0, 4e-3, n)
    cage = np.zeros((n, 3))
    cage[:, 0] = np.array([0.0, 0.1, 0.2, 0.35, 0.1]) * 1e-3
    inner = np.zeros((n, 3))
    axis = np.tile([0.0, 0.0, 1.0], (n, 1))
    gap = non_guiding_gap(cage, inner, axis, 0.29e-3, 0.0127)
    assert gap == pytest.approx(0.29e-3 - np.abs(cage[:, 0]), abs=1e-15)
    s = non_guiding_summary(t, gap, 0.29e-3)
    assert s["non_guiding_gap_min"] == pytest.approx(-0.06e-3) and s["non_guiding_gap_min_time"] == t[3]
    assert s["non_guiding_contact_fraction"] == pytest.approx(0.2)
    tilt = 1e-3  # inner-ring axis tilted towards +x: its land moves by tilt * z at height z
    tilted = np.tile([math.sin(tilt), 0.0, math.cos(tilt)], (n, 1))
    gap_t = non_guiding_gap(np.zeros((n, 3)), inner, tilted, 0.29e-3, 0.0127)
    assert gap_t == pytest.approx(0.29e-3 - math.tan(tilt) * 0.0127, rel=1e-9)


def test_a_run_reports_the_cage_touching_the_inner_land(tmp_path):
    """A cage bore 10 µm over the inner land (parts at 20 °C, radial gap 5 µm): the inner ring's
    static offset and tilt under case b's moment close the gap at once, and the run says so."""
    import json

    from typer.testing import CliRunner

    from bearingsim.pipeline.cli.commands import app

    bore, od = 0.150 + 10e-6, 0.16542
    args = ["simulate", "helicopter-b-given-hinge", "--out", str(tmp_path / "run")]
    for o in ("thermal.parts_degC=20", "solver.duration=0.002", f"cage.mean_diameter={(od + bore) / 2}",
              f"cage.radial_thickness={(od - bore) / 2}"):
        args += ["--set", o]
    result = CliRunner().invoke(app, args)
    assert result.exit_code == 0, result.output
    summary = json.loads((tmp_path / "run" / "simulate" / "summary.json").read_text())
    assert summary["non_guiding_clearance"] == pytest.approx(5e-6, rel=1e-6)
    assert summary["non_guiding_gap_min"] < 0.0 and summary["non_guiding_contact_fraction"] > 0.5
    assert any("touches the non-guiding land" in w for w in summary["warnings"])
    assert "touches the non-guiding land" in result.output


def test_quasistatic_json_reports_operating_clearances_and_a_smaller_margin_hot(tmp_path):
    """`bearingsim quasistatic helicopter-b --json`: the screen at 100 °C has a smaller crush
    margin than the same command with every part at 20 °C, and names both clearance sets."""
    import json

    from typer.testing import CliRunner

    from bearingsim.pipeline.cli.commands import app

    def screen(*extra):
        args = ["quasistatic", "helicopter-b", "--json", "--out", str(tmp_path / f"r{len(extra)}")]
        for o in extra:
            args += ["--set", o]
        result = CliRunner().invoke(app, args)
        assert result.exit_code == 0, result.output
        return json.loads(result.stdout)["cage_screen"]

    hot, cold = screen(), screen("thermal.parts_degC=20")
    assert hot["clearances"]["temperatures_degC"]["cage"] == 100.0
    assert hot["clearances"]["guide_clearance"]["operating"] == pytest.approx(hot["guide_clearance"])
    assert hot["clearances"]["guide_clearance"]["reference"] == pytest.approx(0.29e-3, rel=1e-9)
    assert hot["crush_margin"] < cold["crush_margin"]
    assert cold["crush_margin"] == pytest.approx(hot["crush_margin_at_reference_temperature"], abs=2e-3)
