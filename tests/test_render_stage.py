"""The `report` stage and `bearingsim render RUN` on a synthetic finished run directory."""

from __future__ import annotations

import html
import json
import math
import re

import numpy as np
import pytest
import tomli_w
from typer.testing import CliRunner

from bearingsim.pipeline.staging.artefacts import atomic_write_json, read_manifest
from bearingsim.pipeline.cli.commands import app
from bearingsim.pipeline.results.timeseries import Series, write_timeseries
from bearingsim.pipeline.staging.runner import run_stages, stage_key
from bearingsim.pipeline.scene.load import load_scene
from bearingsim.pipeline.stages import STAGES
from bearingsim.pipeline.stages.identify import STAGE as IDENTIFY
from bearingsim.pipeline.stages.quasistatic import STAGE as QUASISTATIC
from bearingsim.pipeline.stages.report import STAGE as REPORT
from bearingsim.pipeline.stages.simulate import STAGE as SIMULATE

from .test_render_fe import write_tiny_case

RUB_AZIMUTH, RUB_POWER, RUB_TIME = 1.0, 100.0, 4e-3  # rad, W, s
FILM_POWER, EPS = 10.0, 0.8  # W, - (the cage pressed at RUB_AZIMUTH through its film)


def _manifest(directory, key):
    atomic_write_json(directory / "stage.json", {"stage": directory.name, "status": "done", "key": key,
                                                 "wall_time_s": 0.1, "finished": "2026-01-01T00:00:00"})


def _timeseries(scene, path):
    """A 10 ms run: balls on the outer groove at contact angle 25° + 5° cos(psi); the cage
    sits at eps = 0.8 towards azimuth 1 rad, its film dissipating 10 W throughout, and rubs
    the land there with 100 W during the first 4 ms (a start-up crash). The summary is the
    simulate stage's own (cage_summary, cage_verdict): a 10 ms run is far shorter than a
    cage revolution, so the settled window is the capped last half, t >= 5 ms."""
    from bearingsim.pipeline.results.cage_metrics import CageSeries, GuideLand, PocketImpacts, cage_summary
    from bearingsim.pipeline.results.verdict import cage_verdict

    b, Z = scene.bearing, scene.bearing.ball_count
    t = np.linspace(0.0, 0.01, 201)
    psi = (np.arange(Z)[None, :] * 2 * math.pi / Z + 140.0 * t[:, None])
    alpha = np.radians(25.0 + 5.0 * np.cos(psi))
    rho = 0.5 * b.outer_groove_center_diameter + 0.43e-3 * np.cos(alpha)
    pos = np.stack([rho * np.cos(psi), rho * np.sin(psi), 0.43e-3 * np.sin(alpha)], axis=2)
    power = np.where(t < RUB_TIME, RUB_POWER, 0.0)
    clearance = 2.9e-4
    cage_xy = np.tile([EPS * clearance * math.cos(RUB_AZIMUTH), EPS * clearance * math.sin(RUB_AZIMUTH)], (t.size, 1))
    T, B = ("time",), ("time", "ball")
    series = {
        "time": Series(t, "s", "sample time", T),
        "balls/position": Series(pos, "m", "ball centres", ("time", "ball", "xyz")),
        "contacts/outer_contact_angle": Series(alpha, "rad", "outer contact angle", B),
        "contacts/outer_load": Series(np.full_like(alpha, 3000.0), "N", "outer load", B),
        "cage/position": Series(np.c_[cage_xy, np.zeros(t.size)], "m", "cage centre", ("time", "xyz")),
        "cage/speed": Series(np.full_like(t, 140.0), "rad/s", "cage speed", T),
        "cage_race/eccentricity_ratio": Series(np.full_like(t, EPS), "-", "eps", T),
        "cage_race/friction_power": Series(power, "W", "friction power", T),
        "cage_race/film_power": Series(np.full_like(t, FILM_POWER), "W", "film power", T),
        "cage_race/contact_azimuth": Series(np.full_like(t, RUB_AZIMUTH), "rad", "contact azimuth", T),
    }
    write_timeseries(path, series, {"guide_clearance_m": clearance})
    summary = {"duration": 0.01, "steps": 1234, "rejected_steps": 5, "newton_iterations": 2000,
               "factorizations": 7, "energy": {"drive": 1.0}}
    summary.update(cage_summary(
        CageSeries(t, cage_xy, series["cage/speed"].data, series["cage_race/eccentricity_ratio"].data,
                   series["cage_race/contact_azimuth"].data, power, np.zeros(t.size),
                   film_power=series["cage_race/film_power"].data),
        PocketImpacts(np.zeros(0)), GuideLand(clearance, 0.05)))
    summary["verdict"] = cage_verdict(summary)
    return summary


