"""The run report: one self-contained HTML page (PNGs embedded as base64 data URIs).

Sections, in the order a reader asks: the verdict (one sentence, a table of its numbers
with names and units, and the evidence: cage orbit and burn zone), summary metrics, burn
zone, dynamic figures, quasi-static table, hinge, FE deflections, solver counters, scene,
versions and stage manifests. Everything comes from files already in the run directory; a section whose
stage did not run says so instead of disappearing.
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
DYNAMIC_FIGURES = ("cage_orbit.png", "cage_speed.png", "cage_race_force.png", "pocket_impacts.png",
                   "phase_portraits.png")
STYLE = """
body{font-family:system-ui,sans-serif;max-width:1200px;margin:1em auto;padding:0 1em;color:#222}
h1{font-size:1.5em}h2{border-bottom:1px solid #ccc;margin-top:2em}
table{border-collapse:collapse;margin:.5em 0;font-size:.9em}
td,th{border:1px solid #ddd;padding:2px 8px;text-align:right}th{background:#f4f4f4}
td:first-child,th:first-child{text-align:left}
figure{margin:1em 0}img{max-width:100%;border:1px solid #eee}
figcaption{font-size:.9em;color:#444}pre{background:#f7f7f7;padding:.5em;overflow-x:auto;font-size:.85em}
.note{color:#a60}.verdict{font-size:1.1em}
"""


def _fmt(value) -> str:
    if isinstance(value, float):
        return "nan" if math.isnan(value) else f"{value:.6g}"
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_fmt(v) for v in value) + "]"
    return "—" if value is None else str(value)


def table(header: list[str], rows: list[list]) -> str:
    """An HTML table; cells are escaped and numbers shown to 6 significant digits."""
    head = "".join(f"<th>{html.escape(h)}</th>" for h in header)
    body = "".join("<tr>" + "".join(f"<td>{html.escape(_fmt(c))}</td>" for c in row) + "</tr>" for row in rows)
    return f"<table><tr>{head}</tr>{body}</table>"


def image(path: Path, caption: str = "") -> str:
    """A PNG embedded as a data URI (the page must open alone, e-mailed or archived)."""
    path = Path(path)
    if not path.is_file():
        return f'<p class="note">missing figure {html.escape(path.name)}</p>'
    data = base64.b64encode(path.read_bytes()).decode("ascii")
    cap = f"<figcaption>{html.escape(caption)}</figcaption>" if caption else ""
    return f'<figure><img alt="{html.escape(path.name)}" src="data:image/png;base64,{data}">{cap}</figure>'


def _read_json(path: Path) -> dict | None:
    try:
        return json.loads(Path(path).read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None


def _not_run(what: str) -> str:
    return f'<p class="note">{html.escape(what)}</p>'


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


def verdict_section(summary: dict | None, burn: dict | None, out_dir: Path, sim_dir: Path | None,
                    evidence: dict | None = None) -> str:
    """The sentence, the verdict's numbers with names and units, the warnings, and the
    evidence figures (cage orbit, burn zone)."""
    from ..results.verdict import screen_sentence, verdict_rows

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
        parts.append(f'<p class="verdict">{html.escape(screen[0].upper() + screen[1:])}.</p>')
    parts.append(table(["quantity", "value", "unit"], [list(r) for r in verdict_rows(verdict)]))
    for w in summary.get("warnings") or []:
        parts.append(_not_run(f"warning: {w}"))
    parts.append(f'<p class="note">{html.escape(LIMITATION)}</p>')
    orbit = (evidence or {}).get("orbit")
    if orbit:
        parts.append(image(out_dir / orbit, "Evidence: the cage-centre orbit, start-up in grey, settled window "
                           "in blue, inside the guide clearance (ε = 1, metal contact begins) and the film "
                           "clearance; the loaded sector shaded, the thinnest film starred."))
    elif sim_dir is not None and (sim_dir / "cage_orbit.png").is_file():
        parts.append(image(sim_dir / "cage_orbit.png", "Evidence: the cage-centre orbit (whole run)."))
    if burn is not None:
        parts.append(image(out_dir / burn["map"], f"Evidence: the burn zone — {burn.get('caption', '')}."))
    return "".join(parts)


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


def quasistatic_section(qs_dir: Path | None) -> str:
    result = _read_json(qs_dir / "quasistatic.json") if qs_dir else None
    if result is None:
        return _not_run("Stage quasistatic did not run.")
    deg = 180.0 / math.pi
    ir = result.get("inner_race", {})
    parts = [table(["inner race", "value", "unit"], [
        ["displacement x, y, z", [d * 1e6 for d in ir.get("displacement", [])], "µm"],
        ["tilt about x, y", [r * 1e3 for r in ir.get("tilt", [])], "mrad"],
        ["cage speed (kinematic)", f"{result['cage_speed'] * 30.0 / math.pi:.1f}" if result.get("cage_speed") is not None
         else None, "rev/min"],
        ["converged", result.get("converged"), ""], ["iterations", result.get("iterations"), ""]])]
    rows = [[f"{b['azimuth'] * deg:.1f}", b["inner_load"], b["outer_load"], b["inner_contact_angle"] * deg,
             b["outer_contact_angle"] * deg, b.get("max_pressure_inner", float("nan")) / 1e6,
             b.get("max_pressure_outer", float("nan")) / 1e6] for b in result.get("balls", [])]
    parts.append(table(["azimuth [deg]", "Q_i [N]", "Q_o [N]", "α_i [deg]", "α_o [deg]",
                        "p_max,i [MPa]", "p_max,o [MPa]"], rows))
    for w in result.get("warnings", []):
        parts.append(_not_run(f"warning: {w}"))
    parts.append(image(qs_dir / "load_distribution.png", "Ball loads and contact angles against azimuth."))
    return "".join(parts)


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
    return (text + image(out_dir / burn["map"], f"Unrolled {ring} race{frame}: azimuth × axial position.")
            + image(out_dir / burn["render"], f"{ring.capitalize()} race in 3-D{frame}, four fixed views (half ring each)."))


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
    """Assemble and write the page (atomically)."""
    from ..staging.artefacts import atomic_write_text

    sim = stage_dirs.get("simulate")
    summary = _read_json(sim / "summary.json") if sim else None
    scene_file = run_dir / "scene.toml"
    scene_text = scene_file.read_text(encoding="utf-8") if scene_file.is_file() else ""
    dyn = "".join(image(sim / f) for f in DYNAMIC_FIGURES if (sim / f).is_file()) if sim else ""
    dyn += paraview_note(out_dir)
    sections = [
        ("Verdict", verdict_section(summary, burn, out_dir, sim, evidence)),
        ("Summary metrics", summary_section(summary)),
        ("Burn zone", burn_section(burn, out_dir)),
        ("Dynamic run", dyn or _not_run("No dynamic figures.")),
        ("Quasi-static equilibrium", quasistatic_section(stage_dirs.get("quasistatic"))),
        ("Hinge", hinge_section(scene, stage_dirs.get("identify"))),
        ("FE deflections", fe_section(fe_records, out_dir, "identify" in stage_dirs)),
        ("Solver counters", solver_section(summary)),
        ("Scene", f"<pre>{html.escape(scene_text)}</pre>"),
        ("Versions and stages", provenance_section(run_dir, stage_dirs)),
    ]
    body = "".join(f"<h2>{html.escape(t)}</h2>{b}" for t, b in sections)
    page = (f"<!DOCTYPE html><html lang=\"en\"><head><meta charset=\"utf-8\">"
            f"<title>bearingsim — {html.escape(scene.name)}</title><style>{STYLE}</style></head><body>"
            f"<h1>bearingsim run report — {html.escape(scene.name)}</h1>"
            f"<p>{html.escape(scene.description)}</p>"
            f"<p>{html.escape(operating_line(scene, 'simulate' in stage_dirs))}</p>"
            f"<p>Generated {time.strftime('%Y-%m-%d %H:%M:%S %z')} from the saved results in "
            f"<code>{html.escape(str(run_dir))}</code>.</p>{body}</body></html>\n")
    atomic_write_text(path, page)
