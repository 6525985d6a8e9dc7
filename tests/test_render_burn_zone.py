"""Burn-zone data (sector energy, contact tracks) and its renders, on synthetic data."""

from __future__ import annotations

import math

import numpy as np
import pytest

from bearingsim.pipeline.render.burn_zone_data import (
    BurnZoneMap,
    RaceProfile,
    _band_cdf,
    contact_track_density,
    race_contact_points,
    race_semi_major_axis,
    sector_energy,
)
from bearingsim.pipeline.scene.load import load_scene

SCENE = load_scene("helicopter-b-given-hinge", ["thermal.parts_degC=20"])  # Table 1 as drawn


@pytest.fixture(scope="module")
def profile() -> RaceProfile:
    return RaceProfile.from_scene(SCENE.bearing, SCENE.cage)


def test_land_geometry_of_reference_bearing(profile):
    # docs/model.md §2: the outer groove meets the land diameter 166 mm at ±8.90 mm from the
    # groove plane; the cage (25.4 mm wide) overlaps each land by ≈ 3.80 mm, L ≈ 7.6 mm.
    assert profile.z_land(1) == pytest.approx(8.90e-3, abs=5e-6) and profile.z_land(-1) == profile.z_land(1)
    assert profile.land_overlap == pytest.approx(7.6e-3, abs=5e-6)
    # second method: the journal length the dynamics uses
    assert profile.land_overlap == pytest.approx(SCENE.cage.guide_land_length(SCENE.bearing), rel=1e-12)


def test_contact_point_lies_on_groove_normal_through_ball_centre(profile):
    """docs/model.md §6.1: the contact is on the line from the groove curvature centre through
    the ball centre, at distance r_o from the centre."""
    rng = np.random.default_rng(1)
    phi_b = rng.uniform(-math.pi, math.pi, 50)
    rho_b = profile.groove_center_radius + rng.uniform(0.2e-3, 0.5e-3, 50)
    z_b = rng.uniform(-0.3e-3, 0.3e-3, 50)
    xyz = np.column_stack([rho_b * np.cos(phi_b), rho_b * np.sin(phi_b), z_b])
    alpha = np.arctan2(z_b, rho_b - profile.groove_center_radius)  # tan α = Ẑ/(ρ − d_o/2)
    phi, radius, z = race_contact_points(xyz, alpha, profile)
    assert np.allclose(phi, np.mod(phi_b, 2 * math.pi))
    to_contact = np.column_stack([radius - profile.groove_center_radius, z])
    to_ball = np.column_stack([rho_b - profile.groove_center_radius, z_b])
    assert np.allclose(np.linalg.norm(to_contact, axis=1), profile.groove_radius, rtol=1e-12)
    cross = to_contact[:, 0] * to_ball[:, 1] - to_contact[:, 1] * to_ball[:, 0]
    assert np.allclose(cross, 0.0, atol=1e-15) and np.all(np.sum(to_contact * to_ball, axis=1) > 0)


def test_sector_energy_is_friction_power_times_time():
    # constant power P over T at one azimuth: that sector holds P T exactly (∫P dt)
    t = np.linspace(0.0, 0.02, 201)
    energy = sector_energy(t, np.full(t.size, math.radians(123.4)), np.full(t.size, 250.0), 360)
    assert energy[123] == pytest.approx(250.0 * 0.02, rel=1e-12)
    assert energy.sum() == pytest.approx(energy[123], rel=1e-12)
    # a linear ramp P = c t is integrated exactly by the trapezoid weights: c T²/2
    e2 = sector_energy(t, np.linspace(0, 2 * math.pi, t.size, endpoint=False), 1e4 * t, 36)
    assert e2.sum() == pytest.approx(1e4 * 0.02**2 / 2, rel=1e-12)


