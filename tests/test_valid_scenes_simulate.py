"""A valid scene simulates through `simulate` as through `stability`: the kernels' warm-up takes
the run's own steps (adaptive, from solver.first_step), so a first step Newton cannot take is
cut as in the run instead of stopping it at t = 0 (docs/reliability.md).

Every stability scene (pipeline/scenes/stability/) runs 2 ms through `simulate`; the dry-contact
and preload cases, and the Coulomb-traction, cold-lubricant and single-Newton-iteration
variants below, all stopped at t = 0 before."""

from __future__ import annotations

import json

import pytest
from typer.testing import CliRunner

from bearingsim.dynamics.multibody.results import Result
from bearingsim.pipeline.cli.commands import app
from bearingsim.pipeline.studies.stability import case_names, case_path

runner = CliRunner()
SHORT = ["--set", "solver.duration=0.002", "--set", "output.figures=false"]
FAST_CASES = ("dry-contact", "preload")  # the two that stopped at t = 0; the rest are marked slow


def simulate(scene: str, out, *extra: str):
    return runner.invoke(app, ["simulate", scene, "--out", str(out), *SHORT, *extra])


@pytest.mark.parametrize("case", [c if c in FAST_CASES else pytest.param(c, marks=pytest.mark.slow)
                                  for c in case_names()])
def test_every_stability_scene_simulates_2_ms(case, tmp_path):
    result = simulate(str(case_path(case)), tmp_path / case)
    assert result.exit_code == 0, result.output[-3000:]
    summary = json.loads((tmp_path / case / "simulate" / "summary.json").read_text())
    assert summary["duration"] == pytest.approx(0.002, abs=1e-6)


@pytest.mark.parametrize("overrides", [
    ["physics.traction=coulomb", "physics.cage_race=dry", "physics.ehd_film=false"],
    ["lubricant.temperature_degC=-60"],
    ["solver.max_newton_iter=1"],
], ids=["coulomb", "cold-lubricant", "one-newton-iteration"])
def test_scene_variants_that_stopped_at_t0_simulate(overrides, tmp_path):
    sets = [a for o in overrides for a in ("--set", o)]
    result = simulate("helicopter-b-given-hinge", tmp_path / "run", *sets)
    assert result.exit_code == 0, result.output[-3000:]


def test_newton_hints_name_the_first_step():
    """A run that fails at its first step is helped by a smaller solver.first_step."""
    for failure in (Result.NEWTON_DIVERGED, Result.NEWTON_MAX_ITER, Result.NAN_RESIDUAL):
        assert "solver.first_step" in failure.hint
