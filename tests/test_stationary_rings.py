"""Rings at rest: the crush screen of a stationary inner ring (inner_rpm = 0) has no orbital
motion to integrate, so no ball leads or lags the cage — regime "free", zero excursions —
instead of a division by a zero mean speed (docs/reliability.md)."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from typer.testing import CliRunner

from bearingsim.dynamics.quasistatic.crush_screen import CageClearances, LandFilm, crush_screen, excursion_of
from bearingsim.pipeline.cli.commands import app

runner = CliRunner()
Z = 22
PSI = np.arange(Z) * 2 * math.pi / Z
# helicopter-b-like cage values; only their finiteness matters at rest
CLEARANCES = CageClearances(pocket=1.18e-3, guide=2.9e-4)
FILM = LandFilm(radius=0.085, length=0.01, lands=2, eps0=0.1, viscosity=0.01)


def test_the_screen_of_balls_at_rest_is_free_and_finite():
    with np.errstate(all="raise"):  # no 0/0 anywhere on the way
        r = crush_screen(excursion_of(PSI, np.zeros(Z), 0.0791), 0.0, CLEARANCES, FILM)
    assert r.regime == "free" and r.required_eccentricity == 0.0 and r.film_push == 0.0
    assert np.all(r.excursion == 0.0) and r.excursion_peak_to_peak == 0.0 and r.crush_margin == 1.0


@pytest.mark.parametrize("scene, sets", [
    ("helicopter-b-given-hinge", ["speed.inner_rpm=0"]),
    ("helicopter-b-given-hinge", ["speed.inner_rpm=0", "output.figures=false"]),
    ("deep-groove-209", ["speed.inner_rpm=0", "speed.outer_rpm=0"]),
], ids=["figures", "no-figures", "both-rings"])
def test_quasistatic_with_a_stationary_inner_ring(scene, sets, tmp_path):
    args = [a for s in sets for a in ("--set", s)]
    result = runner.invoke(app, ["quasistatic", scene, "--json", "--out", str(tmp_path / "run"), *args])
    assert result.exit_code == 0, result.output[-3000:]
    out = json.loads(result.stdout)
    screen = out.get("cage_screen")
    assert (screen is None) == (scene == "deep-groove-209")  # helicopter-b has a cage
    if screen is not None:
        assert screen["regime"] == "free"
        assert all(x == 0.0 for x in screen["excursion_per_ball"])