def test_burn_zone_map_holds_land_heat_of_the_settled_window_only(profile):
    """A rub at 40.5° in the start-up (t < 4 ms), the film dissipating 2 W at eps 0.9 towards
    40.5° all run long; the map from t = 5 ms holds film heat only, peaking at the offset,
    and the raceway tracks of the settled window only."""
    from bearingsim.pipeline.render.burn_zone_data import burn_zone_map
    from bearingsim.pipeline.results.timeseries import Series

    t = np.linspace(0.0, 0.01, 201)
    n, az = t.size, math.radians(40.5)
    rho = profile.groove_center_radius + 0.4e-3
    series = {name: Series(data, "", "") for name, data in {
        "time": t,
        "balls/position": np.tile([[[rho, 0.0, 0.0]]], (n, 1, 1)),
        "contacts/outer_contact_angle": np.zeros((n, 1)),
        "contacts/outer_load": np.full((n, 1), 1000.0),
        "cage_race/friction_power": np.where(t < 4e-3, 100.0, 0.0),
        "cage_race/film_power": np.full(n, 2.0),
        "cage_race/eccentricity_ratio": np.full(n, 0.9),
        "cage_race/contact_azimuth": np.full(n, az),
    }.items()}
    bzm = burn_zone_map(series, profile, start=5e-3, land_boundary=0.05, startup_metal_energy=0.4)
    assert bzm.metal_energy.sum() == 0.0
    assert bzm.film_energy.sum() == pytest.approx(2.0 * 5e-3, rel=1e-12)
    np.testing.assert_array_equal(bzm.sector_energy, bzm.metal_energy + bzm.film_energy)
    assert bzm.peak_sector == 40 and bzm.window == (5e-3, 0.01)
    assert bzm.track_density.sum() == pytest.approx(1000.0 * 5e-3, rel=1e-12)  # load x settled time
    whole = burn_zone_map(series, profile, land_boundary=0.05)  # no window: the whole run
    assert whole.metal_energy.sum() == pytest.approx(100.0 * 5e-5 * 79.5, rel=1e-12)
    assert whole.film_energy.sum() == pytest.approx(2.0 * 0.01, rel=1e-12)


def test_unrolled_map_draws_both_heat_layers(profile, tmp_path):
    from bearingsim.pipeline.render.burn_zone import heat_caption, render_burn_zone_map

    base = _map(profile, 30.0)
    film = np.full(360, 0.1)
    metal = base.sector_energy.copy()
    bzm = BurnZoneMap(profile, metal + film, base.sector, base.track_density, base.track_alpha_edges, 0.0,
                      metal, film, (0.05, 0.8), 1.5)
    render_burn_zone_map(bzm, tmp_path / "m.png", "layers")
    assert _png(tmp_path / "m.png").std() > 0.05
    caption = heat_caption(bzm)
    assert "metal friction 3 J" in caption and "film shear 36 J" in caption and "0.05–0.8 s" in caption
    assert "start-up metal energy 1.5 J not shown" in caption


def _one_contact(profile, alpha, load=1000.0, semi_axis=None, n=11):
    t = np.linspace(0.0, 1e-3, n)
    rho = profile.groove_center_radius + 0.4e-3
    xyz = np.tile([[[rho * math.cos(0.3), rho * math.sin(0.3), 0.0]]], (n, 1, 1))
    a = None if semi_axis is None else np.full((n, 1), semi_axis)
    return contact_track_density(t, xyz, np.full((n, 1), alpha), np.full((n, 1), load), profile, a)


def test_track_density_conserves_load_time_and_truncates_at_land_edge(profile):
    a = 2.5e-3
    density, edges, outside = _one_contact(profile, math.radians(30.0), semi_axis=a)
    assert density.sum() == pytest.approx(1000.0 * 1e-3, rel=1e-12)  # Q × T, all inside
    assert outside == 0.0
    assert np.nonzero(density.sum(axis=1))[0].tolist() == [int(0.3 / (2 * math.pi) * 360)]
    # the band spans alpha ± a/r_o: it must cover about 2a/r_o / bin width bins
    bins = np.count_nonzero(density.sum(axis=0))
    width = edges[1] - edges[0]
    assert abs(bins - 2 * a / profile.groove_radius / width) <= 2
    # ellipse centred on the land edge: by symmetry half of it rides over the land
    _, _, half_out = _one_contact(profile, profile.alpha_limits[1], semi_axis=a)
    assert half_out == pytest.approx(0.5, abs=1e-9)
    # centre a/2 inside the edge: outside share 1 - F(1/2), F(u) = (2 + 3u - u^3)/4 is the
    # integral of the Hertz line load across the ellipse, (3/4)(1 - u^2) (pressure
    # p0 sqrt(1 - x²/b² - y²/a²), Harris & Kotzalas, Rolling Bearing Analysis, 5th ed.,
    # vol. 1, ch. 6, integrated over x): 1 - 27/32 = 5/32
    _, _, part = _one_contact(profile, profile.alpha_limits[1] - 0.5 * a / profile.groove_radius, semi_axis=a)
    assert part == pytest.approx(5.0 / 32.0, rel=1e-9)
    assert _band_cdf(np.array([-1.0, 0.0, 1.0])).tolist() == [0.0, 0.5, 1.0]


def test_point_track_and_unloaded_balls(profile):
    density, edges, _ = _one_contact(profile, math.radians(-12.0))
    k = np.nonzero(density.sum(axis=0))[0]
    assert k.size == 1 and edges[k[0]] <= math.radians(-12.0) < edges[k[0] + 1]
    empty, _, out = _one_contact(profile, math.radians(20.0), load=0.0, semi_axis=2e-3)
    assert empty.sum() == 0.0 and out == 0.0


