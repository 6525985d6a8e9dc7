"""Fuzz the command line with malformed and extreme scenes: never a traceback, never garbage.

A seeded generator builds scene files (broken TOML, wrong encodings, wrong types, missing or
unknown tables, absurd numbers) and `--set` overrides (every scene key with extreme, wrong-
typed or nested values). Every case goes through `check` and must exit 0 (a valid scene) or
2 (a message naming what is wrong) — never 1 with a traceback, never an uncaught exception.
A few dozen physically varied cases go through `quasistatic --json`: exit 0 must come with a
finite, strictly valid JSON result whose validity list flags what the result's own numbers
say is doubtful (pressure beyond ISO 76's 4.2 GPa, contact ellipses cut by the lands), and
exit 2 with a message; exit 1 (the solver giving up) is a failure, including under the mostly
radial, lightly thrust loads where the free race pivots (docs/model.md §10, M.119). The larger
variants are marked slow.
"""

from __future__ import annotations

import json
import math
import random
from pathlib import Path

import pytest
import tomli_w
from typer.testing import CliRunner

from bearingsim.pipeline.cli.commands import app
from bearingsim.pipeline.scene.load import read_scene_table
from bearingsim.pipeline.scene.validity import STATIC_CAPACITY_PRESSURE

SEED = 20261123
BASES = ("deep-groove-209", "helicopter-b-given-hinge", "helicopter-b")

# every scene key a `--set` may touch, with a plausible value (the mutations start from it)
KEYS = {
    "bearing.ball_diameter": 0.0127, "bearing.ball_count": 9, "bearing.pitch_diameter": 0.065,
    "bearing.inner_conformity": 0.52, "bearing.outer_conformity": 0.52,
    "bearing.diametral_clearance": 1.5e-5, "bearing.inner_shoulder_diameter": 0.06,
    "bearing.outer_shoulder_diameter": 0.07, "bearing.inner_bore_diameter": 0.045,
    "bearing.outer_outside_diameter": 0.085, "bearing.width": 0.019,
    "bearing.inner_groove_center_diameter": 0.1584, "bearing.outer_groove_center_diameter": 0.1573,
    "bearing.inner_groove_radius": 0.009753, "bearing.outer_groove_radius": 0.009906,
    "cage.mean_diameter": 0.158, "cage.pocket_diameter": 0.02023, "cage.radial_thickness": 0.00742,
    "cage.width": 0.0254, "cage.guidance": "outer",
    "materials.ball.youngs_modulus": 208e9, "materials.ball.poisson_ratio": 0.3,
    "materials.ball.density": 7850.0, "materials.race.youngs_modulus": 208e9,
    "materials.cage.density": 8800.0,
    "lubricant.name": "nato-o156", "lubricant.temperature_degC": 100.0,
    "load.axial": 34000.0, "load.radial": 8900.0, "load.moment": 430.0, "load.step_time": 0.01,
    "load.step_moment": 600.0, "speed.inner_rpm": 3060.0, "speed.outer_rpm": 0.0,
    "hinge.source": "given", "hinge.translational": [1e9, 1e9, 1e9], "hinge.bending": [1e5, 1e5],
    "hinge.damping_ratio_time": 1e-6, "solver.alpha": 0.1, "solver.duration": 0.8,
    "solver.first_step": 1e-6, "solver.min_step": 1e-8, "solver.max_step": 2e-6, "solver.rtol": 1e-4,
    "solver.atol": 1e-9, "physics.traction": "eyring", "physics.cage_race": "hybrid",
    "physics.ehd_film": True, "physics.centrifugal": True, "physics.min_film": 5e-8,
    "physics.cage_race_lands": 2, "output.sample_interval": 1e-5, "fe.mesh_size": 0.03,
    "fe.element_order": 2, "name": "fuzz", "description": "text",
}
EXTREMES = ["0", "-0.0", "1e-300", "1e300", "-1e9", "1e9", "inf", "-inf", "nan", "2e6", "-1",
            str(2**70), "1e-12", "0.5", "3", "true", '"text"', '"[m] :smile: [lubricant]"', "[]", "[1, 2]",
            "[[1, 2], [3]]", "{ a = 1 }", '""', "'\\u0000'", "1979-05-27", "[" * 60 + "]" * 60,
            "x" * 400, "1_000", "0x10", '"   "', "-5e-3", "12.7", "207.7", "7.85"]
BOGUS_KEYS = ["bearing.ball_diamter", "load", "load.moment.x", "nope.key", "materials.ball",
              "materials.steel.density", "cage", "solver.tol", "physics", ".", "a..b", "name.x",
              "hinge.translational[0]", "x" * 300]


