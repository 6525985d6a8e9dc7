"""Text from users is shown as written, never read as markup or terminal control
(docs/reliability.md): a description holding `[/]`, `[b]` or `[red]`, an ESC sequence in a
scene, a sweep value of `[/]`; and a long description costs `check` time in proportion to its
length (rich's word wrap is quadratic in a long word: text that long is not wrapped by it)."""

from __future__ import annotations

import io

import pytest
from typer.testing import CliRunner

from bearingsim.pipeline.cli.commands import app
from bearingsim.pipeline.console import LiteralConsole, finding_lines, styled, visible
from bearingsim.pipeline.scene.validity import warning

runner = CliRunner()
SCENE = "helicopter-b-given-hinge"
MARKUP = "a [/] b [b]bold[/b] [red]red :smile: [m]"


def test_a_description_with_markup_is_printed_as_written():
    result = runner.invoke(app, ["check", SCENE, "--set", f'description="{MARKUP}"'])
    assert result.exit_code == 0, result.output
    assert f"{SCENE} — {MARKUP}" in result.stdout


def test_a_lubricant_description_with_markup_shows_in_the_table():
    result = runner.invoke(app, ["check", SCENE, "--set", 'lubricant.description="[/]oil [m]"'])
    assert result.exit_code == 0, result.output
    assert "[/]oil [m]" in result.stdout


def test_control_characters_are_shown_escaped(tmp_path):
    text = (tmp_path / "scene.toml")
    from bearingsim.pipeline.scene.load import builtin_scene_text

    body = "\n".join(line for line in builtin_scene_text(SCENE).splitlines() if not line.startswith("description"))
    text.write_text('description = "red \\u001b[31m text\\r over \\u0007 bell"\n' + body + "\n")
    result = runner.invoke(app, ["check", str(text)])
    assert result.exit_code == 0, result.output
    assert "\x1b" not in result.output and "\r" not in result.output and "\x07" not in result.output
    assert "red \\x1b[31m text\\x0d over \\x07 bell" in result.stdout


def test_an_error_naming_user_text_keeps_its_brackets():
    result = runner.invoke(app, ["check", "no-such[/]scene[b]"])
    assert result.exit_code == 2 and "'no-such[/]scene[b]'" in result.stderr


def test_sweep_table_prints_a_value_with_markup():
    from bearingsim.pipeline.sweep.console import print_results

    out = io.StringIO()
    rows = [{"point_id": "p0", "lubricant.description": "[/]", "status": "done", "cage_class": "free",
             "cage_metal_contact_fraction": 0.0},
            {"point_id": "p1", "lubricant.description": "ok [b]", "status": "done", "cage_class": "free",
             "cage_metal_contact_fraction": 0.0}]
    print_results(rows, ["lubricant.description"], LiteralConsole(file=out, width=120))
    assert "[/]" in out.getvalue() and "ok [b]" in out.getvalue()


def test_finding_lines_keep_brackets_and_escape_controls():
    out = io.StringIO()
    console = LiteralConsole(file=out, width=200, force_terminal=False)
    for line in finding_lines([warning("load.moment", "x [N.m] [/] \x1b[2J")]):
        console.print(line)
    assert out.getvalue().strip() == "warning: load.moment: x [N.m] [/] \\x1b[2J"
    assert visible("tab\tand\nline") == "tab\tand\nline"  # layout characters stay
    assert styled(("a", "bold"), " [b]").plain == "a [b]"


def test_a_long_description_is_never_word_wrapped(monkeypatch, tmp_path):
    """rich wraps by trying break points word by word: a 40 kB word took 10 s, 900 kB more than
    300 s. No text that long may reach rich's wrapping."""
    import rich.text

    wrap = rich.text.Text.wrap

    def guarded(self, *args, **kwargs):
        assert len(self.plain) < 10_000 or kwargs.get("no_wrap"), "a long text went through rich's word wrap"
        return wrap(self, *args, **kwargs)

    monkeypatch.setattr(rich.text.Text, "wrap", guarded)
    long = "x" * 200_000
    result = runner.invoke(app, ["check", SCENE, "--set", f'description="{long}"',
                                 "--set", f'lubricant.description="{long}"'])
    assert result.exit_code == 0, result.output
    assert long in result.stdout  # the description whole; the table's cell shortened
    assert "(200000 characters)" in result.stdout