@pytest.fixture(scope="module")
def run_dir(tmp_path_factory):
    """A finished run of helicopter-b (FE hinge) with the real stages' keys in the manifests."""
    scene = load_scene("helicopter-b")
    run = tmp_path_factory.mktemp("run") / "helicopter-b"
    run.mkdir()
    (run / "scene.toml").write_text("# Resolved scene (synthetic)\n" + tomli_w.dumps(scene.raw))
    (run / ".bearingsim-run").write_text("a run directory\n")
    (run / "versions.json").write_text(json.dumps({"bearingsim": "test", "numpy": np.__version__}))
    keys = {"identify": stage_key(IDENTIFY, scene, {}), "quasistatic": stage_key(QUASISTATIC, scene, {})}
    keys["simulate"] = stage_key(SIMULATE, scene, dict(keys))
    for name in keys:
        (run / name).mkdir()
        _manifest(run / name, keys[name])
    write_tiny_case(run / "identify" / "case_fx.vtu", 3e-6)
    (run / "identify" / "hinge.toml").write_text(
        '[hinge]\nsource = "fe"\ntranslational = [[6.5e8, 0, 0], [0, 6.5e8, 0], [0, 0, 5.3e8]]\n'
        'bending = [8.7e6, 8.7e6]\n[fit]\nrelative_residual = 0.0015\ncondition_number = 1.41\n'
        '[[cases]]\nname = "fx_-1000"\nload = [-1000.0, 0, 0, 0, 0, 0]\n')
    balls = [{"azimuth": k * 2 * math.pi / 22, "inner_load": 3000.0, "outer_load": 3050.0,
              "inner_contact_angle": 0.45, "outer_contact_angle": 0.44} for k in range(22)]
    (run / "quasistatic" / "quasistatic.json").write_text(json.dumps(
        {"inner_race": {"displacement": [4e-5, 0.0, 3e-4], "tilt": [0.0, 9e-4]}, "balls": balls,
         "converged": True, "iterations": 9, "cage_speed": 143.7}))
    summary = _timeseries(scene, run / "simulate" / "timeseries.h5")
    (run / "simulate" / "summary.json").write_text(json.dumps(summary))
    return run, scene, keys


def _no_solving(monkeypatch):
    """Every solver entry point of the other stages fails the test if called."""
    import bearingsim.dynamics.bearing
    import bearingsim.dynamics.quasistatic.solver
    import bearingsim.fe_model

    def boom(*args, **kwargs):
        raise AssertionError("rendering must not solve anything")

    monkeypatch.setattr(bearingsim.dynamics.bearing, "simulate_bearing", boom)
    monkeypatch.setattr(bearingsim.dynamics.quasistatic.solver, "solve_quasistatic", boom)
    monkeypatch.setattr(bearingsim.fe_model, "identify_hinge", boom)
    monkeypatch.setattr("bearingsim.pipeline.staging.runner.run_stages", boom)  # render never runs the pipeline