def mutate(value, rng: random.Random) -> str:
    """A TOML literal near, far from, or of another type than `value`."""
    roll = rng.random()
    if isinstance(value, (int, float)) and not isinstance(value, bool) and roll < 0.45:
        exponent = rng.choice([-12, -6, -3, -1, 0, 1, 3, 6, 12])
        sign = -1 if rng.random() < 0.15 else 1
        return repr(sign * float(value) * 10.0 ** exponent * rng.uniform(0.5, 2.0))
    if roll < 0.85:
        return rng.choice(EXTREMES)
    return tomli_w.dumps({"v": value})[4:].strip()


FORM1 = ("inner_groove_center_diameter", "outer_groove_center_diameter", "inner_groove_radius",
         "outer_groove_radius")
FORM2 = ("pitch_diameter", "inner_conformity", "outer_conformity", "diametral_clearance")


def keys_for(base: str) -> list[str]:
    """The keys that fit the base scene's geometry form (deep-groove-209: catalogue form, no
    cage); a few foreign ones stay in through BOGUS_KEYS and the broken files."""
    if base == "deep-groove-209":
        return sorted(k for k in KEYS if not k.startswith(("cage.", "lubricant.", "materials.cage"))
                      and k.split(".")[-1] not in FORM1)
    return sorted(k for k in KEYS if k.split(".")[-1] not in FORM2)


def set_args(rng: random.Random, n: int, base: str = "helicopter-b") -> list[str]:
    out = []
    keys = keys_for(base)
    for _ in range(n):
        if rng.random() < 0.12:
            key = rng.choice(BOGUS_KEYS)
            out.append(f"{key}={rng.choice(EXTREMES)}")
        elif rng.random() < 0.04:
            out.append(rng.choice(["noequals", "=5", "load.moment=", " = ", "load.moment==3"]))
        else:
            key = rng.choice(keys)
            out.append(f"{key}={mutate(KEYS[key], rng)}")
    return [a for pair in (("--set", a) for a in out) for a in pair]


def broken_file(rng: random.Random, directory: Path, i: int) -> str:
    """A scene file damaged in one of several ways."""
    table, _ = read_scene_table(rng.choice(BASES))
    text = tomli_w.dumps(table)
    kind = rng.randrange(9)
    path = directory / f"case{i}.toml"
    if kind == 0:
        path.write_bytes(text.encode() + b"\nbad = \"\xff\xfe\"\n")  # not UTF-8
    elif kind == 1:
        path.write_text(text[: rng.randrange(len(text))])  # truncated
    elif kind == 2:
        path.write_text("name = 'deep'\nv = " + "[" * 3000 + "]" * 3000 + "\n")
    elif kind == 3:
        section = rng.choice([k for k in table if isinstance(table[k], dict)])
        table.pop(section)
        path.write_text(tomli_w.dumps(table))  # a required table missing (or an optional one)
    elif kind == 4:
        table[rng.choice(["bogus", "Bearing", "loads"])] = {"x": 1}
        path.write_text(tomli_w.dumps(table))
    elif kind == 5:
        section = rng.choice([k for k in table if isinstance(table[k], dict)])
        table[section] = rng.choice([1, "text", [1, 2], True])
        path.write_text(tomli_w.dumps(table))
    elif kind == 6:  # a scene written in millimetres
        bearing = table["bearing"]
        for k, v in list(bearing.items()):
            if isinstance(v, float) and k != "inner_conformity" and k != "outer_conformity":
                bearing[k] = v * 1000.0
        path.write_text(tomli_w.dumps(table))
    elif kind == 7:
        path.write_bytes(bytes(rng.randrange(256) for _ in range(rng.randrange(1, 400))))
    else:
        path.write_text(text.replace("=", "= = ", 1))
    return str(path)


def cases(n: int, directory: Path):
    rng = random.Random(SEED)
    for i in range(n):
        if rng.random() < 0.3:
            yield broken_file(rng, directory, i), set_args(rng, rng.randrange(0, 3))
        else:
            base = rng.choice(BASES)
            yield base, set_args(rng, rng.randrange(1, 4), base)


def assert_clean(result, args) -> None:
    """Exit 0, 2, or 4 (check: valid for the quasi-static stage, refused by simulate), and on 2 a
    message rather than a traceback."""
    assert result.exit_code in (0, 2, 4), (args, result.exit_code, result.output, result.exception)
    assert result.exception is None or isinstance(result.exception, SystemExit), (args, repr(result.exception))
    assert "Traceback" not in result.output, (args, result.output)
    if result.exit_code == 2:
        assert "error:" in result.stderr, (args, result.output)


@pytest.mark.parametrize("chunk", range(4))
def test_check_never_crashes(chunk, tmp_path):
    """240 generated cases through `check` (four chunks so a failure names fewer)."""
    runner = CliRunner()
    all_cases = list(cases(240, tmp_path))
    for scene, args in all_cases[chunk * 60:(chunk + 1) * 60]:
        argv = ["check", scene, *args]
        assert_clean(runner.invoke(app, argv), argv)


