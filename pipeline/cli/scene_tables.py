"""Human-readable tables: the resolved scene (`check`) and the quasi-static result."""

from __future__ import annotations

import dataclasses
import math

from rich.console import Console
from rich.table import Table

from ..console import styled
from ..scene.load import Scene

# a text value longer than this is shown shortened in the tables (the scene file holds it whole)
TABLE_TEXT = 80


def _unit(f: dataclasses.Field) -> str:
    unit = f.metadata.get("unit", "")
    return "" if unit == "-" else unit


def _fmt(value) -> str:
    if isinstance(value, float):
        return f"{value:.6g}"
    if isinstance(value, tuple):
        return "[" + ", ".join(_fmt(v) for v in value) + "]"
    text = str(value)
    return text if len(text) <= TABLE_TEXT else f"{text[:TABLE_TEXT - 20]}… ({len(text)} characters)"


def _fixed(value: float, digits: int) -> str:
    """`value` to `digits` decimals, without the "-0.00" of a tiny negative."""
    return f"{round(value, digits) + 0.0:.{digits}f}"


def _section(table: Table, title: str, obj, skip: tuple[str, ...] = ()) -> None:
    table.add_row(styled((f"[{title}]", "bold")), "", "")
    tables = []  # [fe.materials.<region>], after the section's own keys
    for f in dataclasses.fields(obj):
        value = getattr(obj, f.name)
        if f.name in skip:
            continue
        if isinstance(value, tuple) and value and all(hasattr(v, "region") for v in value):
            tables += [(f"{title}.{f.name}.{item.region}", item) for item in value]
        elif dataclasses.is_dataclass(value):
            _section(table, f"{title}.{f.name}", value)
        else:
            shown = _fmt(value) if value is not None else "—"
            if value is None and f.name == "thermal_expansion":
                shown = "default ([thermal] below)"
            table.add_row(f"  {f.name}", shown, _unit(f))
    for name, item in tables:
        _section(table, name, item, skip=("region",))


def derived_geometry(scene: Scene) -> list[tuple[str, float, str]]:
    """Derived quantities of docs/model.md §2 in engineering units (mm, deg, g, kg), from the
    dimensions as drawn (the operating ones are in the clearance table)."""
    parts = scene.nominal
    b, m = parts.bearing, parts.materials
    rows = [
        ("pitch diameter d_m", b.pitch_diameter * 1e3, "mm"),
        ("inner groove bottom diameter d_i - 2 r_i", b.inner_groove_bottom_diameter * 1e3, "mm"),
        ("outer groove bottom diameter d_o + 2 r_o", b.outer_groove_bottom_diameter * 1e3, "mm"),
        ("curvature-centre distance A = r_i + r_o - D", b.curvature_center_distance * 1e3, "mm"),
        ("curvature-centre radial offset (d_i - d_o)/2", b.curvature_center_radial_offset * 1e3, "mm"),
        ("free contact angle alpha_0", math.degrees(b.free_contact_angle), "deg"),
        ("diametral clearance P_d", b.diametral_clearance * 1e3, "mm"),
        ("inner conformity f_i = r_i/D", b.inner_conformity, ""),
        ("outer conformity f_o = r_o/D", b.outer_conformity, ""),
        ("ball mass", b.ball_mass(m.ball) * 1e3, "g"),
    ]
    c = parts.cage
    if c is not None and m.cage is not None:
        rows.append(("cage mass (pockets removed)", c.mass(m.cage, b), "kg"))
        try:
            rows += [
                ("cage radial guide clearance C", c.guide_clearance(b) * 1e3, "mm"),
                ("cage guide land length L (both lands)", c.guide_land_length(b) * 1e3, "mm"),
            ]
        except ValueError:
            pass
    rows.append(("inner-race speed Omega_i", scene.speed.inner, "rad/s"))
    if scene.lubricant is not None:
        rows += [
            ("lubricant viscosity eta_0 at temperature", scene.lubricant.eta0 * 1e3, "mPa.s"),
            ("pressure-viscosity coefficient alpha*", scene.lubricant.alpha_star, "1/Pa"),
        ]
        p_g = scene.lubricant.glass_pressure()
        if p_g is not None:  # docs/model.md §6.4: every viscosity model is held at eta_g above it
            rows.append(("pressure where eta reaches 1e12 Pa.s (held there above)", p_g * 1e-9, "GPa"))
    return rows


def _resolved_thermal(table: Table, scene: Scene) -> None:
    """[thermal] as resolved: every part's temperature (a part not given takes
    thermal.parts_degC, else the oil's) and the expansion coefficient each part grows by (a
    material's thermal_expansion, else the default of its kind)."""
    t, e = scene.temperatures, scene.expansion
    table.add_row(styled(("[thermal]", "bold"), " (resolved)"), "", "")
    for name in ("reference", "inner_ring", "outer_ring", "ball", "cage"):
        table.add_row(f"  {name}_degC", _fmt(float(getattr(t, name))), "degC")
    for name in ("race", "ball", "cage"):
        table.add_row(f"  expansion of the {name}", _fmt(float(getattr(e, name))), "1/K")


