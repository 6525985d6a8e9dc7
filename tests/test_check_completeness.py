"""`check` runs every validation that a stage or a sweep would run at once: the FE geometry
against the bearing ring, the size of the FE mesh, every point of the scene's own [sweep] table
(docs/reliability.md). Mesh-size bounds admit the value they state."""

from __future__ import annotations

from pathlib import Path

import pytest
from typer.testing import CliRunner

from bearingsim.pipeline.cli.commands import app

runner = CliRunner()
GIVEN = (Path(__file__).parents[1] / "pipeline" / "scenes" / "helicopter-b-given-hinge.toml").read_text()

# each refused by `identify` (FEConfig.validate, or the mesh size) in helicopter-b
FE_REFUSALS = {
    "fe.shaft_inner_diameter=0.2": "shaft_inner_diameter = 0.2 m is not allowed: it must be < 0.13 m",
    "fe.support_a_position=0.11": "support_a_position = 0.11 m is not allowed",  # overlaps the ring
    "fe.housing_flange_diameter=0.05": "housing_flange_diameter = 0.05 m is not allowed",
    "fe.mesh_size=10": "mesh_size = 10.0 m is not allowed: it must be <= 0.04 m",
    "fe.mesh_size=0.0401": "mesh_size = 0.0401 m is not allowed: it must be <= 0.04 m",
    "fe.mesh_size=1e-5": "fe.mesh_size: 1e-05 m gives at least 2.38e+08 triangles",
}


@pytest.mark.parametrize("override", FE_REFUSALS)
def test_check_refuses_what_identify_refuses(override):
    result = runner.invoke(app, ["check", "helicopter-b", "--set", override])
    assert result.exit_code == 2, result.output[-2000:]
    assert FE_REFUSALS[override] in result.stderr


def test_a_tiny_mesh_is_refused_before_any_file_with_the_smallest_allowed(tmp_path):
    result = runner.invoke(app, ["identify", "helicopter-b", "--set", "fe.mesh_size=1e-5", "--out", str(tmp_path / "r")])
    assert result.exit_code == 2 and "allowed >= 0.000109 m" in result.stderr
    assert not (tmp_path / "r").exists()


def test_a_fine_mesh_is_a_warning():
    result = runner.invoke(app, ["check", "helicopter-b", "--set", "fe.mesh_size=0.0003"])
    assert result.exit_code == 0 and "expect a long identification" in result.stderr


def test_the_stated_mesh_bound_is_allowed():
    """4 x the thinnest wall (10 mm) is 0.04 m as stated; 4 * 0.01 is 0.039999... in binary."""
    result = runner.invoke(app, ["check", "helicopter-b", "--set", "fe.mesh_size=0.04"])
    assert result.exit_code == 0, result.output[-2000:]


def test_check_refuses_a_sweep_point_with_an_unknown_key(tmp_path):
    scene = tmp_path / "sweep.toml"
    scene.write_text(GIVEN + '\n[sweep]\nmode = "list"\npoints = [{ "load.moment" = 1 }, { "load.momnet" = 2 }]\n')
    result = runner.invoke(app, ["check", str(scene)])
    assert result.exit_code == 2 and "load.momnet: unknown key" in result.stderr
    scene.write_text(GIVEN + '\n[sweep]\nmode = "list"\npoints = [{ "load.moment" = 1 }, { "load.moment" = 2 }]\n')
    assert runner.invoke(app, ["check", str(scene)]).exit_code == 0
