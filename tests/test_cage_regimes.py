"""The regime contrast of the reference cases under the shipped defaults (docs/validation.md), so
that a later change cannot silently invert it again. Shortened runs (0.25 s, the scene's own
solver settings); the settled window starts at 0.1 s, after the start-up transient of both cases.

What the defaults produce and this test pins (docs/validation.md §1, §9, §12), with every part at
the oil's 100 °C (the operating clearances of docs/model.md §2.1):
- case b (430 N m): the cage is pressed onto one sector of its land near +x (the push direction
  of the crush screen), steadily: small spread of the offset direction, high eccentricity;
- case a (100 N m): the cage wanders round its land (no fixed sector), without metal contact;
- 600 N m: crushed: metal contact most of the time in one sector;
- each run's crush screen (summary.json `crush_screen`) names the same regime at the operating
  clearances, and the gap to the inner ring's land stays open (no contact the model ignores).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

pytestmark = pytest.mark.slow

FAST = ["solver.duration=0.25"]
SETTLE = 0.1


def _settled(tmp_path, moment: float) -> dict:
    import h5py
    from typer.testing import CliRunner

    from bearingsim.pipeline.cli.commands import app

    out = tmp_path / f"m{moment:g}"
    args = ["simulate", "helicopter-b-given-hinge", "--out", str(out), "--set", f"load.moment={moment}"]
    for o in FAST:
        args += ["--set", o]
    result = CliRunner().invoke(app, args)
    assert result.exit_code == 0, result.output
    import json

    summary = json.loads((out / "simulate" / "summary.json").read_text())
    with h5py.File(out / "simulate" / "timeseries.h5") as f:
        t = f["time"][:]
        c = f["cage/position"][:]
        eps = f["cage_race/eccentricity_ratio"][:]
    m = t >= SETTLE
    z = np.mean(np.exp(1j * np.arctan2(c[m, 1], c[m, 0])))
    return {"eps_mean": float(eps[m].mean()), "metal": float(np.mean(eps[m] > 1.0)),
            "azimuth": math.degrees(math.atan2(z.imag, z.real)),
            "spread": math.sqrt(-2.0 * math.log(min(abs(z), 1.0))),
            "screen": summary["crush_screen"], "gap": summary["non_guiding_gap_min"]}


def test_reference_cases_keep_their_regimes(tmp_path):
    a = _settled(tmp_path, 100.0)
    b = _settled(tmp_path, 430.0)
    crushed = _settled(tmp_path, 600.0)
    # case b: one fixed sector near +x (crush screen: push towards 0 deg), no wandering
    assert b["spread"] < 0.5 and abs(b["azimuth"]) < 30.0 and b["eps_mean"] > 0.85, b
    # case a: no fixed sector, no metal contact
    assert a["spread"] > 1.0 and a["metal"] < 0.05, a
    # the contrast itself: b's offset direction is at least 3x more concentrated than a's
    assert a["spread"] > 3.0 * b["spread"]
    # beyond the crush threshold (screen: 512 N m at 100 °C): metal contact most of the time, one sector
    assert crushed["metal"] > 0.5 and crushed["spread"] < 0.5, crushed
    # the screen at the operating clearances (guide 0.25 mm, pocket 1.19 mm) names the same regimes
    assert [r["screen"]["regime"] for r in (a, b, crushed)] == ["free", "pressed", "crushed"]
    assert b["screen"]["guide_clearance"] < 0.26e-3 and b["screen"]["crush_margin"] < b["screen"][
        "crush_margin_at_reference_temperature"]
    # the cage never reaches the inner ring's land
    assert min(r["gap"] for r in (a, b, crushed)) > 0.0
