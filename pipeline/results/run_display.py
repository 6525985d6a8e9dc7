"""How a `bearingsim.pipeline.api.Run` shows itself: a one-line `repr` and a notebook
display (`_repr_html_`) of the verdict, its key numbers and the cage-orbit figure.

Both read the run directory's files only (summary.json, the figures); a missing file gives a
shorter display, never an error.
"""

from __future__ import annotations

import base64
import html
import json
from pathlib import Path

# the figure behind the verdict (report stage), else the simulate stage's whole-run orbit
ORBIT_FIGURES = (("report", "verdict_orbit.png"), ("simulate", "cage_orbit.png"))


def _summary(run) -> dict | None:
    try:
        return json.loads((Path(run.run_dir) / "simulate" / "summary.json").read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None


def _stages_held(run) -> list[str]:
    """The stages whose results are in the directory (not those this call did not need)."""
    try:
        return [name for name, status in run.stages.items() if status != "not needed"]
    except (OSError, ValueError):
        return []


def run_repr(run) -> str:
    """`Run('helicopter-b', runs/demo; stages: quasistatic, simulate; pressed, elevated risk)`,
    with "; too short to settle" when the run is (results.verdict.short_label)."""
    from .verdict import short_label

    stages = _stages_held(run)
    parts = [f"{run.scene.name!r}, {run.run_dir}", "stages: " + (", ".join(stages) if stages else "none")]
    summary = _summary(run)
    if ((summary or {}).get("verdict") or {}).get("class"):
        parts.append(short_label(summary))
    return f"Run({'; '.join(parts)})"


def run_html(run) -> str:
    """The verdict sentence, its table (quantity, value, unit) and the orbit figure."""
    from .verdict import verdict_rows

    title = f"<b>bearingsim run</b> {html.escape(run.scene.name)} — <code>{html.escape(str(run.run_dir))}</code>"
    summary = _summary(run)
    verdict = (summary or {}).get("verdict")
    if not verdict:
        why = "no dynamic run yet" if summary is None else "no verdict (the scene has no cage)"
        stages = ", ".join(_stages_held(run)) or "none"
        return f"<div>{title}<p>{why}; stages: {html.escape(stages)}</p></div>"
    rows = "".join(f"<tr><td style='text-align:left'>{html.escape(q)}</td><td>{html.escape(str(v))}</td>"
                   f"<td>{html.escape(u)}</td></tr>" for q, v, u in verdict_rows(verdict))
    table = f"<table><tr><th>quantity</th><th>value</th><th>unit</th></tr>{rows}</table>"
    figure = ""
    for stage, name in ORBIT_FIGURES:
        path = Path(run.run_dir) / stage / name
        if path.is_file():
            data = base64.b64encode(path.read_bytes()).decode("ascii")
            figure = f'<img alt="{name}" style="max-width:420px" src="data:image/png;base64,{data}">'
            break
    return (f"<div>{title}<p><b>{html.escape(verdict.get('text', ''))}</b></p>"
            f"<div style='display:flex;gap:1em;align-items:flex-start'>{table}{figure}</div></div>")
