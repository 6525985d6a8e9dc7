"""The run report: one self-contained HTML page (PNGs embedded as base64 data URIs), read in a
minute.

The first screen holds the verdict sentence, the cage orbit behind it, the polar burn map
centred on the hot sector and the key numbers with their units; everything else sits in
collapsible sections, in the order a reader asks: all the verdict's numbers, summary metrics,
burn zone (unrolled map and 3-D), dynamic run, quasi-static equilibrium, hinge, FE deflections,
solver counters, scene, versions and stage manifests. Each figure appears once. The page is the
jinja2 template `templates/report.html` (its pieces in `templates/parts.html`); everything comes
from files already in the run directory, and a section whose stage did not run says so instead
of disappearing.
"""

from __future__ import annotations

import base64
import html
import json
import math
import time
import tomllib
from pathlib import Path

SOLVER_COUNTERS = ("steps", "rejected_steps", "newton_failures", "newton_iterations", "factorizations",
                   "residual_evaluations", "min_step_accepts", "integration_wall_time", "kernel_load_time",
                   "wall_time")
# the simulate stage's figures the report shows (its cage_orbit.png is the verdict's orbit, shown
# once above; its phase portraits stay in the stage folder)
DYNAMIC_FIGURES = ("cage_speed.png", "pocket_impacts.png", "cage_race_force.png")


def _templates():
    """The jinja2 environment of templates/ (autoescaped: scene text is never markup)."""
    import jinja2

    return jinja2.Environment(loader=jinja2.FileSystemLoader(Path(__file__).parent / "templates"),
                              autoescape=True, trim_blocks=True, lstrip_blocks=True)


def _parts():
    return _templates().get_template("parts.html").module


def _fmt(value) -> str:
    if isinstance(value, float):
        return "nan" if math.isnan(value) else f"{value:.6g}"
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_fmt(v) for v in value) + "]"
    return "—" if value is None else str(value)


def fixed(value, digits: int) -> str:
    """`value` rounded to `digits` decimals, the quantity's resolution: round-off below it
    reads 0 (not 4.7e-12 or -0.000); None and NaN read —."""
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "—"
    rounded = round(float(value), digits) + 0.0
    return "0" if rounded == 0.0 else f"{rounded:.{digits}f}"


def table(header: list[str], rows: list[list]) -> str:
    """An HTML table (templates/parts.html); numbers shown to 6 significant digits unless a
    cell is already text."""
    return str(_parts().table(header, [[c if isinstance(c, str) else _fmt(c) for c in row] for row in rows]))


def image(path: Path, caption: str = "", width: int | None = None) -> str:
    """A PNG embedded as a data URI (the page must open alone, e-mailed or archived)."""
    path = Path(path)
    if not path.is_file():
        return str(_parts().missing(path.name))
    data = base64.b64encode(path.read_bytes()).decode("ascii")
    return str(_parts().figure(data, path.name, caption, width))


