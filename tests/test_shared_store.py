"""The FE identification is shared between run directories through the user's stage store:
a second scene with the same FE inputs reuses it; `--no-store` opts out."""

from __future__ import annotations

import pytest
from typer.testing import CliRunner

from bearingsim.pipeline.cli.commands import app

# a coarse, uniform mesh: the identification in a few seconds (accuracy is not the point here)
COARSE = ["--set", "fe.mesh_size=0.035", "--set", "fe.edge_refinement=1.0", "--set", "fe.element_order=1"]


def _identify(scene, out, *extra):
    """`bearingsim simulate` of a very short run: identify (shared) -> quasistatic -> simulate."""
    result = CliRunner().invoke(app, ["simulate", scene, "--out", str(out), *COARSE,
                                      "--set", "solver.duration=0.0005", *extra])
    assert result.exit_code == 0, result.output
    return result.output


@pytest.mark.filterwarnings("ignore")
def test_a_second_scene_with_the_same_fe_inputs_reuses_the_identification(tmp_path):
    from bearingsim.pipeline.staging.artefacts import read_manifest

    first = _identify("helicopter-b", tmp_path / "b")
    assert "identify     computed" in first
    # helicopter-a differs in the moment only: the FE inputs, hence the identify key, are the same
    second = _identify("helicopter-a", tmp_path / "a")
    assert "identify     from store (reused" in second
    assert read_manifest(tmp_path / "a" / "identify")["key"] == read_manifest(tmp_path / "b" / "identify")["key"]
    assert (tmp_path / "a" / "identify" / "hinge.toml").read_bytes() == (tmp_path / "b" / "identify" / "hinge.toml").read_bytes()
    # opting out computes it again
    third = _identify("helicopter-a", tmp_path / "a2", "--no-store")
    assert "identify     computed" in third
