"""The `bearingsim` command line: outputs, exit codes, and that light commands stay light."""

from __future__ import annotations

import subprocess
import sys

import pytest

from typer.testing import CliRunner

from bearingsim.pipeline.cli.commands import app

runner = CliRunner()


def test_check_prints_derived_geometry_of_reference_bearing():
    """pitch ≈ 158.003 mm, alpha_0 ≈ 25.43°, P_d = 0.118 mm (docs/model.md §2)."""
    result = runner.invoke(app, ["check", "helicopter-b"])
    assert result.exit_code == 0, result.output
    out = result.output

    def row(label: str) -> tuple[float, str]:
        line = next(ln for ln in out.splitlines() if ln.startswith(label))
        value, unit = line[len(label):].split()[-2:]
        return float(value), unit

    assert row("pitch diameter d_m") == (pytest.approx(158.003, abs=5e-4), "mm")
    assert row("free contact angle alpha_0") == (pytest.approx(25.43, abs=0.005), "deg")
    assert row("diametral clearance P_d") == (pytest.approx(0.118, abs=5e-7), "mm")
    assert "N.m" in out and "rad/s" in out  # every section shows its units


def test_scenes_lists_builtins():
    result = runner.invoke(app, ["scenes"])
    assert result.exit_code == 0
    for name in ("helicopter-a", "helicopter-b", "helicopter-b-given-hinge"):
        assert name in result.output


def test_scenes_prints_a_builtin_scene_to_start_from(tmp_path):
    """`bearingsim scenes NAME > mine.toml` gives a file that loads as the same scene."""
    from bearingsim.pipeline.scene.load import load_scene

    result = runner.invoke(app, ["scenes", "helicopter-b-given-hinge"])
    assert result.exit_code == 0 and result.stderr == ""
    mine = tmp_path / "mine.toml"
    mine.write_text(result.stdout)
    assert load_scene(str(mine)).raw == load_scene("helicopter-b-given-hinge").raw
    missing = runner.invoke(app, ["scenes", "helicopter-c"])
    assert missing.exit_code == 2 and "built-in scenes: acbb-7210-inner-guided, deep-groove-209" in missing.stderr


def test_bad_scene_exits_2_naming_the_key():
    result = runner.invoke(app, ["check", "helicopter-b", "--set", "bearing.ball_count=0"])
    assert result.exit_code == 2
    assert "bearing.ball_count" in result.output


def test_render_of_a_non_run_directory_is_a_clear_error(tmp_path):
    result = runner.invoke(app, ["render", str(tmp_path)])
    assert result.exit_code == 2 and "scene.toml" in result.output


def test_light_commands_do_not_import_heavy_libraries():
    """docs/contributing.md rule 6: scene checking must not pay for gmsh, pyvista or matplotlib."""
    code = (
        "import sys; from typer.testing import CliRunner; from bearingsim.pipeline.cli.commands import app;"
        "r = CliRunner().invoke(app, ['check', 'helicopter-b-given-hinge']);"
        "assert r.exit_code == 0, r.output;"
        "heavy = [m for m in ('gmsh', 'pyvista', 'vtk', 'matplotlib', 'skfem') if m in sys.modules];"
        "print(heavy); sys.exit(1 if heavy else 0)"
    )
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert proc.returncode == 0, proc.stdout + proc.stderr


def test_a_second_run_into_a_busy_run_directory_is_refused(tmp_path):
    # two processes writing one run directory would swap stage results over each other
    from bearingsim.pipeline.staging.artefacts import run_directory_lock

    with run_directory_lock(tmp_path):
        result = CliRunner().invoke(app, ["quasistatic", "deep-groove-209", "--out", str(tmp_path)])
    assert result.exit_code == 1
    assert "another bearingsim process is writing" in result.output and "--out" in result.output
    assert not (tmp_path / "quasistatic").exists()
    result = CliRunner().invoke(app, ["quasistatic", "deep-groove-209", "--json", "--out", str(tmp_path)])
    assert result.exit_code == 0, result.output


def test_check_prints_the_thermal_table_resolved():
    """A part not given takes the oil's temperature; default expansions are shown by value
    (docs/scenes.md: steel 11.9e-6, cage bronze 18e-6 1/K)."""
    result = runner.invoke(app, ["check", "helicopter-b", "--set", "thermal.cage_degC=120"])
    assert result.exit_code == 0, result.output
    lines = result.stdout.splitlines()
    start = next(i for i, ln in enumerate(lines) if ln.startswith("[thermal] (resolved)"))
    value = {" ".join(ln.split()[:-2]): ln.split()[-2] for ln in lines[start + 1:start + 9]}  # key, value, unit
    assert value["cage_degC"] == "120" and value["ball_degC"] == "100"  # oil at 100 degC
    assert float(value["expansion of the race"]) == pytest.approx(11.9e-6)
    assert float(value["expansion of the cage"]) == pytest.approx(18e-6)


def test_quasistatic_prints_units_and_the_stiffness(tmp_path):
    """README command table: ball loads, contact angles, displacement and tilt, stiffness."""
    result = CliRunner().invoke(app, ["quasistatic", "deep-groove-209", "--out", str(tmp_path)])
    assert result.exit_code == 0, result.output
    for header in ("azimuth [deg]", "Q_i [N]", "alpha_i [deg]", "alpha_o [deg]"):
        assert header in result.stdout
    assert "bearing stiffness, diagonal" in result.stdout and "dz " in result.stdout


def test_help_shows_units_and_defaults_in_square_brackets():
    """typer renders help as rich markup, where "[s]" or "[default: ...]" would be taken for tags
    and vanish ("Simulated window per case ." instead of "[s]"): every bracketed part of every
    option's help must reach the rendered --help (whitespace and box lines ignored)."""
    import re
    import typing

    from bearingsim.pipeline.cli.commands import app

    def squeeze(text: str) -> str:
        return re.sub(r"[\s│]+", "", text)

    checked = 0
    for info in app.registered_commands:
        shown = squeeze(runner.invoke(app, [info.callback.__name__.replace("_", "-"), "--help"]).output)
        for ann in typing.get_type_hints(info.callback, include_extras=True).values():
            for meta in getattr(ann, "__metadata__", ()):
                for part in re.findall(r"\[[^\]]*\]", getattr(meta, "help", None) or ""):
                    assert squeeze(part) in shown, (info.callback.__name__, part)
                    checked += 1
    assert checked >= 10
