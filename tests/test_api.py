"""The Python API: `import bearingsim` stays light, the README's example runs verbatim, stages
go through the command line's runner and cache (a stage the API computed is cached for the
CLI), results come back with units and dimension names."""

from __future__ import annotations

import csv
import json
import math
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import bearingsim
from bearingsim.pipeline.api import forced_stages, override_strings
from bearingsim.pipeline.scene.schema import SceneError

README = Path(__file__).resolve().parents[1] / "README.md"
SCENE = "helicopter-b-given-hinge"


def readme_example() -> str:
    """The python block between `<!-- api-example ... -->` and `<!-- /api-example -->`."""
    text = README.read_text(encoding="utf-8")
    section = re.search(r"<!-- api-example\b.*?-->(.*?)<!-- /api-example -->", text, re.S)
    assert section, "README.md lost its <!-- api-example --> block"
    code = re.search(r"```python\n(.*?)```", section.group(1), re.S)
    assert code, "the api-example block holds no ```python code"
    return code.group(1)


@pytest.fixture(scope="module")
def example(tmp_path_factory):
    """Run the README example verbatim in a fresh directory; its namespace and directory."""
    import os

    where = tmp_path_factory.mktemp("api")
    code = readme_example()
    assert '"solver.duration": 0.01' in code  # short enough for the default suite
    cwd = os.getcwd()
    os.chdir(where)
    try:
        namespace: dict = {}
        exec(compile(code, str(README), "exec"), namespace)  # noqa: S102 - the documented example
    finally:
        os.chdir(cwd)
    return namespace, where


def test_import_bearingsim_is_light():
    code = ("import sys, bearingsim; bearingsim.NamedArray; bearingsim.load_scene;"
            "heavy = [m for m in ('numba', 'matplotlib', 'gmsh', 'pyvista', 'h5py', 'scipy') if m in sys.modules];"
            "print(heavy); sys.exit(1 if heavy else 0)")
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert result.returncode == 0, f"import bearingsim loads {result.stdout.strip()} {result.stderr[-500:]}"
    assert {"load_scene", "run", "open_run", "Run", "NamedArray", "export_stiffness"} <= set(dir(bearingsim))


def test_readme_example_runs_and_gives_named_results(example):
    ns, where = example
    run = ns["run"]
    assert run.run_dir == (where / "runs" / "demo").absolute()  # absolute, so valid after a chdir
    assert run.stages == {"identify": "not needed", "quasistatic": "computed", "simulate": "computed"}
    summary = json.loads((where / "runs/demo/simulate/summary.json").read_text())
    assert ns["cage_speed"] == summary["cage_speed_mean"] and summary["duration"] == pytest.approx(0.01, abs=1e-5)
    # the scene's overrides reached the run (and its scene.toml)
    assert run.scene.load.moment == 300.0 and run.scene.solver.duration == 0.01
    assert "moment = 300" in (where / "runs/demo/scene.toml").read_text()
    assert "built-in:helicopter-b-given-hinge" in (where / "runs/demo/scene.toml").read_text()
    position = ns["position"]
    assert position.unit == "m" and position.dims == ("time", "xyz") and position.values.shape == (1001, 3)
    ts = ns["ts"]
    np.testing.assert_allclose(ts["time"].values[[0, -1]], [0.0, 0.01], atol=1e-5)
    assert ts["balls/position"].dims == ("time", "ball", "xyz") and ts["balls/position"].shape == (1001, 22, 3)
    assert ts["cage/speed"].unit == "rad/s" and "cage" in ts["cage/speed"].description
    assert np.asarray(ts["cage/speed"]).mean() == pytest.approx(ns["cage_speed"], rel=0.05)
    assert ns["heaviest"] == max(run.quasistatic_arrays()["inner_load"].values) > 1000.0


def test_api_and_command_line_share_stages_and_cache(example):
    from typer.testing import CliRunner

    from bearingsim.pipeline.cli.commands import app

    _, where = example
    run_dir = where / "runs" / "demo"
    before = {s: json.loads((run_dir / s / "stage.json").read_text()) for s in ("quasistatic", "simulate")}
    again = bearingsim.run(SCENE, run_dir, ["simulate"], overrides=["load.moment=300", "solver.duration=0.01"])
    assert {o.name: o.status for o in again.outcomes} == {
        "identify": "not needed", "quasistatic": "cached", "simulate": "cached"}
    result = CliRunner().invoke(app, ["simulate", SCENE, "--out", str(run_dir),
                                      "--set", "load.moment=300", "--set", "solver.duration=0.01"])
    assert result.exit_code == 0, result.output
    after = {s: json.loads((run_dir / s / "stage.json").read_text()) for s in ("quasistatic", "simulate")}
    assert after == before  # same keys, nothing recomputed by either


def test_timeseries_of_a_run_is_compressed(example):
    import h5py

    _, where = example
    with h5py.File(where / "runs/demo/simulate/timeseries.h5", "r") as h5:
        ds = h5["balls/position"]
        assert ds.compression == "gzip" and ds.chunks[1:] == ds.shape[1:]


