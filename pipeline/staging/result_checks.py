"""Result checks of pipeline.scene.validity: a finished stage's own numbers against the limits of
the model (docs/model.md §6, §10), and stage failures that are such a limit.

The quasi-static result (`quasistatic.json`) is checked for a contact angle past the groove
(90°), a contact pressure beyond the ISO 76 static-rating pressure (warning) or the fully
plastic limit of hardened bearing steel (error), contact ellipses cut by the lands (warning)
and an inner-race displacement as large as the ball (error); the dynamic summary
(`summary.json`) for values that are no physical quantity.
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

from ..scene.validity import (ABSURD, MIN_SAMPLES, PLASTIC_LIMIT_PRESSURE, STATIC_CAPACITY_PRESSURE, Finding, _g,
                       error, warning)

RESULT_FILES = {"quasistatic": "quasistatic.json", "simulate": "summary.json"}


def stage_findings(stage: str, scene, stage_dir: Path) -> list[Finding]:
    """Findings on a finished stage's result file (none for stages without checks)."""
    if stage == "identify":
        return identify_findings(Path(stage_dir) / "hinge.toml")
    name = RESULT_FILES.get(stage)
    if name is None:
        return []
    path = Path(stage_dir) / name
    if not path.is_file():
        return []  # a stand-in stage (tests) or one that writes its results elsewhere
    try:
        payload = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return [error("", f"the {stage} stage wrote an unreadable {name}")]
    if not isinstance(payload, dict):
        return []
    if stage == "quasistatic":
        return quasistatic_findings(scene, payload)
    return simulation_findings(scene, payload)


def identify_findings(path: Path) -> list[Finding]:
    """The doubts the FE stage found on the engineer's mesh (hinge.toml [mesh] warnings:
    a seat in pieces or of another length than the ring, no outer seat), as warnings."""
    import tomllib

    if not path.is_file():
        return []
    try:
        doc = tomllib.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return [error("", "the identify stage wrote an unreadable hinge.toml")]
    found = doc.get("mesh", {}).get("warnings", [])
    return [warning(str(w.get("key", "")), str(w.get("message", ""))) for w in found if isinstance(w, dict)]


def annotate(stage: str, stage_dir: Path, findings: list[Finding]) -> None:
    """Store the findings in the stage's result file (`validity` list), atomically."""
    from .artefacts import atomic_write_json

    name = RESULT_FILES.get(stage)
    path = Path(stage_dir) / name if name else None
    if path is None or not path.is_file():
        return
    payload = json.loads(path.read_text(encoding="utf-8"))
    if stage == "simulate":
        payload = null_absurd(payload)
    payload["validity"] = [f.to_json() for f in findings]
    atomic_write_json(path, payload)


LOAD_UNITS = {"radial": "N", "axial": "N", "moment": "N.m"}


def _main_load_key(scene) -> str:
    arm = 0.5 * scene.operating.bearing.pitch_diameter
    sizes = {"load.radial": abs(scene.load.radial), "load.axial": abs(scene.load.axial),
             "load.moment": abs(scene.load.moment) / arm}
    return max(sizes, key=sizes.get) if any(sizes.values()) else "load"


def _load_text(scene, key: str) -> str:
    """'1e+09 N' (the value of `key`), with the other non-zero loads: the loads of a result."""
    others = [f"load.{k} = {_g(getattr(scene.load, k))} {u}" for k, u in LOAD_UNITS.items()
              if getattr(scene.load, k) and f"load.{k}" != key]
    if key == "load":
        return "the load"
    name = key.split(".", 1)[1]
    head = f"{_g(getattr(scene.load, name))} {LOAD_UNITS[name]}"
    return head + (f" (with {', '.join(others)})" if others else "")


def _number(x: Any) -> float | None:
    return float(x) if isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(x) else None


# A groove within this of the ball's radius (conformity r/D - 1/2) holds the ball over a contact
# that is no longer small against the groove's relative curvature (Hertz's assumption), and the
# curvature-centre distance A = (f_i + f_o - 1) D that sets the contact angle nearly vanishes.
# Grooves are made well away from it: the reference bearing's conformities are 0.512 and 0.520
# (docs/model.md §2, Table 1 of the reference paper), small low-torque bearings' 0.56 +- 0.03
# (Dynaroll, "Raceway curvature").
TIGHT_GROOVE = 0.005


def _tight_groove(scene) -> str:
    """A note naming the conformity when a groove is nearly as tight as the ball, the likelier
    cause of a contact angle past the groove than the load."""
    b = scene.bearing
    tight = [(side, f) for side, f in (("inner", b.inner_conformity), ("outer", b.outer_conformity))
             if f - 0.5 < TIGHT_GROOVE]
    if not tight:
        return ""
    side, f = tight[0]
    return (f"; bearing.{side}_conformity = {f:.10g} (r/D) is within {TIGHT_GROOVE} of 0.5, a groove as tight "
            f"as the ball: the contact angle is ill-defined there, check the conformity (grooves are made with 0.51 "
            f"and more) before the load")