def test_render_command_regenerates_the_report_without_solving(run_dir, monkeypatch):
    run, scene, keys = run_dir
    _no_solving(monkeypatch)
    monkeypatch.delenv("DISPLAY", raising=False)
    monkeypatch.delenv("WAYLAND_DISPLAY", raising=False)
    h5_mtime = (run / "simulate" / "timeseries.h5").stat().st_mtime_ns
    result = CliRunner().invoke(app, ["render", str(run), "--show"])
    assert result.exit_code == 0, result.output
    assert "no display" in result.output and "off-screen" in result.output  # --show falls back
    out = run / "report"
    for name in ("report.html", "burn_zone_3d.png", "burn_zone_map.png", "fe_fx.png", "fe_fx.vtu", "renders.json",
                 "paraview/balls.pvd", "paraview/outer_race.vtp"):
        assert (out / name).is_file() and (out / name).stat().st_size > 0, name
    assert (run / "simulate" / "timeseries.h5").stat().st_mtime_ns == h5_mtime
    manifest = read_manifest(out)
    assert manifest["status"] == "done"
    assert manifest["key"] == stage_key(REPORT, scene, keys)  # the key `run` would compute

    renders = json.loads((out / "renders.json").read_text())
    burn = renders["burn_zone"]
    # the map covers the settled window t >= 5 ms of summary.json: the start-up rub is not in it
    assert burn["settled"] and burn["window_s"] == pytest.approx([0.005, 0.01])
    assert burn["energy_metal_J"] == 0.0
    # the start-up's metal energy: P on the 80 samples t_k = k dt < 4 ms (dt = 50 µs), trapezoid
    # weights dt/2 for the first and dt for the others (the sample after the last powered one
    # carries P = 0): E = P dt (80 - 1/2) = 100 W × 3.975 ms
    assert burn["startup_metal_energy_J"] == pytest.approx(RUB_POWER * 5e-5 * 79.5, rel=1e-9)
    # film heat: 10 W over the 5 ms of the settled window, all of it on the land
    assert burn["energy_film_J"] == pytest.approx(FILM_POWER * 0.005, rel=1e-9)
    assert burn["energy_total_J"] == pytest.approx(FILM_POWER * 0.005, rel=1e-9)
    # the film is thinnest, and heats most, where the cage is pressed
    assert burn["peak_sector_deg"] == pytest.approx(math.floor(math.degrees(RUB_AZIMUTH)) + 0.5)
    assert burn["track_outside_fraction"] == 0.0  # 25° ± 5° tracks stay inside the raceway
    assert renders["fe"][0]["max_displacement_m"] == pytest.approx(3e-6, rel=1e-12)
    # ParaView: the series the synthetic run holds (balls only: it saved no race or cage motion)
    assert renders["paraview"] == {"balls": "paraview/balls.pvd", "outer_race": "paraview/outer_race.vtp"}

    page = (out / "report.html").read_text()
    assert len(re.findall(r'src="data:image/png;base64,', page)) >= 5  # orbit, map twice, burn 3-D, FE
    assert not re.search(r'src="(?!data:)', page)  # self-contained: no external files
    for text in ("The verdict&#39;s numbers", "Summary metrics", "Burn zone", "Quasi-static", "Hinge", "FE deflections",
                 "Solver counters", "Scene", "Versions", "6.5e+08", "1234", "load case fx = -1000 N",
                 "thinnest land film", "µm", "run too short to settle",
                 "How far to trust this verdict", "docs/validation.md"):
        assert text in page, text
    # the page opens with the verdict: its sentence comes before every other section
    summary = json.loads((run / "simulate" / "summary.json").read_text())
    sentence = summary["verdict"]["text"]
    assert sentence.startswith("Cage pressed onto the outer-race land at 5") and "no metal contact" in sentence
    assert page.index(html.escape(sentence)) < page.index("<details")  # the first screen, before every section
    assert (out / "verdict_orbit.png").is_file()


def test_run_finds_the_rendered_report_up_to_date_and_redraws_when_forced(run_dir, monkeypatch):
    run, scene, _ = run_dir
    if read_manifest(run / "report") is None:
        CliRunner().invoke(app, ["render", str(run)])
    _no_solving(monkeypatch)  # (run_stages was imported by name above: still the real one)
    outcomes = run_stages(scene, run, STAGES, ["report"])
    assert [o.status for o in outcomes] == ["cached"] * 4
    first = (run / "report" / "burn_zone_map.png").read_bytes()
    outcomes = run_stages(scene, run, STAGES, ["report"], force={"report"})  # the `run` path
    assert [o.status for o in outcomes] == ["cached"] * 3 + ["computed"]
    assert (run / "report" / "burn_zone_map.png").read_bytes() == first  # reproducible


def test_render_rejects_a_directory_that_is_not_a_run(tmp_path):
    result = CliRunner().invoke(app, ["render", str(tmp_path)])
    assert result.exit_code == 2 and "not a run directory" in " ".join(result.output.split())


def test_report_metrics_read_as_an_engineers_table(run_dir):
    """No raw summary.json key in a table cell: every metric has a name and a unit."""
    from bearingsim.pipeline.results.summary_keys import numeric_keys

    run, _, _ = run_dir
    if not (run / "report" / "report.html").is_file():
        CliRunner().invoke(app, ["render", str(run)])
    page = (run / "report" / "report.html").read_text()
    summary = json.loads((run / "simulate" / "summary.json").read_text())
    raw = [k for k in numeric_keys(summary) + list(summary)
           if f"<td>{html.escape(k)}</td>" in page or f"<td>{html.escape(k.rpartition('.')[2])}</td>" in page]
    assert raw == []
    assert "<td>cage offset direction, mean</td>" in page and "<td>deg</td>" in page
    # the azimuth 1 rad of the synthetic cage, in degrees 0–360
    assert f"<td>{math.degrees(RUB_AZIMUTH):.0f}</td>" in page


