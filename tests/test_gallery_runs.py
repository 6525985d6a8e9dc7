"""`bearingsim run` end to end on a built-in scene of each cage guidance (docs/validation.md
§15): the full pipeline exits 0, the verdict names the guiding part, and the burn zone is drawn
on the land of the ring that guides the cage (none for a ball-guided cage, whose verdict speaks of
its pockets). The runs are cut to 30 ms: the verdict then also says the run is too short to settle.

The ball-guided gallery scene is run as shipped (film traction, which its nearly pure-rolling,
spin-free contacts need the film's elasticity for: docs/validation.md §15.3) and with Coulomb
traction."""

from __future__ import annotations

import json

import pytest
from typer.testing import CliRunner

from bearingsim.pipeline.cli.commands import app

SHORT = ["solver.duration=0.03"]
COULOMB = ["physics.traction=coulomb", "physics.ehd_film=false"]
CASES = [
    ("acbb-7210-inner-guided", [], "inner"),
    ("turbine-thrust-120", [], "inner"),
    ("helicopter-b-given-hinge", [], "outer"),
    ("deep-groove-6205-ball-guided", [], "ball"),
    pytest.param("deep-groove-6205-ball-guided", COULOMB, "ball", id="deep-groove-6205-ball-guided-coulomb"),
]


@pytest.mark.slow
@pytest.mark.parametrize("scene, overrides, guidance", CASES)
def test_every_guidance_runs_end_to_end_with_its_verdict_and_burn_zone(scene, overrides, guidance, tmp_path):
    sets = [a for o in (*SHORT, *overrides) for a in ("--set", o)]
    result = CliRunner().invoke(app, ["run", scene, "--out", str(tmp_path), *sets])
    assert result.exit_code == 0, result.output[-3000:]
    assert "verdict:" in result.output
    summary = json.loads((tmp_path / "simulate" / "summary.json").read_text(encoding="utf-8"))
    renders = json.loads((tmp_path / "report" / "renders.json").read_text(encoding="utf-8"))
    verdict = summary["verdict"]["text"]
    assert summary["cage_guidance"] == guidance
    if guidance == "ball":
        assert renders["burn_zone"] is None  # no land to burn
        assert "no land" in verdict and "pocket" in verdict
        assert (tmp_path / "report" / "verdict_orbit.png").is_file()
        return
    assert renders["burn_zone"]["ring"] == guidance
    for figure in ("render", "map", "polar"):
        assert (tmp_path / "report" / renders["burn_zone"][figure]).is_file()
    assert "land" in verdict