def _read_json(path: Path) -> dict | None:
    try:
        return json.loads(Path(path).read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None


def _not_run(what: str) -> str:
    return str(_parts().note(what))


def summary_section(summary: dict | None) -> str:
    """The summary's metrics as an engineer reads them (results.summary_keys.METRICS: names,
    units, digits; azimuths 0–360°), the start-up apart, and the drift check."""
    from ..results.summary_keys import METRICS, metric_text

    if summary is None:
        return _not_run("No dynamic run in this directory (stage simulate did not run).")
    rows, startup = [], []
    for key, metric in METRICS.items():
        table_name, _, name = key.rpartition(".")
        value = (summary.get(table_name) or {}).get(name) if table_name else summary.get(key)
        if value is None and (table_name or key not in summary):
            continue
        (startup if table_name == "startup" else rows).append([metric.label, metric_text(metric, value), metric.unit])
    parts = [table(["metric (settled window)", "value", "unit"], rows)]
    if startup:
        parts.append(table(["start-up (before the settled window)", "value", "unit"], startup))
    parts.append(drift_section(summary.get("settled_drift")))
    return "".join(parts)


DRIFT_LIMIT = 0.2  # relative change between the halves that reads as a drift
DRIFT_ANGLE_LIMIT_DEG = 10.0  # change of a mean direction that reads as a drift


def drift_rows(drift: dict) -> list[list]:
    """[metric, first half, second half, unit, change] per drift metric; a direction's
    change is its angle on the circle (6.27 rad and 0.007 rad are 0.6° apart)."""
    from ..results.summary_keys import METRICS, angle_difference, metric_text

    rows = []
    for key, pair in drift.items():
        metric = METRICS.get(key)
        if metric is None or not pair or None in pair:
            continue
        first, second = (float(v) for v in pair)
        if metric.kind == "position":
            change = math.degrees(angle_difference(first, second))
            note = f"{change:.1f}°" + (" — drifts" if change > DRIFT_ANGLE_LIMIT_DEG else "")
        else:
            scale = max(abs(first), abs(second))
            change = abs(second - first) / scale if scale > 0.0 else 0.0
            note = f"{100 * change:.0f} %" + (" — drifts" if change > DRIFT_LIMIT else "")
        rows.append([metric.label, metric_text(metric, first), metric_text(metric, second), metric.unit, note])
    return rows


def drift_section(drift: dict | None) -> str:
    if not drift:
        return ""
    return ("<p>Drift check: the same metrics over the first and the second half of the settled window; "
            f"a change of more than {100 * DRIFT_LIMIT:.0f} % (or {DRIFT_ANGLE_LIMIT_DEG:.0f}° for a direction, "
            "measured on the circle) means the statistics still drift: run longer.</p>"
            + table(["metric", "first half", "second half", "unit", "change"], drift_rows(drift)))


# How far to trust the verdict: the validation against the reference cases (docs/validation.md)
LIMITATION = (
    "How far to trust this verdict: on the reference bearing this model reproduces the regimes "
    "and the loaded sector, but it under-predicts the severity of a crush. The reference case b "
    "(430 N·m), whose cage was crushed and whose race burnt on a test rig, comes out 'pressed, "
    "elevated risk' here, at its operating clearances: the model crushes that cage only from about "
    "500–512 N·m at 100 °C. The crush depends on 0.2 mm of pocket and guide clearance and on the "
    "bearing's internal clearance, which the reference data do not pin down (with the uncertainty "
    "of its internal clearance, P(crushed) is about 9 %). Read 'pressed' as a warning, check the "
    "crush margin, and give the drawing's tolerances to `bearingsim tolerances` for the crush "
    "probability. Details: docs/validation.md §10, §12.")


def verdict_section(summary: dict | None) -> str:
    """The verdict sentence, the crush screen in one line and the run's warnings (the first
    screen); its full table of numbers is `verdict_table`."""
    from ..results.verdict import screen_sentence, too_short_to_settle

    if summary is None:
        return _not_run("No dynamic run in this directory (stage simulate did not run): no verdict.")
    verdict = summary.get("verdict")
    if not verdict:
        reason = ("the scene has no cage" if "cage_speed_mean" not in summary
                  else "this summary.json predates the verdict; rerun `bearingsim simulate SCENE --force`")
        return _not_run(f"No verdict: {reason}.")
    parts = [f'<p class="verdict"><b>{html.escape(verdict["text"])}</b></p>']
    screen = screen_sentence(verdict.get("screen"))
    if screen:
        parts.append(f'<p class="sub">{html.escape(screen[0].upper() + screen[1:])}.</p>')
    if too_short_to_settle(summary):
        parts.append('<p class="short">This run is too short to settle: its numbers are not a verdict yet; '
                     'run longer (solver.duration).</p>')
    return "".join(parts)


def verdict_table(summary: dict | None) -> str:
    """Every number of the verdict with its name and unit, the warnings, and how far to trust it."""
    from ..results.verdict import verdict_rows

    verdict = (summary or {}).get("verdict")
    if not verdict:
        return _not_run("No verdict.")
    parts = [table(["quantity", "value", "unit"], [list(r) for r in verdict_rows(verdict)])]
    parts += [_not_run(f"warning: {w}") for w in summary.get("warnings") or []]
    return "".join(parts)


def key_numbers(summary: dict | None, burn: dict | None) -> str:
    """The numbers a reader looks for first, with units and the precision they carry."""
    from ..results.verdict import format_arc, format_film_um, format_percent, format_ratio, too_short_to_settle

    verdict = (summary or {}).get("verdict")
    if not verdict:
        return ""
    screen = verdict.get("screen") or {}
    rows = [["cage motion", f"{verdict['class']}", ""], ["risk", verdict["risk"], ""],
            ["loaded sector", format_arc(verdict.get("sector_deg")), "deg"],
            ["land heat, 80 % arc", format_arc(verdict.get("heat_sector_deg")), "deg"],
            ["thinnest land film", format_film_um(verdict.get("land_film_min_um")), "µm"],
            ["Λ_min = h_min/σ", format_ratio(verdict.get("land_film_ratio_min")), "-"],
            ["metal contact", format_percent(verdict.get("metal_contact_fraction") or 0.0), "% of settled run"],
            ["mean eccentricity ε", fixed(verdict.get("eps_mean"), 2), "-"],
            ["pocket impacts", "—" if verdict.get("pocket_impacts") is None else str(verdict["pocket_impacts"]), "count"]]
    if verdict.get("pocket_impact_force_p95_N") is not None:
        rows.append(["impact force p95", fixed(verdict["pocket_impact_force_p95_N"], 0), "N"])
    if screen:
        rows += [["crush margin (screen)", fixed(screen.get("crush_margin"), 2), "-"],
                 ["guide clearance C", fixed(1e6 * screen["guide_clearance"], 0), "µm"]]
    if burn is not None:
        rows.append(["land heat (settled)", f"{burn['energy_total_J']:.3g}", "J"])
    settled = verdict.get("settled_revolutions")
    rows.append(["settled cage revolutions", fixed(settled, 1)
                 + (" — too short to settle" if too_short_to_settle(summary) else ""), "rev"])
    return table(["key number", "value", "unit"], rows)


SOLVER_LABELS = {"steps": "accepted steps", "rejected_steps": "rejected steps",
                 "newton_failures": "Newton failures", "newton_iterations": "Newton iterations",
                 "factorizations": "matrix factorisations", "residual_evaluations": "residual evaluations",
                 "min_step_accepts": "steps accepted at the minimum step", "integration_wall_time": "integration time",
                 "kernel_load_time": "kernel compile/load time", "wall_time": "wall time of the stage"}


def solver_section(summary: dict | None) -> str:
    if summary is None:
        return _not_run("No dynamic run: no solver counters.")
    rows = [[SOLVER_LABELS[k], f"{summary[k]:.3g}" if isinstance(summary[k], float) else summary[k],
             "s" if k.endswith("time") else ""] for k in SOLVER_COUNTERS if k in summary]
    if summary.get("viscosity_lookup"):
        rows.append(["viscosity lookup route (speed only, same results)", summary["viscosity_lookup"], ""])
    return table(["counter", "value", "unit"], rows)


def quasistatic_section(qs_dir: Path | None, out_dir: Path | None = None) -> str:
    """Inner-race displacement and tilt and the per-ball table, each rounded to its quantity's
    resolution (0.01 µm, 0.001 mrad, 0.1 N, 0.01°, 1 MPa), the polar ball loads and the loads
    against azimuth."""
    result = _read_json(qs_dir / "quasistatic.json") if qs_dir else None
    if result is None:
        return _not_run("Stage quasistatic did not run.")
    deg = 180.0 / math.pi
    ir = result.get("inner_race", {})
    parts = [table(["inner race", "value", "unit"], [
        ["displacement x, y, z", ", ".join(fixed(d * 1e6, 2) for d in ir.get("displacement", [])), "µm"],
        ["tilt about x, y", ", ".join(fixed(r * 1e3, 3) for r in ir.get("tilt", [])), "mrad"],
        ["cage speed (kinematic)", fixed(result["cage_speed"] * 30.0 / math.pi, 1) if result.get("cage_speed") is not None
         else "—", "rev/min"],
        ["converged", result.get("converged"), ""], ["iterations", result.get("iterations"), ""]])]
    rows = [[fixed(b["azimuth"] * deg, 1), fixed(b["inner_load"], 1), fixed(b["outer_load"], 1),
             fixed(b["inner_contact_angle"] * deg, 2), fixed(b["outer_contact_angle"] * deg, 2),
             fixed(b.get("max_pressure_inner", float("nan")) / 1e6, 0),
             fixed(b.get("max_pressure_outer", float("nan")) / 1e6, 0)] for b in result.get("balls", [])]
    parts += [_not_run(f"warning: {w}") for w in result.get("warnings", [])]
    if out_dir is not None and (Path(out_dir) / BALL_LOAD_FIGURE).is_file():
        parts.append(image(Path(out_dir) / BALL_LOAD_FIGURE, "Ball loads round the bearing, seen along its axis.", 460))
    parts.append(image(qs_dir / "load_distribution.png", "Ball loads and contact angles against azimuth.", 620))
    parts.append(table(["azimuth [deg]", "Q_i [N]", "Q_o [N]", "α_i [deg]", "α_o [deg]",
                        "p_max,i [MPa]", "p_max,o [MPa]"], rows))
    return "".join(parts)


BALL_LOAD_FIGURE = "ball_loads_polar.png"


def _cleaned(matrix) -> list:
    """A hinge matrix with the round-off of an FE fit (terms below 1e-12 of its largest) shown as 0."""
    import numpy as np

    m = np.asarray(matrix, dtype=float)
    big = float(np.max(np.abs(m), initial=0.0))
    return np.where(np.abs(m) < 1e-12 * big, 0.0, m).tolist()


def hinge_section(scene, identify_dir: Path | None) -> str:
    """Identified hinge (hinge.toml) or the values given in the scene."""
    h = scene.hinge
    if h.source == "none":
        return _not_run("hinge.source = 'none': the inner race is free (no hinge).")
    if h.source == "given" or identify_dir is None:
        return (f"<p>Given in the scene (hinge.source = {html.escape(h.source)}); no FE stage.</p>"
                + table(["quantity", "value", "unit"], [
                    ["H_u (translational)", h.stiffness_matrix(), "N/m"],
                    ["H_psi (bending)", list(h.bending), "N·m/rad"],
                    ["damping time c_G", h.damping_ratio_time, "s"]]))
    path = identify_dir / "hinge.toml"
    if not path.is_file():
        return _not_run(f"identify stage ran but {path.name} is missing.")
    with open(path, "rb") as fh:
        doc = tomllib.load(fh)
    hinge, fit, mesh = doc.get("hinge", {}), doc.get("fit", {}), doc.get("mesh", {})
    rows = [["H_u (translational)", _cleaned(hinge.get("translational", [])), "N/m"],
            ["H_psi (bending)", hinge.get("bending"), "N·m/rad"],
            ["damping time c_G", h.damping_ratio_time, "s"]]
    rows += [[f"fit: {k}", v, ""] for k, v in fit.items()]
    rows += [[f"mesh: {k}", v, ""] for k, v in mesh.items()]
    rows += [[f"time: {k}", v, "s"] for k, v in doc.get("timings_s", {}).items()]
    return "<p>Identified by FE (stage identify, fit M.2).</p>" + table(["quantity", "value", "unit"], rows)


def fe_section(fe_records: list[dict], out_dir: Path, identify_ran: bool) -> str:
    if not identify_ran:
        return _not_run("No FE stage in this run (hinge not identified by FE): no deflection renders.")
    if not fe_records:
        return _not_run("The identify stage wrote no case_*.vtu files.")
    parts = []
    for r in fe_records:
        parts.append(image(out_dir / r["file"], (
            f"{r['load_case']}: half model cut through the axis, deformation ×{r['warp_scale']:g}; "
            f"left |u| (max {r['max_displacement_m'] * 1e6:.3g} µm), right von Mises stress"
            + (f" (max {r['max_von_mises_Pa'] / 1e6:.3g} MPa)" if r.get("max_von_mises_Pa") else "")
            + f"; colour scales 0 to max. ParaView file: {r['vtu']}.")))
    return "".join(parts)


def operating_line(scene, simulated: bool) -> str:
    """The loads and speeds this run used, from its resolved scene: the description above it
    is the scene file's text, which `--set` overrides do not change."""
    ld, sp = scene.load, scene.speed
    parts = [f"radial {ld.radial:g} N", f"axial {ld.axial:g} N", f"moment {ld.moment:g} N·m",
             f"inner ring {sp.inner_rpm:g} rev/min"]
    if sp.outer_rpm:
        parts.append(f"outer ring {sp.outer_rpm:g} rev/min")
    if scene.lubricant is not None and scene.lubricant.temperature_degC is not None:
        parts.append(f"oil {scene.lubricant.temperature_degC:g} °C")
    return "This run: " + ", ".join(parts) + (f"; {scene.solver.duration:g} s simulated." if simulated else ".")


def burn_section(burn: dict | None, out_dir: Path) -> str:
    if burn is None:
        return _not_run("No burn-zone map (no dynamic run, or no land-guided cage: a ball-guided cage touches no land).")
    peak = (f"peak sector centred at {burn['peak_sector_deg']:.1f}° "
            f"({burn['peak_sector_energy_J']:.3g} J, {burn['peak_areal_density_J_m2']:.3g} J/m²)"
            if burn.get("peak_sector_deg") is not None else "no heat on the guide land")
    # the arc as the verdict prints it: 0–360 at both ends, "347–12°" across zero
    arc = (f"80 % of the heat in {burn['sector_deg'][0] % 360.0:.1f}–{burn['sector_deg'][1] % 360.0:.1f}°"
           f" ({burn['sector_deg'][1] - burn['sector_deg'][0]:.0f}° wide)" if burn.get("sector_deg") else "")
    window = burn.get("window_s") or [float("nan"), float("nan")]
    scope = (f"over the settled window t = {window[0]:.4g}–{window[1]:.4g} s" if burn.get("settled")
             else f"over the whole run t = {window[0]:.4g}–{window[1]:.4g} s (no settled window found)")
    film = ("" if burn.get("film_layer", True) else
            " This run saved no film power (cage_race/film_power): the map holds metal friction only.")
    text = (f"<p>Heat on the guiding land {scope}: metal-contact friction energy (friction power × time, "
            f"at the contact azimuth) plus the viscous shear energy of the land film (film power × time, "
            f"spread round the land like the film's shear: ∝ 1/h(θ) on the converging side of the thinnest film, ∝ h_min/h² on the cavitated side), {burn['sectors']} sectors of "
            f"{360 / burn['sectors']:g}°: total {burn['energy_total_J']:.4g} J = metal "
            f"{burn.get('energy_metal_J', float('nan')):.4g} J + film {burn.get('energy_film_J', float('nan')):.4g} J. "
            f"The start-up's metal energy ({burn.get('startup_metal_energy_J') or 0.0:.4g} J) is not in the map "
            f"(summary.json startup).{film} "
            f"{html.escape(peak)}; {html.escape(arc)}. The model gives the azimuth of the heat only: each "
            f"sector's energy is spread uniformly over the cage's land overlap (both lands, "
            f"L = {burn['land_overlap_mm']:.2f} mm). Raceway: ball–{burn.get('ring', 'outer')}-race contact load × time, each "
            f"contact spread over its Hertz ellipse across the groove; "
            f"{burn['track_outside_fraction'] * 100:.2g} % of it lies beyond the land edges. "
            "Colour scales run from 0 to the data's maximum.</p>")
    ring = burn.get("ring", "outer")
    frame = "" if ring == "outer" else " in the frame that turns with the ring"
    return (text + image(out_dir / burn["map"], f"Unrolled {ring} race{frame}: azimuth × axial position, centred on "
                                                "the hot sector.", 900)
            + image(out_dir / burn["render"], f"{ring.capitalize()} race in 3-D{frame}, four fixed views (half ring "
                                              "each).", 900))


def paraview_note(out_dir: Path) -> str:
    """Where the ParaView files are (docs/outputs.md "ParaView"), when the stage wrote them."""
    folder = Path(out_dir) / "paraview"
    files = sorted(p.name for p in folder.iterdir() if p.suffix in (".pvd", ".vtp")) if folder.is_dir() else []
    if not files:
        return ""
    return (f"<p>ParaView: open {html.escape(', '.join(files))} in <code>report/paraview/</code> together "
            "(the time slider plays the run; balls as points with a <code>diameter</code> for Glyph → Sphere; "
            "the outer race coloured by <code>land_heat</code> is the burn zone). Fields and units: "
            "docs/outputs.md.</p>")


def provenance_section(run_dir: Path, stage_dirs: dict[str, Path]) -> str:
    versions = _read_json(run_dir / "versions.json") or {}
    rows = []
    for name, d in stage_dirs.items():
        m = _read_json(d / "stage.json") or {}
        rows.append([name, (m.get("key") or "")[:16], m.get("wall_time_s"), m.get("finished")])
    return (table(["stage", "input key", "wall time [s]", "finished"], rows)
            + table(["package", "version"], [[k, v] for k, v in versions.items()]))


def write_report_html(path: Path, scene, run_dir: Path, stage_dirs: dict[str, Path], out_dir: Path,
                      fe_records: list[dict], burn: dict | None, evidence: dict | None = None) -> None:
    """Assemble the page from templates/report.html and write it (atomically)."""
    from markupsafe import Markup

    from ..results.verdict import LAND_NAMES, short_label
    from ..staging.artefacts import atomic_write_text

    sim = stage_dirs.get("simulate")
    summary = _read_json(sim / "summary.json") if sim else None
    scene_file = run_dir / "scene.toml"
    scene_text = scene_file.read_text(encoding="utf-8") if scene_file.is_file() else ""
    dyn = "".join(image(sim / f, width=820) for f in DYNAMIC_FIGURES if (sim / f).is_file()) if sim else ""
    dyn += paraview_note(out_dir)
    orbit = (evidence or {}).get("orbit")
    orbit_html = image(out_dir / orbit) if orbit else (
        image(sim / "cage_orbit.png") if sim is not None and (sim / "cage_orbit.png").is_file() else "")
    land = LAND_NAMES.get(getattr(scene.cage, "guidance", ""), "guide land")
    burn_html = image(out_dir / burn["polar"]) if burn is not None and burn.get("polar") else ""
    sections = [
        ("The verdict's numbers", "every quantity behind the sentence, with its unit", verdict_table(summary)),
        ("How far to trust this verdict", "validation against the reference cases", _not_run(LIMITATION)),
        ("Summary metrics", "the settled window's statistics and the drift check", summary_section(summary)),
        ("Burn zone", f"the {land} unrolled and in 3-D", burn_section(burn, out_dir)),
        ("Dynamic run", "cage speed, pocket impacts, cage–land force", dyn or _not_run("No dynamic figures.")),
        ("Quasi-static equilibrium", "ball loads, contact angles, inner-race position",
         quasistatic_section(stage_dirs.get("quasistatic"), out_dir)),
        ("Hinge", "the mounting's stiffness", hinge_section(scene, stage_dirs.get("identify"))),
        ("FE deflections", "the identification's load cases", fe_section(fe_records, out_dir, "identify" in stage_dirs)),
        ("Solver counters", "", solver_section(summary)),
        ("Scene", "as this run used it", f"<pre>{html.escape(scene_text)}</pre>"),
        ("Versions and stages", "", provenance_section(run_dir, stage_dirs)),
    ]
    page = _templates().get_template("report.html").render(
        name=scene.name, description=scene.description,
        label=short_label(summary) if (summary or {}).get("verdict") else "no verdict",
        operating=operating_line(scene, "simulate" in stage_dirs),
        generated=time.strftime("%Y-%m-%d %H:%M:%S %z"), run_dir=str(run_dir),
        verdict=Markup(verdict_section(summary)), orbit=Markup(orbit_html), burn=Markup(burn_html),
        key_numbers=Markup(key_numbers(summary, burn)),
        sections=[{"title": t, "hint": h, "body": Markup(b)} for t, h, b in sections])
    atomic_write_text(path, page)