def test_drift_check_compares_directions_on_the_circle():
    from bearingsim.pipeline.render.report import drift_rows

    # 6.27 rad and 0.007 rad: 0.02 rad (0.6°) apart across the 2π wrap, not 6.26 rad
    (row,) = drift_rows({"cage_offset_azimuth_mean": [6.27, 0.007]})
    assert row[1:4] == ["359", "0", "deg"]
    assert row[4] == f"{math.degrees(2 * math.pi - 6.27 + 0.007):.1f}°" and "drifts" not in row[4]
    (row,) = drift_rows({"cage_offset_azimuth_mean": [0.0, 1.0]})
    assert "drifts" in row[4]
    (row,) = drift_rows({"cage_eps_mean": [0.5, 0.52]})
    assert row[4] == "4 %"


def test_the_reports_heat_arc_across_zero_reads_in_0_to_360(tmp_path):
    """docs/outputs.md, Arcs: data keeps end = start + width, text prints both ends in 0–360."""
    from bearingsim.pipeline.render.report import burn_section

    burn = {"sector_deg": [291.0, 397.0], "peak_sector_deg": 330.5, "peak_sector_energy_J": 1.0,
            "peak_areal_density_J_m2": 2.0, "window_s": [0.1, 0.8], "settled": True, "sectors": 360,
            "energy_total_J": 3.0, "land_overlap_mm": 7.6, "track_outside_fraction": 0.0,
            "map": "m.png", "render": "r.png"}
    text = burn_section(burn, tmp_path)
    assert "80 % of the heat in 291.0–37.0° (106° wide)" in text and "397" not in text


def test_the_report_states_the_loads_the_run_used():
    """A --set override changes the loads but not the scene's description text."""
    from bearingsim.pipeline.render.report import operating_line
    from bearingsim.pipeline.scene.load import load_scene

    scene = load_scene("helicopter-b-given-hinge", ["load.moment=300", "solver.duration=0.05"])
    assert "430" in scene.description  # the file's words, unchanged by the override
    line = operating_line(scene, simulated=True)
    assert "moment 300 N·m" in line and "axial 34000 N" in line and "0.05 s simulated" in line
    assert "simulated" not in operating_line(scene, simulated=False)


def test_fe_renders_drawn_beside_are_the_ones_drawn_here(run_dir, tmp_path, monkeypatch):
    """On two cores the report draws the FE load cases in a second process while it draws the
    burn zone: the same records and byte for byte the same files as drawn in this process."""
    from bearingsim.pipeline.machine import cores
    from bearingsim.pipeline.render import run_report

    run, scene, _ = run_dir
    here, beside = tmp_path / "here", tmp_path / "beside"
    here.mkdir()
    beside.mkdir()
    with run_report.fe_renders(scene, run / "identify", here, False, lambda text, f: None, beside=False) as records:
        drawn_here = records()
    # drawing in this process now fails: the records below can only come from the second one
    monkeypatch.setattr(run_report, "render_fe_cases", lambda *a: pytest.fail("drawn in this process"))
    monkeypatch.setattr(cores, "usable_cores", lambda: 2)
    with run_report.fe_renders(scene, run / "identify", beside, False, lambda text, f: None, beside=True) as records:
        drawn_beside = records()
    assert drawn_here and drawn_beside == drawn_here
    assert sorted(p.name for p in here.iterdir()) == sorted(p.name for p in beside.iterdir()) == ["fe_fx.png", "fe_fx.vtu"]
    for path in here.iterdir():
        assert (beside / path.name).read_bytes() == path.read_bytes(), path.name


@pytest.mark.parametrize("failure", ["cannot start", "dies"])
def test_fe_renders_fall_back_to_this_process(run_dir, tmp_path, monkeypatch, caplog, failure):
    """A second process that cannot start, or dies, costs the overlap, not the renders: they are
    drawn here, with a warning that says why."""
    from concurrent.futures import Future, ProcessPoolExecutor
    from concurrent.futures.process import BrokenProcessPool

    from bearingsim.pipeline.machine import cores
    from bearingsim.pipeline.render import run_report

    def submit(self, *args, **kwargs):
        if failure == "cannot start":
            raise OSError(11, "Resource temporarily unavailable")
        future = Future()
        future.set_exception(BrokenProcessPool("a worker was killed"))
        return future

    run, scene, _ = run_dir
    monkeypatch.setattr(cores, "usable_cores", lambda: 2)
    monkeypatch.setattr(ProcessPoolExecutor, "submit", submit)
    with run_report.fe_renders(scene, run / "identify", tmp_path, False, lambda text, f: None, beside=True) as records:
        drawn = records()
    assert [r["file"] for r in drawn] == ["fe_fx.png"] and (tmp_path / "fe_fx.png").is_file()
    assert "drawing them in this process" in caplog.text
