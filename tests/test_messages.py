"""Messages speak in scene keys and keep their units (README, exit codes and messages).

Every dotted scene key a message names must exist in docs/scenes.md; the solvers' own hints
(`tol`, `max_newton_iter`, ...), which name no scene key, are translated by
pipeline.console.explain before the user reads them. Rich must not eat `[s]` or `[m]` as
markup, nor turn `:smile:` into an emoji.
"""

from __future__ import annotations

import ast
import re
from pathlib import Path

import pytest
from typer.testing import CliRunner

from bearingsim.pipeline.cli.commands import app
from bearingsim.pipeline.console import INTEGRATION_HINTS, PHRASES, explain

ROOT = Path(__file__).parents[1]
SECTIONS = "bearing|cage|materials|lubricant|load|speed|hinge|fe|solver|physics|output|sweep"
KEY = re.compile(rf"(?<![\w./`])({SECTIONS})\.([a-z_][a-z0-9_]*(?:\.[a-z_][a-z0-9_]*)?)(?![\w(])")
NOT_KEYS = re.compile(r"\.(toml|json|csv|h5|png|py|md|log)$")
OWN_FILES = ("cli/commands.py", "console.py", "scene/validity.py", "scene/load.py", "scene/schema.py",
             "staging/runner.py", "staging/artefacts.py", "staging/provenance.py")
runner = CliRunner()


def documented_keys() -> set[str]:
    """`section.key` for every row of the key tables of docs/scenes.md."""
    keys, sections = set(), []
    for line in (ROOT / "docs" / "scenes.md").read_text().splitlines():
        if line.startswith("## "):
            sections = re.findall(r"\[([a-z_.]+)\]", line)
        row = re.match(r"\|\s*`([a-z_0-9]+)`\s*\|", line)
        if row:
            keys.update(f"{s}.{row.group(1)}" for s in sections)
    keys.update({"sweep.vary", "sweep.points"})  # the sub-tables of [sweep], documented in its text
    return keys


KEYS = documented_keys()


def named_keys(text: str) -> set[str]:
    return {m.group(0) for m in KEY.finditer(text) if not NOT_KEYS.search(m.group(0))}


def unknown(text: str) -> set[str]:
    return {k for k in named_keys(text) if k not in KEYS and not any(v.startswith(k + ".") for v in KEYS)}


def string_literals(path: Path):
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Constant) and isinstance(node.value, str):
            yield node.lineno, node.value


def test_the_key_table_is_read():
    assert {"load.moment", "solver.max_step", "materials.ball.density", "output.sample_interval"} <= KEYS


def test_the_translated_hints_name_only_scene_keys():
    for text in [*INTEGRATION_HINTS.values(), *(new for _, new in PHRASES)]:
        assert not unknown(text), (text, unknown(text))


def test_every_integrator_failure_has_a_translated_hint():
    from bearingsim.dynamics.multibody.results import IntegrationError, Result

    for result in Result:
        if result is Result.SUCCESSFUL:
            continue
        assert result.value in INTEGRATION_HINTS, result
        message = explain(IntegrationError(0.0125, 1e-7, result.value, result.hint))
        assert message.startswith("integration stopped at t = 0.0125 s") and not unknown(message), message
        advice = message.split(". Try: ", 1)[1]
        for word in ("max_newton_iter", "newton_tol", "reuse_jacobian", "tangents"):
            assert word not in advice, (word, message)


def test_each_translated_phrase_still_occurs_in_the_code():
    """A solver message reworded upstream would slip past its translation: fail instead."""
    sources = "".join(p.read_text() for folder in ("dynamics", "fe_model", "pipeline")
                      for p in (ROOT / folder).rglob("*.py") if p.name != "console.py")
    for old, _ in PHRASES:
        assert old in sources, old


def test_quasistatic_newton_hint_loses_tol():
    from bearingsim.dynamics.quasistatic.solver import QuasiStaticError

    exc = QuasiStaticError("Newton diverged at 0.02 % of the load (residual 0.1 N): the bearing probably "
                           "cannot carry it (contact angles near the groove limit). Try a smaller load, check "
                           "the clearance and groove radii, or loosen `tol`.")
    text = explain(exc)
    assert "tol" not in text and "bearing.diametral_clearance" in text and not unknown(text)


@pytest.mark.parametrize("name", OWN_FILES)
def test_messages_of_the_command_line_and_scene_layer_name_real_keys(name):
    for line, text in string_literals(ROOT / "pipeline" / name):
        assert not unknown(text), (name, line, text, unknown(text))


def test_messages_anywhere_name_keys_the_docs_know():
    """All sources: a dotted key in a message is a documented key, one mentioned in
    docs/scenes.md, or a solver hint that explain() replaces (dynamics/multibody/results.py)."""
    docs = (ROOT / "docs" / "scenes.md").read_text()
    replaced = ROOT / "dynamics" / "multibody" / "results.py"
    for folder in ("pipeline", "dynamics", "fe_model", "meshes"):
        for path in (ROOT / folder).rglob("*.py"):
            if path == replaced:
                continue
            for line, text in string_literals(path):
                bad = {k for k in unknown(text) if k not in docs}
                assert not bad, (str(path.relative_to(ROOT)), line, bad)


# --- units and scene text survive the console ------------------------------------------------
def test_units_stay_in_range_messages():
    """Issue case 6: 'allowed > 0 ' without its unit."""
    result = runner.invoke(app, ["check", "helicopter-b-given-hinge", "--set", "solver.duration=-1"])
    assert result.exit_code == 2
    assert "solver.duration: -1 is out of range: allowed > 0 [s]" in result.stderr
    result = runner.invoke(app, ["check", "helicopter-b-given-hinge", "--set", "speed.inner_rpm=fast"])
    assert "[rev/min]" in result.stderr


def test_scene_text_is_printed_verbatim():
    result = runner.invoke(app, ["check", "helicopter-b-given-hinge", "--set", 'description="a:smile:b"'])
    assert result.exit_code == 0 and "a:smile:b" in result.stdout, result.output
    assert "\U0001f604" not in result.output
    result = runner.invoke(app, ["check", "helicopter-b-given-hinge", "--set", 'load.moment="[lubricant] :x:"'])
    assert result.exit_code == 2 and "'[lubricant] :x:'" in result.stderr