def test_timeseries_units_are_udunits_strings(example):
    """docs/outputs.md: files carry UDUNITS unit strings (`1`, `N m`), which netCDF tools and
    pint parse; the channels are declared with `-` and `N.m`, as the scene keys are."""
    import h5py

    _, where = example
    units = {}
    with h5py.File(where / "runs/demo/simulate/timeseries.h5", "r") as h5:
        h5.visititems(lambda name, obj: units.__setitem__(name, obj.attrs["units"])
                      if isinstance(obj, h5py.Dataset) and "units" in obj.attrs else None)
    assert units["cage_race/eccentricity_ratio"] == "1" and units["cage_race/torque"] == "N m"
    assert units["contacts/inner_slide_roll"] == "1" and units["power/drive_moment"] == "N m"
    assert not [name for name, unit in units.items() if unit in ("-", "") or "N.m" in unit]


def test_one_series_to_xarray_has_the_coordinates_of_its_file(example):
    """README: `a.to_xarray()` of a series from `run.timeseries()` has time and component
    coordinates, as the whole file's Dataset has."""
    pytest.importorskip("xarray")
    ns, _ = example
    series = ns["run"].timeseries()
    da = series["cage/position"].to_xarray()
    assert da.dims == ("time", "xyz") and list(da.coords["xyz"].values) == ["x", "y", "z"]
    np.testing.assert_array_equal(da.coords["time"].values, np.asarray(series["time"]))
    assert float(da.sel(xyz="x").isel(time=-1)) == float(np.asarray(series["cage/position"])[-1, 0])


def test_summary_closes_the_energy_balance(example):
    """Work in = dissipation + change of stored energy, up to a residual that summary.json
    reports; like tests/test_bearing_dynamics.py, within 1 % of the drive's work."""
    ns, _ = example
    run = ns["run"]
    energy = run.summary["energy"]
    series = run.timeseries(["energy/kinetic", "energy/hertz", "energy/hinge"])
    stored = sum(float(np.asarray(series[n])[-1] - np.asarray(series[n])[0])
                 for n in ("energy/kinetic", "energy/hertz", "energy/hinge"))
    assert energy["stored_change"] == pytest.approx(stored, rel=1e-12, abs=1e-12)
    assert energy["balance_residual"] == pytest.approx(
        energy["drive"] + energy["external"] - energy["dissipated"] - stored, rel=1e-9, abs=1e-12)
    assert abs(energy["balance_residual"]) < 0.01 * abs(energy["drive"])
    assert run.summary["units"]["energy.balance_residual"] == "J"


def test_open_run_reads_the_same_results(example):
    ns, where = example
    opened = bearingsim.open_run(where / "runs" / "demo")
    assert opened.summary == ns["run"].summary
    assert opened.stages["simulate"] == "done"
    assert opened.hinge["source"] == "given" and opened.hinge["bending"].tolist() == [1e5, 1e5]
    impacts = opened.impacts()
    assert set(impacts) == {"time", "ball", "orbital_position", "peak_force", "impact_speed", "duration"}
    assert impacts["peak_force"].unit == "N" and impacts["peak_force"].dims == ("impact",)
    qa = opened.quasistatic_arrays()
    assert qa["stiffness"].shape == (5, 5) and qa["inner_contact_angle"].unit == "rad"
    assert opened.report is None  # the report stage did not run


def test_missing_stage_says_how_to_run_it(tmp_path):
    scene = bearingsim.load_scene("deep-groove-209")
    run = bearingsim.run(scene, tmp_path / "qs", stages="quasistatic")
    assert run.quasistatic["converged"]
    with pytest.raises(FileNotFoundError, match=r"stages=\['simulate'\]"):
        run.summary
    with pytest.raises(FileNotFoundError, match="simulate"):
        run.timeseries()


def test_a_refused_directory_is_named_as_the_python_argument(tmp_path):
    """From Python there is no --out: the message names `run_dir`, and the command line's
    messages keep naming --out."""
    mine = tmp_path / "mine"
    mine.mkdir()
    (mine / "notes.txt").write_text("mine")
    with pytest.raises(bearingsim.OutputRefused) as refused:
        bearingsim.run("deep-groove-209", mine, stages="quasistatic")
    message = str(refused.value)
    assert f"run_dir={str(mine)!r}: the directory holds files" in message
    assert f"e.g. run_dir={str(mine / 'run')!r}" in message and "--out" not in message
    assert sorted(p.name for p in mine.iterdir()) == ["notes.txt"]
    from bearingsim.pipeline.staging.artefacts import claim_run_directory
    with pytest.raises(bearingsim.OutputRefused, match=r"^--out .*e\.g\. --out "):
        claim_run_directory(mine)