def quasistatic_findings(scene, payload: dict) -> list[Finding]:
    """The quasi-static result against the limits of the contact model (docs/model.md §6, §10)."""
    out: list[Finding] = []
    b = scene.operating.bearing
    key = _main_load_key(scene)
    loads = _load_text(scene, key)
    race = payload.get("inner_race", {})
    numbers = list(race.get("displacement", [])) + list(race.get("tilt", []))
    if not payload.get("balls") or any(_number(v) is None for v in numbers):
        return [error(key, f"the quasi-static solution is not finite ({loads}); check the scene's units")]
    if not payload.get("converged", False):
        out.append(warning(key, f"the quasi-static equilibrium did not converge ({loads})"))
    worst_angle, worst_p, truncated = (0.0, None), (0.0, None), []
    for k, ball in enumerate(payload["balls"]):
        for side in ("inner", "outer"):
            load = _number(ball.get(f"{side}_load")) or 0.0
            if load <= 0.0:
                continue
            angle = abs(_number(ball.get(f"{side}_contact_angle")) or 0.0)
            if angle > worst_angle[0]:
                worst_angle = (angle, (k, side))
            p = _number(ball.get(f"max_pressure_{side}")) or 0.0
            if p > worst_p[0]:
                worst_p = (p, (k, side))
            margin = _number(ball.get(f"truncation_margin_{side}"))
            if margin is not None and margin < 0.0:
                truncated.append((-margin, k, side))
    angle, where = worst_angle
    if where is not None and angle >= 0.5 * math.pi:
        k, side = where
        out.append(error(key, f"{loads} pushes ball {k} out of its groove: its {side} contact angle is "
                              f"{math.degrees(angle):.1f}°, beyond 90° where the groove stops holding it; allowed: "
                              f"loads that keep every contact angle below 90° (below the lands when "
                              f"bearing.inner_shoulder_diameter and bearing.outer_shoulder_diameter are given) [deg]"
                              + _tight_groove(scene)))
    p, where = worst_p
    if where is not None and p > STATIC_CAPACITY_PRESSURE:
        k, side = where
        # p_max grows like Q^(1/3) (Hertz): the load factor that would bring it to a limit
        def scaled(limit: float) -> str:
            factor = (limit / p) ** 3
            return ", ".join(f"load.{n} <= {_g(abs(getattr(scene.load, n)) * factor)}"
                             for n in ("radial", "axial", "moment") if getattr(scene.load, n))
        if p > PLASTIC_LIMIT_PRESSURE:
            out.append(error(key, f"{loads} gives a contact pressure of {p / 1e9:.3g} GPa (ball {k}, {side} race), "
                                  f"beyond the {PLASTIC_LIMIT_PRESSURE / 1e9:.0f} GPa at which hardened bearing steel "
                                  f"yields through (mean pressure 3 Y, Johnson 1985 §6.5): the elastic Hertz contact "
                                  f"is meaningless there; allowed: about {scaled(PLASTIC_LIMIT_PRESSURE)} "
                                  f"(N, N.m)"))
        else:
            out.append(warning(key, f"{loads} gives a contact pressure of {p / 1e9:.3g} GPa (ball {k}, {side} race), "
                                    f"beyond the {STATIC_CAPACITY_PRESSURE / 1e9:.1f} GPa of the ISO 76 static load "
                                    f"rating (permanent deformation > 0.0001 D): the elastic result is doubtful; "
                                    f"within the rating: about {scaled(STATIC_CAPACITY_PRESSURE)} (N, N.m)"))
    u = math.sqrt(sum(v * v for v in race["displacement"]))
    if u > 0.5 * b.ball_diameter:
        out.append(error(key, f"{loads} moves the inner race by {u * 1e3:.4g} mm, more than half the ball "
                              f"diameter ({0.5 * b.ball_diameter * 1e3:.4g} mm): no rolling contact model holds "
                              f"there; allowed: loads that keep the displacement well below D/2 [m]"))
    out += _crush_screen_findings(payload, key, loads)
    if truncated:
        depth, k, side = max(truncated)
        out.append(warning(key, f"{loads} truncates {len(truncated)} contact ellipses at the lands, the worst by "
                                f"{depth * 1e3:.3g} mm (ball {k}, {side} race): the pressure at the land edge is "
                                f"higher than the Hertz result and the load distribution is doubtful; see "
                                f"quasistatic.json 'warnings' (bearing.inner_shoulder_diameter, "
                                f"bearing.outer_shoulder_diameter) [m]"))
    return out