def test_semi_axis_table_matches_direct_hertz_solution():
    """Two methods: interpolated α-table of exact constants vs the direct exact solve."""
    from bearingsim.dynamics.geometry import effective_modulus
    from bearingsim.dynamics.contact.hertz import hertz_exact, race_curvature

    b, m = SCENE.bearing, SCENE.materials
    alpha = np.radians([12.0, 25.43, 31.7, 40.0])
    load = np.array([500.0, 1500.0, 3000.0, 6000.0])
    a = race_semi_major_axis(b, m.ball, m.race, alpha, load)
    e_eff = effective_modulus(m.ball, m.race)
    for k in range(alpha.size):
        sum_rho, f_rho = race_curvature(alpha[k], b.ball_diameter, b.pitch_diameter, b.outer_groove_radius, True)
        c_a = hertz_exact(sum_rho, f_rho, e_eff)[3]
        assert a[k] == pytest.approx(c_a * load[k] ** (1 / 3), rel=1e-5)


# --- renders ---------------------------------------------------------------------------

def _map(profile, peak_deg: float, side_deg: int | None = None) -> BurnZoneMap:
    energy = np.zeros(360)
    energy[int(peak_deg)] = 2.0
    energy[int(peak_deg) + 1] = 1.0
    if side_deg is not None:  # an unmarked secondary rub: only its colour shows it
        energy[side_deg] = 1.5
    tracks = np.zeros((360, 96))
    tracks[:, 60:64] = 5.0
    edges = np.linspace(*profile.alpha_limits, 97)
    start = math.radians(int(peak_deg))
    return BurnZoneMap(profile, energy, (start, start + math.radians(2)), tracks, edges, 0.0)


def test_camera_faces_the_loaded_half_of_the_groove(profile):
    from bearingsim.pipeline.render.burn_zone import camera_side

    upper, lower = _map(profile, 30.0), _map(profile, 30.0)
    lower.track_density[:] = upper.track_density[:, ::-1]  # mirror the tracks to z < 0
    assert camera_side(upper) == -1.0 and camera_side(lower) == 1.0  # look from the other side


def _png(path):
    import matplotlib.image as mpimg

    return mpimg.imread(path)[..., :3]


def test_unrolled_map_differs_where_the_data_differ(profile, tmp_path):
    from bearingsim.pipeline.render.burn_zone import render_burn_zone_map

    box = render_burn_zone_map(_map(profile, 30.0, 90), tmp_path / "a.png", "a")["box_px"]
    render_burn_zone_map(_map(profile, 200.0, 250), tmp_path / "b.png", "a")
    a, b = _png(tmp_path / "a.png"), _png(tmp_path / "b.png")
    assert a.shape == b.shape and a.std() > 0.05  # not blank
    left, top, right, bottom = box

    def pixel(img, az_deg, z):
        col = int(left + (az_deg / 360.0) * (right - left))
        row = int(bottom - (z + profile.half_width) / (2 * profile.half_width) * (bottom - top))
        return img[row, col]

    z_land = 0.5 * (profile.z_land(1) + profile.cage_half_width)  # middle of a land overlap band
    black = np.zeros(3)  # inferno at 0
    for az, img in ((90.5, a), (250.5, b)):  # the secondary rub: coloured on both lands
        for z in (z_land, -z_land):
            assert np.abs(pixel(img, az, z) - black).max() > 0.3
            assert np.abs(pixel(a, az, z) - pixel(b, az, z)).max() > 0.3
    for az in (30.5, 200.5):  # the peak moved (marked cyan): both places change
        assert np.abs(pixel(a, az, z_land) - pixel(b, az, z_land)).max() > 0.3
    for az in (100.5, 300.5):  # no data changed there: same pixels
        assert np.abs(pixel(a, az, z_land) - pixel(b, az, z_land)).max() < 1e-6
        assert np.abs(pixel(a, az, -z_land) - pixel(b, az, -z_land)).max() < 1e-6


def test_3d_render_is_not_blank_and_changes_with_the_data(profile, tmp_path):
    from bearingsim.pipeline.render.burn_zone import render_burn_zone_3d

    render_burn_zone_3d(_map(profile, 30.0), tmp_path / "a.png", "a")
    render_burn_zone_3d(_map(profile, 30.0), tmp_path / "a2.png", "a")
    render_burn_zone_3d(_map(profile, 200.0), tmp_path / "b.png", "a")
    a, a2, b = _png(tmp_path / "a.png"), _png(tmp_path / "a2.png"), _png(tmp_path / "b.png")
    assert a.std() > 0.05 and (a < 0.9).mean() > 0.05  # something drawn, not a white page
    assert np.array_equal(a, a2)  # fixed camera and colour range: reproducible
    changed = np.abs(a - b).max(axis=2) > 0.1
    assert 1e-4 < changed.mean() < 0.2  # the burn moved; most of the picture did not
