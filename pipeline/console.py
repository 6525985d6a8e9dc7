"""What the user reads on the terminal: consoles that show text as written, and advice in scene keys.

Rich would read `[m]`, `[s]`, `[rev/min]` or `[lubricant]` as markup (and a description holding
`[/]` would stop the program), `:smile:` as an emoji, and pass an ESC byte of a scene file to the
terminal as a control sequence. The consoles of `make_console` do none of this, for every string
they print, whoever built it (a table cell too): no markup, no emoji codes, and control
characters shown escaped (`\\x1b`). Styling is explicit: `styled("error:", "bold red")`.

The solvers' own hints speak of their settings (`tol`, `max_newton_iter`, ...), which are
not scene keys; `explain` turns a failure into a message whose advice names only keys
of docs/scenes.md.
"""

from __future__ import annotations

import re

from rich.console import Console
from rich.text import Text

__all__ = ["make_console", "styled", "visible", "explain", "finding_lines", "INTEGRATION_HINTS", "PHRASES"]

# C0 and C1 control characters but line feed and tab: an ESC starts a terminal control sequence
_CONTROL = re.compile(r"[\x00-\x08\x0b-\x1f\x7f-\x9f]")


def visible(text: str) -> str:
    """`text` with its control characters (ESC, carriage return, bell, ...) written as escapes."""
    return _CONTROL.sub(lambda m: f"\\x{ord(m.group()):02x}", text)


class LiteralConsole(Console):
    """A rich console that renders every string as written (module docstring)."""

    def render_str(self, text: str, **kwargs) -> Text:
        kwargs.update(markup=False, emoji=False)
        return super().render_str(visible(text), **kwargs)


def make_console(stderr: bool = False) -> Console:
    """stderr's lines are soft-wrapped: a path or a message is printed whole, never broken at
    the console's width (80 columns when stderr is not a terminal), so it can be copied."""
    return LiteralConsole(stderr=stderr, emoji=False, markup=False, soft_wrap=stderr)


def styled(*parts: str | tuple[str, str]) -> Text:
    """One line of text from plain strings and (text, style) pairs, control characters escaped."""
    line = Text()
    for part in parts:
        text, style = part if isinstance(part, tuple) else (part, "")
        line.append(visible(text), style=style)
    return line


# The integrator's failure reasons (dynamics/multibody/results.py, Result.value) -> what to
# change in the scene.
INTEGRATION_HINTS = {
    "Newton iteration diverged": (
        "lower solver.max_step and solver.first_step (or solver.min_step, so the step controller may "
        "cut the step further); a very stiff hinge (hinge.translational, hinge.bending) or contact "
        "(physics.contact_damping_ratio) needs smaller steps"),
    "Newton did not converge within max_newton_iter iterations": (
        "lower solver.first_step and solver.min_step so the step controller may cut the step further; "
        "a tighter solver.rtol gives smaller steps everywhere"),
    "residual is NaN or infinite": (
        "a force became NaN or infinite: check the scene's units (lengths in m, loads in N and N.m, "
        "speeds in rev/min), lower solver.first_step, and check physics.min_film"),
    "iteration matrix is singular": (
        "a body has neither mass nor stiffness: check materials.ball.density, materials.cage.density "
        "and hinge.source ('none' leaves the inner race free)"),
}

# Phrases of solver and model messages that name no scene key -> the scene keys they mean.
PHRASES = (
    (", or loosen `tol`", ""),
    ("or loosen `tol`", ""),
    ("Reduce the axial load or moment, or check the shoulder diameter",
     "Reduce load.axial or load.moment, or check bearing.inner_shoulder_diameter and "
     "bearing.outer_shoulder_diameter"),
    ("try a smaller load or check the geometry",
     "try a smaller load (load.radial, load.axial, load.moment) or check the [bearing] keys"),
    ("check the geometry (groove radii, diameters) and the load units (N, N·m)",
     "check the [bearing] keys (groove radii and diameters, in m) and the load units (load.* in N and N.m)"),
    ("Try a smaller load, check the clearance and groove radii",
     "Try a smaller load (load.radial, load.axial, load.moment), check bearing.diametral_clearance "
     "(form 2) or the groove-centre diameters (form 1) and the groove radii"),
    ("Raise the operating temperature or check the WLF set.",
     "Raise lubricant.temperature_degC or check lubricant.wlf_tg0_degC."),
    ("Check the identified stiffness or give it by hand.",
     "Check the identified hinge (identify/hinge.toml) or give it by hand: hinge.source = 'given' "
     "with hinge.translational and hinge.bending."),
)

_TRY = re.compile(r"\. Try: .*$", re.S)


def explain(exc: BaseException) -> str:
    """`exc` as a one-paragraph message whose advice names scene keys."""
    text = str(exc)
    reason = getattr(exc, "reason", None)
    # the reason may end with where it happened ("... at the minimum step")
    hint = next((h for r, h in INTEGRATION_HINTS.items() if isinstance(reason, str) and reason.startswith(r)), None)
    if type(exc).__name__ == "IntegrationError" and hint is not None:
        text = _TRY.sub(f". Try: {hint}.", text)
    for phrase, replacement in PHRASES:
        text = text.replace(phrase, replacement)
    return text


def finding_lines(findings, prefix: str = "") -> list[Text]:
    """Console lines for validity findings (Finding or dicts): the level styled, the text as written."""
    lines = []
    for f in findings:
        level = f.get("level") if isinstance(f, dict) else f.level
        key = f.get("key") if isinstance(f, dict) else f.key
        message = f.get("message") if isinstance(f, dict) else f.message
        text = f"{key}: {message}" if key else str(message)
        style = "bold red" if level == "error" else "yellow"
        lines.append(styled((f"{level}:", style), f" {prefix}{text}"))
    return lines
