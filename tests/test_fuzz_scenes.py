"""Fuzz the command line with malformed and extreme scenes: never a traceback, never garbage.

A seeded generator builds scene files (broken TOML, wrong encodings, wrong types, missing or
unknown tables, absurd numbers) and `--set` overrides (every scene key with extreme, wrong-
typed or nested values: integers no float holds, 1e308, 1e-300, markup, ESC sequences, a 20 kB
string). Every case goes through `check` and must exit 0 (a valid scene) or
2 (a message naming what is wrong) — never 1 with a traceback, never an uncaught exception —
and a scene it accepts must hold no value that cannot exist (`impossible`: an oracle of
physical facts written apart from the scene's own checks). 120 generated `[tolerances]` tables
go through `check` the same way, their ranges held to the same oracle at their ends, and 72
generated option values (sweep plans, stability windows, scheduler addresses, `render` of
folders that are not runs) must be usage errors or sound, writing nothing into a user's folder.
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

import numpy as np
from pathlib import Path

import pytest
import tomli_w
from typer.testing import CliRunner

from bearingsim.pipeline.cli.commands import app
from bearingsim.pipeline.scene.load import load_scene, read_scene_table
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
            "x" * 400, "1_000", "0x10", '"   "', "-5e-3", "12.7", "207.7", "7.85",
            # numbers no float holds, or at the edges of the model's sizes; text that is markup or control
            "9" * 400, "9" * 5000, "1e308", "-1e308", "-1e-300", "1e29", "1e-29", "1e31", str(2**63), str(-2**63),
            '"[/] [b]bold[/b] [red]"', '"\\u001b[31m red \\u001b[0m"', '"' + "x" * 20000 + '"']
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


def assert_clean(result, args, usage: bool = False) -> None:
    """Exit 0, 2, or 4 (check: valid for the quasi-static stage, refused by simulate), and on 2 a
    message rather than a traceback (`usage`: or typer's usage error for an option value of the
    wrong type)."""
    assert result.exit_code in (0, 2, 4), (args, result.exit_code, result.output, result.exception)
    assert result.exception is None or isinstance(result.exception, SystemExit), (args, repr(result.exception))
    assert "Traceback" not in result.output, (args, result.output)
    if result.exit_code == 2:
        assert "error:" in result.stderr or (usage and "Invalid value" in result.stderr), (args, result.output)


@pytest.mark.parametrize("chunk", range(4))
def test_check_never_crashes(chunk, tmp_path):
    """240 generated cases through `check` (four chunks so a failure names fewer); a scene it
    accepts holds no value that cannot exist (`impossible`)."""
    runner = CliRunner()
    all_cases = list(cases(240, tmp_path))
    for scene, args in all_cases[chunk * 60:(chunk + 1) * 60]:
        argv = ["check", scene, *args]
        result = runner.invoke(app, argv)
        assert_clean(result, argv)
        if result.exit_code in (0, 4):
            problem = impossible(load_scene(scene, args[1::2]))
            assert problem is None, (argv, problem)


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


# --- what cannot exist: an oracle of physical facts, apart from the scene's own checks -------------
ABSOLUTE_ZERO_DEGC = -273.15
LARGEST, SMALLEST = 1e30, 1e-30  # a double's product of ten such numbers stays finite and non-zero


def impossible(scene) -> str | None:
    """The first value of an accepted scene that no bearing can have, or None: a number beyond
    what the model's arithmetic holds, a size of zero or less, a part below absolute zero, a
    Poisson ratio outside (-1, 1/2), a ball that does not fit its pocket or groove, a cage outside
    the rings, or a tolerance whose range reaches any of these."""
    import dataclasses

    parts = scene.nominal
    for section, obj in (("bearing", parts.bearing), ("cage", parts.cage), ("materials.ball", parts.materials.ball),
                         ("materials.race", parts.materials.race), ("materials.cage", parts.materials.cage),
                         ("load", scene.load), ("speed", scene.speed), ("solver", scene.solver),
                         ("physics", scene.physics), ("lubricant", scene.lubricant), ("hinge", scene.hinge)):
        if obj is None:
            continue
        for f in dataclasses.fields(obj):
            for value in (v for v in np.ravel(getattr(obj, f.name) if getattr(obj, f.name) is not None else [])
                          if isinstance(v, (int, float, np.floating)) and not isinstance(v, bool)):
                if not math.isfinite(value) or abs(value) > LARGEST or 0 < abs(value) < SMALLEST:
                    return f"{section}.{f.name} = {value!r} is beyond what the model computes with"
    b, c, m = parts.bearing, parts.cage, parts.materials
    if min(b.ball_diameter, b.inner_groove_radius, b.outer_groove_radius) <= 0.0:
        return "a non-positive ball or groove size"
    if min(b.inner_groove_radius, b.outer_groove_radius) <= 0.5 * b.ball_diameter:
        return "a groove tighter than the ball"
    for material in (x for x in (m.ball, m.race, m.cage) if x is not None):
        if material.youngs_modulus <= 0 or material.density <= 0 or not -1.0 < material.poisson_ratio < 0.5:
            return f"an impossible material {material}"
    temperatures = scene.temperatures
    if min(temperatures.inner_ring, temperatures.outer_ring, temperatures.ball, temperatures.cage) <= ABSOLUTE_ZERO_DEGC:
        return "a part below absolute zero"
    if c is not None:
        if c.pocket_diameter <= b.ball_diameter:
            return "a pocket smaller than its ball"
        outer = b.outer_shoulder_diameter or b.outer_groove_bottom_diameter
        inner = b.inner_shoulder_diameter or b.inner_groove_bottom_diameter
        if not inner < c.bore_diameter < c.outside_diameter < outer:
            return "a cage that is not between the rings"
    return _impossible_tolerances(scene) if scene.tolerances is not None else None


def _impossible_tolerances(scene) -> str | None:
    """A tolerance whose range (a uniform end, a normal one at 3 sd), the others nominal, reaches
    a part that cannot exist."""
    b, c, t = scene.nominal.bearing, scene.nominal.cage, scene.temperatures
    for d in scene.tolerances.deviations:
        for end in ((d.lower, d.upper) if d.kind == "uniform" else (-3 * d.sd, 3 * d.sd)):
            if d.name == "pocket_diameter" and c.pocket_diameter + end <= b.ball_diameter:
                return f"tolerances.{d.name} reaches a pocket smaller than its ball ({end:g} m)"
            if d.name == "ball_diameter" and not 0 < b.ball_diameter + end < c.pocket_diameter:
                return f"tolerances.{d.name} reaches a ball that does not fit ({end:g} m)"
            if d.name in ("cage_outside_diameter", "cage_bore_diameter"):
                od = c.outside_diameter + (end if d.name == "cage_outside_diameter" else 0.0)
                bore = c.bore_diameter + (end if d.name == "cage_bore_diameter" else 0.0)
                if not 0 < bore < od:
                    return f"tolerances.{d.name} reaches a cage without a wall ({end:g} m)"
            if d.name.endswith("_land_diameter") and getattr(b, d.name.replace("land", "shoulder")) + end <= 0:
                return f"tolerances.{d.name} reaches a land of no size ({end:g} m)"
            if d.name.endswith("_temperature") and getattr(t, d.name[:-len("_temperature")]) + end <= ABSOLUTE_ZERO_DEGC:
                return f"tolerances.{d.name} reaches below absolute zero ({end:g} K)"
    return None


QUANTITY_SCALES = {"pocket_diameter": 1e-3, "cage_outside_diameter": 1e-3, "cage_bore_diameter": 1e-3,
                   "outer_land_diameter": 1e-3, "inner_land_diameter": 1e-3, "ball_diameter": 1e-3,
                   "diametral_clearance": 1e-4, "pocket_circle_eccentricity": 1e-4, "inner_ring_temperature": 100.0,
                   "outer_ring_temperature": 100.0, "ball_temperature": 100.0, "cage_temperature": 100.0,
                   "moment": 300.0, "axial": 3e4}


def tolerance_args(rng: random.Random) -> list[str]:
    """A [tolerances] table as --set overrides: ranges from tight to impossible, some malformed."""
    out = [f"tolerances.samples={rng.choice([100, 1000, 99, 10**7, '1e3', 'true'])}",
           f"tolerances.seed={rng.choice([0, 7, 2**53 + 1, -1, 10**30, '0.5'])}"]
    for name in rng.sample(sorted(QUANTITY_SCALES), rng.randrange(1, 4)):
        scale = QUANTITY_SCALES[name] * 10.0 ** rng.uniform(-4, 1.5)
        roll = rng.random()
        if roll < 0.45:
            lo = -scale * rng.uniform(0, 1)
            out.append(f"tolerances.{name}={{lower = {lo!r}, upper = {scale * rng.uniform(0, 1)!r}}}")
        elif roll < 0.9:
            out.append(f"tolerances.{name}={{sd = {scale * rng.uniform(0.1, 1)!r}}}")
        else:
            out.append(f"tolerances.{name}={rng.choice(['{sd = -1}', '{lower = 1, upper = 0}', '{mean = 1}', '1', '{sd = 1e308}', '{lower = -1e31, upper = 0}'])}")
    return [a for pair in (("--set", x) for x in out) for a in pair]


def test_tolerance_tables_are_refused_or_possible():
    """120 generated [tolerances] tables through `check`: a refusal names a key, and a table it
    accepts reaches no part that cannot exist at the ends of its ranges."""
    runner = CliRunner()
    rng = random.Random(SEED + 2)
    seen = set()
    for _ in range(120):
        args = tolerance_args(rng)
        argv = ["check", "helicopter-b-given-hinge", *args]
        result = runner.invoke(app, argv)
        assert_clean(result, argv)
        seen.add(result.exit_code)
        if result.exit_code in (0, 4):
            problem = impossible(load_scene("helicopter-b-given-hinge", args[1::2]))
            assert problem is None, (argv, problem)
    assert seen == {0, 2}  # the generator reaches both


def option_cases(rng: random.Random, tmp_path: Path):
    """Command lines whose options are generated: sweep plans (dry run), stability windows,
    scheduler addresses, render of folders that are not runs."""
    numbers = ["0", "-1", "1e-300", "1e-5", "2e-5", "0.01", "1e308", "inf", "nan", "abc", "9" * 400, "1e30"]
    for i in range(72):
        kind = i % 4
        if kind == 0:
            vary = rng.choice(["load.moment=0:600:13", "load.moment=0:600:0", "load.moment=a,b", "x.y=1,2",
                               "load.moment=1e308,0", "load.moment=" + "9" * 400, "load.moment=0:1:20000",
                               "load.moment=[/],1", "description=[/],ok", "load.moment=100,100.0,1e2"])
            yield ["sweep", "deep-groove-209", "--vary", vary, "--dry-run", "--out", str(tmp_path / f"s{i}"),
                   "--mode", rng.choice(["factorial", "list", "nope"]), "--max-points", rng.choice(["1", "100", "10000"])]
        elif kind == 1:
            yield ["stability", "dry-contact", "--window", rng.choice(numbers), "--wall-budget", rng.choice(numbers),
                   "--out", str(tmp_path / f"st{i}")]
        elif kind == 2:
            address = rng.choice(["not a url", "tcp://h:0", "tcp://h", "http://h:1", "", "h:99999", ":8786",
                                  "tcp://[::1]:70000", "[/]", "\x1b[31m"])
            yield ["sweep", "deep-groove-209", "--vary", "load.radial=1000,2000", "--scheduler", address,
                   "--out", str(tmp_path / f"sc{i}")]
        else:
            folder = tmp_path / f"user{i}"
            folder.mkdir()
            (folder / rng.choice(["scene.toml", "run.log", "notes.txt"])).write_text("mine\n")
            yield ["render", str(folder)]


def test_option_values_are_refused_or_sound(tmp_path, monkeypatch):
    """72 generated option values: exit 0 or 2 with a message, never a traceback; an accepted
    stability window holds samples and a finite budget (the suite itself is replaced by a stub:
    nothing is integrated here), and a folder that is not a run directory is left as it was."""
    from bearingsim.pipeline.studies import stability

    accepted = []
    monkeypatch.setattr(stability, "run_suite", lambda names, window, budget, progress=None: accepted.append(
        (window, budget)) or [])
    monkeypatch.setattr(stability, "write_suite", lambda results, out: [])
    runner = CliRunner()
    for argv in option_cases(random.Random(SEED + 3), tmp_path):
        before = sorted(p.name for p in Path(argv[1]).iterdir()) if argv[0] == "render" else None
        result = runner.invoke(app, argv)
        assert_clean(result, argv, usage=True)
        if before is not None:
            assert result.exit_code == 2 and sorted(p.name for p in Path(argv[1]).iterdir()) == before, argv
    for window, budget in accepted:
        assert math.isfinite(window) and window >= stability.MIN_WINDOW and 0 < budget <= 1e30, (window, budget)
