"""The ParaView files of the report stage (pipeline.render.paraview_series), opened with
pyvista as ParaView would: the motion series' time steps and fields follow a synthetic run
whose motion is known in closed form, and the land heat on the outer race integrates to the
burn-zone energy it was drawn from."""

from __future__ import annotations

import math

import numpy as np
import pytest

from bearingsim.pipeline.render.burn_zone_data import BurnZoneMap, RaceProfile
from bearingsim.pipeline.render.paraview_series import frame_indices, write_paraview
from bearingsim.pipeline.results.timeseries import Series, write_timeseries
from bearingsim.pipeline.scene.load import load_scene

pv = pytest.importorskip("pyvista")

N, FRAMES = 201, 20
WHIRL, ORBIT = 500.0, 1e-4  # rad/s, m: the cage centre circles the origin
CAGE_SPEED, INNER_SPEED = 140.0, 320.0  # rad/s
HEAT = {57: 2.0, 200: 1.0}  # J per 1° sector of the land (sector index: energy)


def synthetic_run(scene, path):
    """A 10 ms run: the cage centre on a circle of radius ORBIT at WHIRL, the cage turning at
    CAGE_SPEED, the inner race displaced and spinning at INNER_SPEED, balls at rest on the
    pitch circle carrying 3000 N at their outer contact."""
    Z = scene.operating.bearing.ball_count
    t = np.linspace(0.0, 0.01, N)
    T, V, B = ("time",), ("time", "xyz"), ("time", "ball")
    cage_xyz = np.c_[ORBIT * np.cos(WHIRL * t), ORBIT * np.sin(WHIRL * t), np.zeros(N)]
    cage_v = np.c_[-ORBIT * WHIRL * np.sin(WHIRL * t), ORBIT * WHIRL * np.cos(WHIRL * t), np.zeros(N)]
    psi = np.arange(Z) * 2 * math.pi / Z
    r = 0.5 * scene.operating.bearing.pitch_diameter
    balls = np.broadcast_to(np.c_[r * np.cos(psi), r * np.sin(psi), np.zeros(Z)], (N, Z, 3)).copy()
    series = {
        "time": Series(t, "s", "time", T),
        "balls/position": Series(balls, "m", "ball centres", ("time", "ball", "xyz")),
        "balls/velocity": Series(np.zeros((N, Z, 3)), "m/s", "ball velocities", ("time", "ball", "xyz")),
        "contacts/outer_load": Series(np.full((N, Z), 3000.0), "N", "outer load", B),
        "pocket/force": Series(np.full((N, Z), 5.0), "N", "pocket force", B),
        "cage/position": Series(cage_xyz, "m", "cage centre", V),
        "cage/velocity": Series(cage_v, "m/s", "cage velocity", V),
        "cage/angular_velocity": Series(np.tile([0.0, 0.0, CAGE_SPEED], (N, 1)), "rad/s", "cage omega", V),
        "cage/speed": Series(np.full(N, CAGE_SPEED), "rad/s", "cage speed", T),
        "cage_race/force": Series(np.tile([30.0, -40.0], (N, 1)), "N", "land force", ("time", "xy")),
        "cage_race/eccentricity_ratio": Series(np.full(N, ORBIT / 2.9e-4), "-", "eps", T),
        "inner_race/position": Series(np.tile([1e-5, 0.0, 3e-4], (N, 1)), "m", "inner race", V),
        "inner_race/velocity": Series(np.zeros((N, 3)), "m/s", "inner race velocity", V),
        "inner_race/axis": Series(np.tile([0.0, 0.0, 1.0], (N, 1)), "-", "axis", V),
        "inner_race/angular_velocity": Series(np.tile([0.0, 0.0, INNER_SPEED], (N, 1)), "rad/s", "omega", V),
    }
    write_timeseries(path, series)
    return t, cage_xyz, cage_v


def burn_map(scene) -> BurnZoneMap:
    energy = np.zeros(360)
    for sector, joules in HEAT.items():
        energy[sector] = joules
    return BurnZoneMap(RaceProfile.from_scene(scene.operating.bearing, scene.operating.cage), energy, None,
                       np.zeros((360, 8)), np.linspace(-0.5, 0.5, 9), 0.0, metal_energy=energy,
                       film_energy=np.zeros(360), window=(0.005, 0.01))