def test_overrides_as_mapping_or_strings_are_validated_like_the_file():
    a = bearingsim.load_scene(SCENE, {"load.moment": np.float64(250), "solver": {"duration": 0.02},
                                      "physics.cage_race": "dry"})
    b = bearingsim.load_scene(SCENE, ["load.moment=250", "solver.duration=0.02", "physics.cage_race=dry"])
    assert a.raw == b.raw and a.load.moment == 250.0 and a.physics.cage_race == "dry"
    c = bearingsim.load_scene(a, {"load.moment": 260})  # from a Scene, keeping its overrides
    assert c.load.moment == 260.0 and c.solver.duration == 0.02
    with pytest.raises(SceneError, match=r"solver\.max_step.*out of range.*\[s\]"):
        bearingsim.load_scene(SCENE, {"solver.max_step": -2e-6})
    with pytest.raises(SceneError, match="load.moment"):
        bearingsim.load_scene(SCENE, {"load.moment": None})
    assert override_strings({"speed": {"inner_rpm": 3000}, "hinge.bending": (1e5, np.float64(2e5))}) == [
        "speed.inner_rpm=3000", "hinge.bending=[100000.0, 200000.0]"]
    d = bearingsim.load_scene(SCENE, {"hinge.bending": np.array([2e5, 3e5])})
    assert d.hinge.bending == (2e5, 3e5)


def test_stage_names_and_force():
    with pytest.raises(ValueError, match="simulation.*identify, quasistatic, simulate, report"):
        bearingsim.run(SCENE, "unused", stages=["simulation"])
    with pytest.raises(ValueError, match=r"^stages: no stage given; name at least one of identify, "):
        bearingsim.run(SCENE, "unused", stages=[])
    assert forced_stages(False, ["simulate"]) == set()
    assert forced_stages(True, ["simulate"]) == {"simulate"}
    assert forced_stages("all", ["simulate"]) == {"identify", "quasistatic", "simulate", "report"}
    assert forced_stages(["quasistatic"], ["simulate"]) == {"quasistatic"}


def test_named_array_is_numpy_and_optionally_xarray():
    a = bearingsim.NamedArray(np.arange(6.0).reshape(3, 2), "N", ("time", "xy"), "force", "cage_race/force")
    assert np.asarray(a).sum() == 15.0 and len(a) == 3 and a.shape == (3, 2)
    assert np.asarray(a, dtype=np.float32).dtype == np.float32
    try:
        import xarray  # noqa: F401
    except ImportError:
        with pytest.raises(ImportError, match="pip install xarray"):
            a.to_xarray()
        return
    da = a.to_xarray({"time": [0.0, 1.0, 2.0], "xy": ["x", "y"]})
    assert da.attrs["units"] == "N" and da.dims == ("time", "xy") and float(da.sel(xy="y").sum()) == 9.0


def test_summary_units_cover_every_number(example):
    """Every number of a real run's summary.json has a unit in its `units` map: a new key
    without one (pipeline/results/summary_keys.py) fails here."""
    from bearingsim.pipeline.results.summary_keys import numeric_keys

    _, where = example
    summary = json.loads((where / "runs/demo/simulate/summary.json").read_text())
    assert [k for k in numeric_keys(summary) if k not in summary["units"]] == []
    units = summary["units"]
    assert (units["cage_speed_mean"], units["energy.drive"], units["land_film_min"], units["steps"]) == (
        "rad/s", "J", "m", "1")
    assert units["verdict.land_film_min_um"] == "um" and units["startup.metal_energy"] == "J"


def test_impact_positions_are_degrees_0_to_360(example):
    """impacts.csv's orbital position is the ball's azimuth at the impact, in degrees 0–360:
    checked against the ball centres of timeseries.h5 (atan2 of the nearest sample; the
    ball moves ~0.1° between samples)."""
    ns, where = example
    with open(where / "runs/demo/simulate/impacts.csv", newline="", encoding="utf-8") as fh:
        rows = list(csv.DictReader(fh))
    assert rows, "the 10 ms example run has pocket impacts (it had 2)"
    assert all(h.endswith("]") for h in rows[0])  # every column carries its unit
    ts = ns["run"].timeseries(["balls/position"])
    t, position = ts.coords()["time"], np.asarray(ts["balls/position"])
    for row in rows:
        angle = float(row["orbital_position [deg]"])
        assert 0.0 <= angle < 360.0
        i, ball = int(np.argmin(np.abs(t - float(row["time [s]"])))), int(row["ball [1]"])
        expected = math.degrees(math.atan2(position[i, ball, 1], position[i, ball, 0])) % 360.0
        assert abs((angle - expected + 180.0) % 360.0 - 180.0) < 0.5


def test_run_repr_is_short_and_the_notebook_display_shows_the_verdict(example):
    ns, _ = example
    run = ns["run"]
    text = repr(run)
    assert text.startswith("Run('helicopter-b-given-hinge', ") and "\n" not in text and len(text) < 300
    assert run.summary["verdict"]["class"] in text
    # the given hinge needs no FE stage: the run holds no identify results to list
    assert run.stages["identify"] == "not needed" and "stages: quasistatic, simulate;" in text
    page = run._repr_html_()
    assert run.summary["verdict"]["text"].split(":")[0] in page.replace("&#x27;", "'")
    assert "thinnest land film" in page and 'src="data:image/png;base64,' in page


def test_dir_bearingsim_lists_public_names_only():
    names = dir(bearingsim)
    assert "annotations" not in names and "importlib" not in names and "_API" not in names
    assert {"load_scene", "run", "open_run", "sweep", "Run", "export_stiffness", "__version__"} <= set(names)