def strict_json(text: str):
    def reject(name):
        raise ValueError(f"non-standard JSON constant {name}")
    return json.loads(text, parse_constant=reject)


def physical_cases(n: int, seed: int):
    """Quasi-static scenes from plausible to absurd: loads over ten decades, clearance up to
    and past the geometric limit, the moment that truncates the contact ellipses."""
    rng = random.Random(seed)
    for _ in range(n):
        base = rng.choice(("deep-groove-209", "helicopter-b-given-hinge"))
        sets = []
        if base == "deep-groove-209":
            sets.append(f"load.radial={10 ** rng.uniform(0, 9.5):.6g}")
            if rng.random() < 0.4:
                sets.append(f"bearing.diametral_clearance={rng.uniform(-2e-5, 1.3e-3):.6g}")
            if rng.random() < 0.3:
                sets.append(f"load.axial={rng.choice([-1, 1]) * 10 ** rng.uniform(1, 8):.6g}")
        elif rng.random() < 0.3:  # mostly radial, light axial load: the free race pivots (docs/model.md M.119)
            sets.append(f"load.axial={rng.choice([-1, 1]) * 10 ** rng.uniform(1, 4):.6g}")
            sets.append(f"load.radial={10 ** rng.uniform(3, 4.7):.6g}")
            sets.append(f"load.moment={rng.choice([0, -1, 1]) * 10 ** rng.uniform(0, 3):.6g}")
        else:
            sets.append(f"load.moment={rng.choice([-1, 1]) * 10 ** rng.uniform(0, 5.2):.6g}")
            if rng.random() < 0.5:
                sets.append(f"load.axial={10 ** rng.uniform(2, 6.5):.6g}")
            if rng.random() < 0.3:
                sets.append(f"load.radial={10 ** rng.uniform(2, 6.5):.6g}")
        yield base, [a for s in sets for a in ("--set", s)]


def finite_numbers(obj) -> bool:
    if isinstance(obj, dict):
        return all(finite_numbers(v) for v in obj.values())
    if isinstance(obj, list):
        return all(finite_numbers(v) for v in obj)
    return not isinstance(obj, float) or math.isfinite(obj)


def check_quasistatic_case(runner, base, args, out: Path) -> str:
    argv = ["quasistatic", base, "--json", "--out", str(out), *args]
    result = runner.invoke(app, argv)
    assert_clean(result, argv)  # exit 0 or 2: a solver failure (exit 1) is a defect (README, exit codes)
    if result.exit_code == 2:
        return "refused"
    payload = strict_json(result.stdout)
    assert finite_numbers(payload) and payload["converged"], argv
    validity = payload["validity"]
    text = " ".join(f["message"] for f in validity)
    loaded = [(b, s) for b in payload["balls"] for s in ("inner", "outer") if (b[f"{s}_load"] or 0) > 0]
    assert all(abs(b[f"{s}_contact_angle"]) < math.pi / 2 for b, s in loaded), argv
    p_max = max((b[f"max_pressure_{s}"] for b, s in loaded), default=0.0)
    assert (p_max > STATIC_CAPACITY_PRESSURE) == ("contact pressure" in text), (argv, p_max, text)
    cut = any((b[f"truncation_margin_{s}"] is not None and b[f"truncation_margin_{s}"] < 0) for b, s in loaded)
    assert cut == ("truncates" in text), (argv, text)
    # what the console and run.log said is the same list
    manifest = json.loads((out / "quasistatic" / "stage.json").read_text())
    assert manifest["validity"] == validity
    return "flagged" if validity else "clean"


def test_quasistatic_results_are_finite_and_flagged(tmp_path):
    """24 physical cases through `quasistatic --json` (about 1.5 s each)."""
    runner = CliRunner()
    seen = [check_quasistatic_case(runner, base, args, tmp_path / f"r{i}")
            for i, (base, args) in enumerate(physical_cases(24, SEED))]
    # the generator reaches all three outcomes (a fuzzer that never leaves the safe region tests nothing)
    assert {"refused", "flagged", "clean"} <= set(seen), seen


@pytest.mark.slow
def test_quasistatic_fuzz_large(tmp_path):
    """200 physical cases, exit 0 or 2 only (README, exit codes; a few minutes)."""
    runner = CliRunner()
    for i, (base, args) in enumerate(physical_cases(200, SEED + 1)):
        check_quasistatic_case(runner, base, args, tmp_path / f"r{i}")


@pytest.mark.slow
def test_check_fuzz_large(tmp_path):
    runner = CliRunner()
    for scene, args in cases(2000, tmp_path):
        argv = ["check", scene, *args]
        assert_clean(runner.invoke(app, argv), argv)
