"""The crush screen in the verdict: operating clearances, margins and the crush probability reach
the printed line, the report's rows and summary.json's units (docs/model.md §10.1–§10.2)."""

from __future__ import annotations

import json

from typer.testing import CliRunner

from bearingsim.pipeline.cli.commands import app
from bearingsim.pipeline.results.simulation_output import screen_summary
from bearingsim.pipeline.results.summary_keys import numeric_keys, unit_of
from bearingsim.pipeline.results.verdict import screen_sentence, verdict_rows


def test_tolerances_reach_the_verdict(tmp_path):
    out = tmp_path / "run"
    result = CliRunner().invoke(app, [
        "tolerances", "helicopter-b-given-hinge", "--out", str(out), "--samples", "500", "--seed", "4",
        "--set", "tolerances.cage_outside_diameter={lower = 0.0, upper = 4e-4}", "--json"])
    assert result.exit_code == 0, result.output
    analysis = json.loads(result.stdout)
    assert analysis["samples"] == 500 and 0.0 < analysis["crush_probability"] < 1.0
    quasistatic = json.loads((out / "quasistatic" / "quasistatic.json").read_text())
    screen = screen_summary(quasistatic)
    # the operating clearances (100 °C) and the drawing's (20 °C) both travel with the screen
    assert screen["guide_clearance"] < screen["guide_clearance_at_reference_temperature"]
    assert abs(screen["guide_clearance_at_reference_temperature"] - 0.29e-3) < 1e-12  # Table 1, docs/model.md §2
    assert screen["crush_margin"] < screen["crush_margin_at_reference_temperature"]
    text = screen_sentence(screen)
    assert "guide 250 µm" in text and "parts at 100 °C" in text and "P(crushed)" in text
    assert "over 500 tolerance stacks" in text
    rows = {label.strip(): value for label, value, _ in verdict_rows({
        "class": "pressed", "risk": "elevated", "risk_reasons": [], "screen": screen})}
    assert rows["crush margin at operating clearances"] == f"{screen['crush_margin']:.2f}"
    assert rows["P(crushed) over tolerance stacks"].startswith(f"{100 * screen['crush_probability']:.3g}")
    summary = {"crush_screen": screen, "verdict": {"screen": screen}}
    assert all(unit_of(k) is not None for k in numeric_keys(summary)), [k for k in numeric_keys(summary) if unit_of(k) is None]
