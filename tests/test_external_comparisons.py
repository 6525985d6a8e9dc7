"""Published data for bearings other than the reference one (docs/validation.md §16).

The quasi-static comparison (a 7-ball deep-groove bearing against MASTA's ISO/TS 16281 results)
is tests/test_quasistatic.py's Reference 1; benchmarks/external_comparisons.py draws it.

Here: the cage speed of the 120-mm-bore turbine bearing of NASA's high-speed tests. Published
(Bamberger, Zaretsky & Signer, "Effect of speed and load on ultra-high-speed ball bearings",
NASA TN D-7870, 1975, abstract): thrust loads to 22 240 N, speeds to 25 000 rpm; skidding
"generally increasing with speed at a given load", the highest, 6 percent, at 25 000 rpm. Skid is
1 - cage speed / cage speed of pure rolling. The scene's internal geometry is assumed
(pipeline/scenes/turbine-thrust-120.toml), so agreement is asked within a factor of two.
"""

from __future__ import annotations

import json
import math

import pytest

import bearingsim

NASA_SKID_AT_25000_RPM = 0.06  # NASA TN D-7870, abstract: the highest skid, at the highest speed


def _pure_rolling_cage_speed(scene) -> float:
    """omega_i (1 - D cos(alpha_0) / d_m) / 2, outer ring fixed (Harris & Kotzalas, Rolling Bearing
    Analysis, 5th ed., vol. 1, ch. 8)."""
    b = scene.operating.bearing
    return 0.5 * scene.speed.inner * (1.0 - b.ball_diameter * math.cos(b.free_contact_angle) / b.pitch_diameter)


def test_the_turbine_scene_is_at_the_published_operating_point():
    scene = bearingsim.load_scene("turbine-thrust-120")
    assert scene.bearing.inner_bore_diameter == pytest.approx(0.120)
    assert scene.load.axial == pytest.approx(22240.0)  # 5000 lb
    assert scene.speed.inner_rpm == pytest.approx(25000.0)  # 3 million DN
    assert math.degrees(scene.bearing.free_contact_angle) == pytest.approx(20.0, abs=0.05)


@pytest.mark.slow
@pytest.mark.xfail(strict=True, reason="the model's cage overruns pure rolling by 6.3 % where NASA measured "
                                       "6 % skid (docs/validation.md §16.2)")
def test_the_turbine_bearing_skids_as_measured_at_25000_rpm(tmp_path):
    run = bearingsim.run("turbine-thrust-120", tmp_path, ["simulate"], overrides=["output.figures=false"])
    summary = json.loads((run.stage_dir("simulate") / "summary.json").read_text(encoding="utf-8"))
    skid = 1.0 - summary["cage_speed_mean"] / _pure_rolling_cage_speed(bearingsim.load_scene("turbine-thrust-120"))
    assert 0.5 * NASA_SKID_AT_25000_RPM < skid < 2.0 * NASA_SKID_AT_25000_RPM, skid


# Case Western Reserve University Bearing Data Center, "Bearing information": drive-end bearing
# 6205-2RS JEM SKF, defect frequencies as multiples of the shaft speed; fundamental train (cage)
# frequency 0.3983
CWRU_CAGE_FACTOR = 0.3983


def _cage_factor(b, alpha_i, alpha_o):
    """omega_c / omega_i of pure rolling, outer ring fixed: (1 - gamma_i) / ((1 - gamma_i) + (1 + gamma_o)),
    gamma = D cos(alpha) / d_m (Harris & Kotzalas, Rolling Bearing Analysis, 5th ed., vol. 1, ch. 8)."""
    import numpy as np

    gi = b.ball_diameter * np.cos(alpha_i) / b.pitch_diameter
    go = b.ball_diameter * np.cos(alpha_o) / b.pitch_diameter
    return (1.0 - gi) / ((1.0 - gi) + (1.0 + go))


def test_the_6205_scene_has_the_cwru_cage_factor_and_says_where_its_load_moves_it():
    """deep-groove-6205-ball-guided against CWRU's published factor: at the zero contact angle the
    published factor assumes, its geometry gives 0.3983 to the last digit. At the quasi-static
    contact angles of its loaded balls (the scene's assumed 50 N axial load turns them by up to
    22 deg) pure rolling is 0.8 % faster, 0.4015 (docs/validation.md §15.3). CWRU publishes no
    measured cage speed, so this checks the scene's geometry and operating point, not its cage
    dynamics."""
    import numpy as np

    from bearingsim.pipeline.quasistatic.solution import solve

    scene = bearingsim.load_scene("deep-groove-6205-ball-guided")
    b = scene.operating.bearing
    assert float(_cage_factor(b, 0.0, 0.0)) == pytest.approx(CWRU_CAGE_FACTOR, abs=5e-5)
    qs = solve(scene)
    loaded = np.asarray(qs.inner_load) > 0.0
    operating = float(np.mean(_cage_factor(b, np.asarray(qs.inner_contact_angle)[loaded],
                                           np.asarray(qs.outer_contact_angle)[loaded])))
    assert loaded.sum() >= 3
    assert 1.005 < operating / CWRU_CAGE_FACTOR < 1.012
