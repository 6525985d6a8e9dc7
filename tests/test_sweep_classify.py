"""Cage-motion classes from summary metrics: the rules and limits documented in
pipeline/scene/cage_classes.py (module docstring) are the reference of these tests."""

from __future__ import annotations

import math

import pytest

from bearingsim.pipeline.scene.cage_classes import CageClassThresholds, classify_cage


def summary(metal=0.0, spread=None, whirl=0.0, variation=0.003, speed=143.7, duration=0.1,
            offset_spread=None, eps_mean=None):
    s = {"duration": duration, "cage_speed_mean": speed, "cage_speed_variation": variation,
         "cage_metal_contact_fraction": metal, "cage_contact_angle_spread": spread,
         "cage_whirl_ratio": whirl}
    if offset_spread is not None:  # summaries with a settled window carry the offset keys
        s.update(cage_offset_spread=offset_spread, cage_eps_mean=eps_mean)
    return s


@pytest.mark.parametrize("metrics, expected", [
    # floating, steady, no net orbit
    (summary(), "centred"),
    # pressed on one sector of the land most of the time
    (summary(metal=0.9, spread=0.2), "crushed"),
    # limits are inclusive as documented: >= crushed_contact, <= crushed_spread
    (summary(metal=0.5, spread=0.5), "crushed"),
    # rolling round the land: metal contact everywhere, centre orbiting with the cage
    # (orbits = 1.0 * 143.7 rad/s * 0.05 s / 2 pi = 1.14 >= 1)
    (summary(metal=0.9, spread=2.5, whirl=1.0, variation=0.05), "whirling"),
    # the same motion in a run too short for one full orbit (0.57) is not called whirl
    (summary(metal=0.9, spread=2.5, whirl=1.0, variation=0.05, duration=0.05), "chaotic"),
    # whirl in the film
    (summary(whirl=0.9, variation=0.02), "whirling"),
    # a whirl with an irregular spin is not a regular whirl
    (summary(whirl=0.9, variation=0.5), "chaotic"),
    # a centre drifting across the axis in a 3 ms run: large ratio, 1.4 rad of azimuth
    (summary(whirl=-3.3, variation=0.0036, speed=282.1, duration=0.003), "centred"),
    # intermittent contact at 5 % and above is no longer centred
    (summary(metal=0.05), "chaotic"),
    (summary(metal=0.2, spread=1.5, whirl=0.1, variation=0.3), "chaotic"),
    # steady metal contact but spread over the land, no whirl
    (summary(metal=0.8, spread=1.2, whirl=0.05), "chaotic"),
    # irregular speed without contact
    (summary(variation=0.06), "chaotic"),
    # pushed onto one sector through its film: the offset stays in one direction at eps >= 0.6
    (summary(offset_spread=0.2, eps_mean=0.85), "pressed"),
    (summary(offset_spread=0.5, eps_mean=0.6), "pressed"),  # limits inclusive
    (summary(offset_spread=0.2, eps_mean=0.5), "centred"),  # steady direction, but near the centre
    (summary(offset_spread=1.5, eps_mean=0.85, whirl=0.9, variation=0.02), "whirling"),
    # crushed first: metal contact on one sector most of the time
    (summary(metal=0.9, spread=0.2, offset_spread=0.1, eps_mean=1.02), "crushed"),
])
def test_documented_rules(metrics, expected):
    assert classify_cage(metrics) == expected


def test_not_motions():
    assert classify_cage(None) == "failed"
    no_cage = {"duration": 0.1, "steps": 10, "inner_race_axial_mean": 1e-4}  # simulate writes no cage keys
    assert classify_cage(no_cage) == "no cage"
    # a NaN variation (cage at rest) can never be centred
    assert classify_cage(summary(variation=math.nan)) == "chaotic"


def test_thresholds_from_the_scene_move_the_limits():
    spread_04 = summary(metal=0.9, spread=0.4)
    assert classify_cage(spread_04) == "crushed"
    assert classify_cage(spread_04, CageClassThresholds(crushed_spread=0.3)) == "chaotic"
    assert classify_cage(summary(metal=0.04)) == "centred"
    assert classify_cage(summary(metal=0.04), CageClassThresholds(contact_free=0.01)) == "chaotic"


def test_inconsistent_thresholds_are_refused():
    with pytest.raises(ValueError, match="contact_free"):
        CageClassThresholds(contact_free=0.6, crushed_contact=0.5)
    with pytest.raises(ValueError, match="steady_speed"):
        CageClassThresholds(steady_speed=0.3, regular_speed=0.2)