@pytest.fixture(scope="module")
def written(tmp_path_factory):
    scene = load_scene("helicopter-b")
    out = tmp_path_factory.mktemp("paraview")
    t, cage_xyz, cage_v = synthetic_run(scene, out / "timeseries.h5")
    files = write_paraview(out / "timeseries.h5", scene, out / "paraview", FRAMES, burn_map(scene))
    return scene, out / "paraview", files, t, cage_xyz, cage_v


def test_frame_indices_keep_first_and_last_and_at_most_the_count():
    keep = frame_indices(N, FRAMES)
    assert keep[0] == 0 and keep[-1] == N - 1 and len(keep) == FRAMES
    assert np.all(np.diff(keep) > 0)
    np.testing.assert_array_equal(frame_indices(5, FRAMES), np.arange(5))  # fewer samples: all


def test_motion_series_have_the_frames_times_and_fields(written):
    scene, out, files, t, cage_xyz, cage_v = written
    assert set(files) == {"balls", "cage", "inner_race", "outer_race"}
    keep = frame_indices(N, FRAMES)
    for body in ("balls", "cage", "inner_race"):
        reader = pv.PVDReader(str(out / files[body]))
        np.testing.assert_allclose(reader.time_values, t[keep], rtol=1e-8, atol=0.0)

    reader = pv.PVDReader(str(out / files["cage"]))
    k = 7
    reader.set_active_time_value(reader.time_values[k])
    cage = reader.read()[0]
    i = keep[k]
    # the ring's points are spread evenly round its axis: their mean is the cage centre
    np.testing.assert_allclose(np.asarray(cage.points, float).mean(axis=0)[:2], cage_xyz[i, :2], atol=2e-8)
    # rigid-body velocity v + omega x r at every point (omega along +z)
    arm = np.asarray(cage.points, float) - cage_xyz[i]
    expected = cage_v[i] + np.cross([0.0, 0.0, CAGE_SPEED], arm)
    np.testing.assert_allclose(cage.point_data["velocity"], expected, rtol=1e-5, atol=1e-6)
    np.testing.assert_allclose(cage.field_data["land_force"][0], [30.0, -40.0, 0.0])
    assert "velocity=m/s" in list(cage.field_data["units"])

    reader = pv.PVDReader(str(out / files["balls"]))
    reader.set_active_time_value(reader.time_values[-1])
    balls = reader.read()[0]
    assert balls.n_points == scene.operating.bearing.ball_count
    np.testing.assert_allclose(balls.point_data["outer_load"], 3000.0)
    np.testing.assert_allclose(balls.point_data["pocket_force"], 5.0)
    np.testing.assert_allclose(balls.point_data["diameter"], scene.operating.bearing.ball_diameter, rtol=1e-7)
    assert {"outer_load=N", "velocity=m/s"} <= set(balls.field_data["units"])
    radius = np.hypot(balls.points[:, 0], balls.points[:, 1])
    np.testing.assert_allclose(radius, 0.5 * scene.operating.bearing.pitch_diameter, rtol=1e-6)

    reader = pv.PVDReader(str(out / files["inner_race"]))
    reader.set_active_time_value(reader.time_values[3])
    inner = reader.read()[0]
    arm = np.asarray(inner.points, float) - [1e-5, 0.0, 3e-4]
    np.testing.assert_allclose(inner.point_data["velocity"], np.cross([0.0, 0.0, INNER_SPEED], arm),
                               rtol=1e-5, atol=1e-6)


def test_land_heat_on_the_outer_race_integrates_to_the_burn_zone_energy(written):
    scene, out, files, *_ = written
    race = pv.read(str(out / files["outer_race"]))
    heat = np.asarray(race.cell_data["land_heat"], float)
    area = np.asarray(race.compute_cell_sizes(length=False, volume=False).cell_data["Area"], float)
    # J/m² × m² summed over the land: the map's 3 J (flat quads on the 1° chords: rel. 1.3e-5)
    assert float(np.sum(heat * area)) == pytest.approx(sum(HEAT.values()), rel=1e-4)
    # the heat lies in the sectors it came from, on the land (not in the groove)
    centres = race.cell_centers().points
    hot = heat > 0.0
    sectors = np.floor(np.degrees(np.arctan2(centres[hot, 1], centres[hot, 0])) % 360.0).astype(int)
    assert set(sectors) == set(HEAT)
    profile = RaceProfile.from_scene(scene.operating.bearing, scene.operating.cage)
    z = np.abs(centres[hot, 2])
    assert z.min() > profile.z_land(1) and z.max() < profile.cage_half_width
    assert "land_heat=J/m2" in list(race.field_data["units"])
    np.testing.assert_allclose(race.cell_data["land_heat_metal"], heat)