def _crush_screen_findings(payload: dict, key: str, loads: str) -> list[Finding]:
    """The crush screen (docs/model.md §10.1) takes every ball's pure-rolling orbital speed; a ball
    in the unloaded zone (here: under a tenth of the mean ball load) has too little traction to
    hold it and is carried by the cage instead, so there the screen's excursion is an upper bound."""
    if "cage_screen" not in payload:
        return []
    out = _screen_premise_findings(payload["cage_screen"], key, loads)
    q = [max(_number(b.get("inner_load")) or 0.0, _number(b.get("outer_load")) or 0.0) for b in payload["balls"]]
    mean = sum(q) / len(q) if q else 0.0
    light = [k for k, v in enumerate(q) if v < 0.1 * mean]
    if not light:
        return out
    return out + [warning(key, f"{loads} leaves {len(light)} of {len(q)} balls in the unloaded zone (under a tenth "
                         f"of the mean ball load of {mean:.4g} N): they do not roll at their own pure-rolling "
                         f"speed, so the crush screen's excursion and regime "
                         f"('{payload['cage_screen'].get('regime')}') overstate the push on the cage; the dynamic "
                         f"run (bearingsim simulate) decides [N]")]


def _screen_premise_findings(screen: dict, key: str, loads: str) -> list[Finding]:
    """The crush screen assumes a cage offset can take the balls' lead and lag (the first
    harmonic of their excursion, docs/model.md §10.1). Its higher harmonics no offset removes:
    where they alone span more than the pocket clearance, every cage position leaves balls
    against both pocket walls, and the screen's regime and margin say nothing of the risk."""
    residual = _number(screen.get("excursion_residual_peak_to_peak"))
    pocket = (_number(screen.get("pocket_clearance")) or 0.0) - (_number(screen.get("pocket_index_range")) or 0.0)
    if residual is None or pocket <= 0.0 or residual <= pocket:
        return []
    return [warning(key, f"{loads}: the part of the balls' lead and lag against the cage that no cage offset "
                         f"takes up (the higher harmonics of the excursion) spans {residual * 1e6:.0f} µm, more than "
                         f"the pocket clearance of {pocket * 1e6:.0f} µm: no cage position gives the balls room, as "
                         f"the crush screen assumes, so its regime ('{screen.get('regime')}') and crush margin "
                         f"({_number(screen.get('crush_margin')) or 0.0:.2f}) do not measure the risk; the dynamic "
                         f"run (bearingsim simulate) decides [m]")]


def failure_finding(stage: str, scene, exc: BaseException) -> Finding | None:
    """A stage failure that is really a result outside the model's validity, as an error
    finding (exit 2) — else None (a solver failure, exit 1). The quasi-static solver stops
    when a loaded contact angle reaches a land (dynamics/quasistatic/solver.py, _truncation):
    the contact centre is past the shoulder, which no groove model covers."""
    text = str(exc)
    if stage == "quasistatic" and type(exc).__name__ == "QuasiStaticError" and "rides over the shoulder" in text:
        key = _main_load_key(scene)
        detail = text.split(": the ball rides over", 1)[0]
        if key == "load.axial":
            what = "reduce load.axial or load.moment"
        else:  # a light thrust under a radial load or moment lets the race pivot onto far balls
            what = f"reduce {key}, or raise load.axial (a thrust seats every ball in its groove)"
        return error(key, f"{_load_text(scene, key)} drives a contact past its land: {detail}; the contact ellipse "
                          f"would lie on the shoulder, outside the groove model; allowed: loads that keep every "
                          f"contact angle below the land angles (set by bearing.inner_shoulder_diameter and "
                          f"bearing.outer_shoulder_diameter) [deg]: {what}")
    return None


def simulation_findings(scene, summary: dict) -> list[Finding]:
    """summary.json: values that are no physical quantity, and statistics on too few samples."""
    out: list[Finding] = []
    absurd = sorted(_absurd_values(summary))
    if absurd:
        shown = ", ".join(absurd[:6]) + (f" and {len(absurd) - 6} more" if len(absurd) > 6 else "")
        out.append(warning("solver.duration", f"summary.json holds values that are not physical quantities "
                                              f"(no value or |x| >= 1e100, written as null): {shown}; the run is "
                                              f"probably too short for them (solver.duration = "
                                              f"{_g(scene.solver.duration)} s) [s]"))
    samples = int(scene.solver.duration / scene.output.sample_interval) + 1
    if samples < MIN_SAMPLES:
        out.append(warning("output.sample_interval", f"only {samples} samples: the time averages of summary.json "
                                                     f"are not meaningful [s]"))
    return out


def _absurd_values(obj: Any, path: str = "") -> list[str]:
    if isinstance(obj, dict):
        return [p for k, v in obj.items() if k not in ("validity", "verdict")
                for p in _absurd_values(v, f"{path}.{k}" if path else k)]
    if isinstance(obj, list):
        return [p for i, v in enumerate(obj) for p in _absurd_values(v, f"{path}[{i}]")]
    if isinstance(obj, float) and (not math.isfinite(obj) or abs(obj) >= ABSURD):
        return [path]
    return []


def null_absurd(obj: Any) -> Any:
    """`obj` with every |x| >= 1e100 replaced by None (JSON null)."""
    if isinstance(obj, dict):
        return {k: null_absurd(v) for k, v in obj.items()}
    if isinstance(obj, list):
        return [null_absurd(v) for v in obj]
    if isinstance(obj, float) and (not math.isfinite(obj) or abs(obj) >= ABSURD):
        return None
    return obj