def print_scene(scene: Scene, console: Console) -> None:
    # soft wrap: the terminal wraps a long description (rich's word wrap is quadratic in a long word)
    console.print(styled((scene.name, "bold"), f" — {scene.description}"), soft_wrap=True)
    table = Table("key", "value", "unit", box=None, pad_edge=False)
    for name in ("bearing", "cage", "materials", "load", "speed", "hinge", "solver", "physics", "output"):
        # the scene's own values (as drawn); the operating ones follow in the clearance table
        obj = getattr(scene, name)
        if obj is not None:
            _section(table, name, obj)
        if name == "materials":
            from ..scene.named_materials import material_rows

            for row in material_rows(scene):
                table.add_row(*row)
    if scene.lubricant is not None:
        _section(table, "lubricant", scene.lubricant)
    if scene.fe is not None:
        from ...fe_model.config import AXISYMMETRIC_KEYS, MESH_KEYS

        _section(table, "fe", scene.fe, skip=AXISYMMETRIC_KEYS if scene.fe.model == "mesh" else MESH_KEYS)
    _resolved_thermal(table, scene)
    console.print(table)
    derived = Table("derived geometry (as drawn)", "value", "unit", box=None, pad_edge=False)
    for label, value, unit in derived_geometry(scene):
        derived.add_row(label, f"{value:.6g}", unit)
    console.print(derived)
    from ..scene.clearances import clearance_rows

    t = scene.temperatures
    temps = Table("clearances", f"at {t.reference:g} °C (as drawn)", "operating", "unit", box=None, pad_edge=False,
                  title=(f"operating temperatures: inner ring {t.inner_ring:g} °C, outer ring {t.outer_ring:g} °C, "
                         f"balls {t.ball:g} °C, cage {t.cage:g} °C (docs/model.md §2.1)"), title_justify="left")
    for row in clearance_rows(scene):
        temps.add_row(*row)
    console.print(temps)
    skipped = []
    if scene.hinge.source != "fe":
        skipped.append("FE identification (hinge not identified)")
    if scene.cage is None:
        skipped.append("cage and its contacts (no [cage])")
    if scene.lubricant is None:
        skipped.append("EHD film and traction (no [lubricant]: dry contacts)")
    if skipped:
        console.print("not computed for this scene: " + "; ".join(skipped))


def print_quasistatic(result: dict, console: Console) -> None:
    """Per-ball table plus inner-race displacement and tilt."""
    table = Table("ball", "azimuth [deg]", "Q_i [N]", "Q_o [N]", "alpha_i [deg]", "alpha_o [deg]",
                  title="quasi-static load distribution", box=None)
    for k, b in enumerate(result["balls"]):
        table.add_row(str(k), _fixed(math.degrees(b['azimuth']), 1), _fixed(b['inner_load'], 1),
                      _fixed(b['outer_load'], 1), _fixed(math.degrees(b['inner_contact_angle']), 2),
                      _fixed(math.degrees(b['outer_contact_angle']), 2))
    console.print(table)
    ir = result["inner_race"]
    d = ", ".join(f"{v * 1e6:.3f}" for v in ir["displacement"])
    t = ", ".join(f"{v * 1e3:.4f}" for v in ir["tilt"])
    console.print(f"inner race displacement [µm]: ({d})   tilt [mrad]: ({t})   "
                  f"converged: {result.get('converged')}")
    stiffness = result.get("stiffness")
    if stiffness:
        diagonal = ", ".join(f"{name} {stiffness[k][k]:.4g}" for k, name in enumerate(result["stiffness_order"]))
        console.print(f"bearing stiffness, diagonal (N/m for dx dy dz, N·m/rad for rx ry): {diagonal}; "
                      f"the 5×5 matrix is 'stiffness' in quasistatic.json (--json)")
    if result.get("cage_screen"):
        console.print(cage_screen_text(result["cage_screen"]))


def cage_screen_text(s: dict) -> str:
    """One paragraph on the crush screen (docs/model.md §10.1) for the console."""
    um = 1e6
    head = {"free": "free: the balls' excursion fits in the pocket clearance, no steady push on the cage",
            "pressed": "pressed: the balls push the cage off-centre onto one sector of its land",
            "crushed": "CRUSHED: the balls need more room than pocket and guide clearance give; "
                       "they force the cage onto its land (metal contact)"}[s["regime"]]
    text = (f"cage crush screen: {head}.\n"
            f"  ball excursion against a rigid cage {s['excursion_peak_to_peak'] * um:.0f} µm peak to peak "
            f"vs pocket clearance {s['pocket_clearance'] * um:.0f} µm; guide clearance {s['guide_clearance'] * um:.0f} µm\n"
            f"  balls lead the cage most at {s['front_wall_azimuth_deg']:.0f}° and lag most at "
            f"{s['rear_wall_azimuth_deg']:.0f}° (orbital position)")
    if s["regime"] != "free":
        text += (f"\n  push towards {round(s['push_azimuth_deg']) % 360}°; required cage offset "
                 f"{s['required_eccentricity'] * um:.0f} µm = {s['required_eccentricity_ratio']:.2f} of the "
                 f"guide clearance (crush margin {s['crush_margin']:.2f})")
    if s.get("crush_margin_at_reference_temperature") is not None:
        text += (f"\n  at operating temperatures (docs/model.md §2.1); with the clearances as drawn the margin "
                 f"would be {s['crush_margin_at_reference_temperature']:.2f} ({s['regime_at_reference_temperature']})")
    if s.get("pocket_circle_eccentricity"):
        text += (f"\n  cage run-out {s['pocket_circle_eccentricity'] * um:.0f} µm: the required offset swings "
                 f"{s['required_eccentricity_min'] * um:.0f}–{s['required_eccentricity'] * um:.0f} µm over a cage "
                 f"revolution (the margin is taken at the worst)")
    if s.get("non_guiding_gap") is not None:
        gap = s["non_guiding_gap"]
        text += (f"\n  gap left to the non-guiding land {gap * um:.0f} µm of {s['non_guiding_clearance'] * um:.0f} µm"
                 + (" — the cage TOUCHES the other ring's land (the model applies no force there)" if gap < 0 else ""))
    return text
