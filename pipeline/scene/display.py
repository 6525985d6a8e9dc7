"""How a `Scene` shows itself: a short `repr` and a notebook display of its resolved tables.

Both show the values as the scene gives them (as drawn, at the reference temperature), with
the units of docs/scenes.md; the HTML display adds the clearances at the operating
temperatures (`scene.operating`, pipeline.scene.clearances), which is what the stages compute with.
"""

from __future__ import annotations

import dataclasses
import html

SECTIONS = ("bearing", "cage", "materials", "lubricant", "load", "speed", "hinge", "fe", "solver", "physics",
            "output")


def _number(value) -> str:
    if isinstance(value, float):
        return f"{value:.6g}"
    if isinstance(value, tuple):
        return "[" + ", ".join(_number(v) for v in value) + "]"
    return "—" if value is None else str(value)


def section_rows(obj, prefix: str) -> list[tuple[str, str, str]]:
    """(dotted key, value, unit) of every field of a resolved section, nested tables flattened."""
    rows = []
    for f in dataclasses.fields(obj):
        value = getattr(obj, f.name)
        key = f"{prefix}.{f.name}"
        if dataclasses.is_dataclass(value):
            rows += section_rows(value, key)
        else:
            unit = f.metadata.get("unit", "")
            rows.append((key, _number(value), "" if unit == "-" else unit))
    return rows


def scene_repr(scene) -> str:
    """`Scene('helicopter-b': 20 balls of 19.05 mm, pitch 138.75 mm, outer-guided cage; moment
    430 N.m, ...)`: what the scene is, in one line of about a hundred characters."""
    b = scene.bearing
    parts = [f"{b.ball_count} balls of {b.ball_diameter * 1e3:.4g} mm, pitch {b.pitch_diameter * 1e3:.5g} mm"]
    if scene.cage is not None:
        parts[-1] += f", {scene.cage.guidance}-guided cage"
    load = scene.load
    loads = [f"{name} {getattr(load, name):g} {unit}" for name, unit in
             (("moment", "N.m"), ("radial", "N"), ("axial", "N")) if getattr(load, name)]
    parts.append(", ".join(loads) if loads else "no load")
    parts.append(f"inner ring {scene.speed.inner_rpm:g} rev/min")
    parts.append(f"hinge {scene.hinge.source}; {scene.solver.duration:g} s")
    return f"Scene({scene.name!r}: {'; '.join(parts)})"


def _table(header: tuple[str, ...], rows) -> str:
    head = "".join(f"<th>{html.escape(h)}</th>" for h in header)
    body = "".join("<tr>" + "".join(f"<td style='text-align:{'left' if i == 0 else 'right'}'>{html.escape(str(c))}</td>"
                                    for i, c in enumerate(row)) + "</tr>" for row in rows)
    return f"<table><tr>{head}</tr>{body}</table>"


def scene_html(scene) -> str:
    """The scene's resolved sections (key, value as given, unit), each in a collapsible block,
    and the clearances as drawn and at the operating temperatures."""
    from .clearances import clearance_rows

    blocks = []
    for name in SECTIONS:
        obj = getattr(scene, name)
        if obj is None:
            continue
        rows = [(k[len(name) + 1:], v, u) for k, v, u in section_rows(obj, name)]
        blocks.append(f"<details><summary>[{name}]</summary>{_table(('key', 'value', 'unit'), rows)}</details>")
    t = scene.temperatures
    clearances = _table(("clearance", f"as drawn ({t.reference:g} °C)", "operating", "unit"), clearance_rows(scene))
    temps = (f"operating temperatures: inner ring {t.inner_ring:g} °C, outer ring {t.outer_ring:g} °C, "
             f"balls {t.ball:g} °C, cage {t.cage:g} °C")
    return (f"<div><b>Scene</b> {html.escape(scene.name)} — {html.escape(scene.description)}"
            f"<p>{html.escape(scene_repr(scene))}</p>{''.join(blocks)}"
            f"<details open><summary>clearances (scene.operating: the parts at operating temperature)</summary>"
            f"<p>{html.escape(temps)}</p>{clearances}</details></div>")
