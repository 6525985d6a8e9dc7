"""The user's Barus oil in the dynamics (docs/model.md §6.4, *Glass viscosity* and *Film
elasticity*): eta0 = 20 mPa.s, alpha = 2e-8 1/Pa at 70 degC. Held at the glass viscosity its
traction table no longer overflows float32 ("RuntimeWarning: overflow encountered in cast"), and
it simulates 20 ms of the reference bearing without a warning. In a 7210-like angular-contact
bearing at 6000 rev/min it puts 1e7-1e12 Pa.s over the contacts; with the film's elasticity
(`lubricant.elastic_shear_modulus`, 1 GPa) it runs 20 ms there too, as do the same eta0 and
alpha* as Roelands and the built-in iso-vg68. Without it (G = 1e30 Pa) the run stops in Newton, and
the message names the lubricant key that bounds the film's stiffness.

The 7210-like bearing (a test scene, not a catalogue one): d = 50 mm, D = 90 mm, B = 20 mm (ISO 15
series 02), 14 balls of 12.7 mm on a 70 mm pitch circle, conformities 0.52 / 0.53, diametral
clearance 0.297 mm for a 40 deg free contact angle (cos 40 deg = 1 - P_d / 2A, A = 0.05 D), a
PA66-GF25 cage guided by the outer ring, 4 kN thrust and 1 kN radial load (about a tenth of such
a bearing's 37.7 kN dynamic rating).
"""

from __future__ import annotations

import copy
import json
import warnings

import pytest
from typer.testing import CliRunner

from bearingsim.dynamics.multibody import IntegrationError
from bearingsim.pipeline.api import run
from bearingsim.pipeline.cli.commands import app
from bearingsim.pipeline.console import explain
from bearingsim.pipeline.scene.load import read_scene_table, resolve

USER_BARUS = {"name": "user-barus", "viscosity_model": "barus", "ambient_viscosity": 0.020,
              "pressure_viscosity_coefficient": 2e-8, "temperature_degC": 70.0, "eyring_stress": 5e6,
              "density": 870.0}
SHORT = {"duration": 0.02}

BEARING_7210 = {
    "name": "acbb-7210",
    "description": "7210-like 40 deg angular-contact ball bearing, PA66-GF25 cage on the outer ring",
    "bearing": {"ball_diameter": 0.0127, "ball_count": 14, "pitch_diameter": 0.070, "inner_conformity": 0.52,
                "outer_conformity": 0.53, "diametral_clearance": 2.97e-4, "inner_shoulder_diameter": 0.0635,
                "outer_shoulder_diameter": 0.0765, "inner_bore_diameter": 0.050, "outer_outside_diameter": 0.090,
                "width": 0.020},
    "cage": {"mean_diameter": 0.070, "pocket_diameter": 0.0131, "radial_thickness": 0.0061, "width": 0.016,
             "guidance": "outer"},
    "materials": {"ball": "aisi-52100", "race": "aisi-52100", "cage": "pa66-gf25"},
    "load": {"axial": 4000.0, "radial": 1000.0},
    "speed": {"inner_rpm": 6000.0},
    "hinge": {"source": "given", "translational": [1e9, 1e9, 1e9], "bending": [1e5, 1e5]},
    "solver": SHORT,
    "output": {"sample_interval": 1e-5},
}


def _simulate(table: dict, run_dir):
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)  # the raw overflow warning fails the test
        return run(resolve(copy.deepcopy(table)), run_dir, stages="simulate")


def _summary(result) -> dict:
    return json.loads((result.stage_dir("simulate") / "summary.json").read_text(encoding="utf-8"))


def test_the_users_barus_oil_runs_20_ms_of_the_reference_bearing_without_a_warning(tmp_path):
    table = copy.deepcopy(read_scene_table("helicopter-b-given-hinge")[0])
    table["lubricant"], table["solver"] = dict(USER_BARUS), {**table["solver"], **SHORT}
    summary = _summary(_simulate(table, tmp_path / "run"))
    assert summary["duration"] == pytest.approx(0.02, rel=1e-6)
    cli = CliRunner().invoke(app, ["simulate", "helicopter-b-given-hinge", "--out", str(tmp_path / "cli"),
                                   *[f"--set=lubricant.{k}={v}" for k, v in USER_BARUS.items() if k != "name"],
                                   "--set=lubricant.name=user-barus", "--set=solver.duration=0.02"])
    assert cli.exit_code == 0, cli.output
    assert "RuntimeWarning" not in cli.stderr and "overflow" not in cli.stderr


@pytest.mark.parametrize("lubricant", [
    {"name": "iso-vg68", "temperature_degC": 70.0},  # the "ISO VG 68-like oil"
    {**USER_BARUS, "viscosity_model": "roelands", "roelands_z": None},  # same eta0 and alpha*, filled below
], ids=["iso-vg68", "barus-as-roelands"])
def test_the_7210_runs_20_ms_with_a_measured_law(lubricant, tmp_path):
    table = copy.deepcopy(BEARING_7210)
    if lubricant.get("roelands_z", 0) is None:
        barus = resolve({**copy.deepcopy(BEARING_7210), "lubricant": dict(USER_BARUS)}).lubricant
        lubricant = {k: v for k, v in lubricant.items() if k != "pressure_viscosity_coefficient"}
        lubricant["roelands_z"] = barus.as_roelands().roelands_z
    table["lubricant"] = lubricant
    summary = _summary(_simulate(table, tmp_path / "run"))
    assert summary["duration"] == pytest.approx(0.02, rel=1e-6)


def test_the_users_barus_oil_runs_20_ms_of_the_7210(tmp_path):
    table = {**copy.deepcopy(BEARING_7210), "lubricant": dict(USER_BARUS)}
    summary = _summary(_simulate(table, tmp_path / "run"))
    assert summary["duration"] == pytest.approx(0.02, rel=1e-6)


def test_without_the_films_elasticity_the_7210_stops_and_the_message_names_the_key(tmp_path):
    table = {**copy.deepcopy(BEARING_7210), "lubricant": {**USER_BARUS, "elastic_shear_modulus": 1e30}}
    with pytest.raises(IntegrationError) as failed:
        _simulate(table, tmp_path / "run")
    text = explain(failed.value)
    # the advice names the lubricant key, not the solver's (which do not help here)
    assert "lubricant.elastic_shear_modulus" in text
    assert "solver." not in text.split("Try:")[1]
