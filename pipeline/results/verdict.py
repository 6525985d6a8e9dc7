"""The verdict of a dynamic run: what an engineer reads first (`summary.json` `verdict`).

One dict built from the summary metrics of the settled window
(`pipeline.results.cage_metrics`): the cage-motion class and risk level
(`pipeline.scene.cage_classes`, default thresholds), the loaded sector of the land, the
thinnest land film (when, where, and its ratio to the roughness), metal contact, whirl, the
pocket impacts and a one-sentence `text`. Angles are in degrees, azimuth from +x towards
+y in the scene's (global) frame; films in µm; forces in N. The raw SI keys stay in
`summary.json`; the verdict repeats them in the units a reader uses.

The loaded sector:

- pressed: the shortest arc holding 80 % of the settled time of the contact azimuth (the
  land point facing the cage offset) — where the cage is pushed, with or without metal;
- crushed, or any class with metal contact: the 80 % arc of the metal-contact energy — where
  the land burns;
- otherwise none: a floating or whirling cage loads no fixed sector (`heat_sector_deg` still
  gives the 80 % arc of the land heat, metal plus film).
"""

from __future__ import annotations

import math

from ..scene.cage_classes import CageClassThresholds, classify_cage, risk_level

LAND_NAMES = {"outer": "outer-race land", "inner": "inner-race land"}
# what the class sentence calls the place the cage is pushed onto, by guidance
PUSHED_ONTO = {"ball": "the balls"}


def _deg(value) -> float | None:
    return None if value is None else math.degrees(float(value))


def _arc_deg(arc) -> list[float] | None:
    """[start, end] rad -> [start, end] deg, start in [0, 360), end = start + width."""
    if not arc:
        return None
    start, end = (math.degrees(float(v)) for v in arc)
    shift = 360.0 * math.floor(start / 360.0)
    return [start - shift, end - shift]


def format_arc(arc_deg) -> str:
    """'5–25°', '350–10°' across zero, 'all round' for a full circle."""
    if not arc_deg:
        return "—"
    start, end = arc_deg
    if end - start >= 359.5:
        return "all round"
    return f"{start % 360.0:.0f}–{end % 360.0:.0f}°"


def format_film_um(value: float | None) -> str:
    if value is None:
        return "—"
    return f"{value:.0f}" if abs(value) >= 10.0 else f"{value:.2g}"


def format_ratio(value: float | None) -> str:
    if value is None:
        return "—"
    return f"{value:.0f}" if value >= 10.0 else f"{value:.2g}"


def format_percent(fraction: float) -> str:
    """A fraction as a percentage for people: '87', '4.2', '0.14'."""
    value = 100.0 * fraction
    return f"{value:.0f}" if value >= 10.0 else f"{value:.2g}"


def cage_verdict(summary: dict, limits: CageClassThresholds = CageClassThresholds(),
                 guidance: str = "outer") -> dict:
    """The `verdict` of a summary with cage keys (module docstring)."""
    cage_class = classify_cage(summary, limits)
    risk, reasons = risk_level(summary, limits, cage_class)
    metal = summary.get("cage_metal_contact_fraction") or 0.0
    if cage_class == "pressed":
        sector, source = _arc_deg(summary.get("cage_offset_sector")), "cage offset direction, 80 % of the settled time"
    elif metal > 0.0 and summary.get("burn_zone_sector_metal"):
        sector, source = _arc_deg(summary.get("burn_zone_sector_metal")), "metal-contact energy, 80 % arc"
    else:
        sector, source = None, None
    film = summary.get("land_film_min")
    roughness = summary.get("land_roughness")
    contact_film = summary.get("land_contact_film")
    regions = summary.get("pocket_impact_regions")
    window = summary.get("settled_window") or [None, None]
    verdict = {
        "class": cage_class,
        "risk": risk,
        "risk_reasons": reasons,
        "sector_deg": sector,
        "sector_source": source,
        "heat_sector_deg": _arc_deg(summary.get("burn_zone_sector")),
        "land_film_min_um": None if film is None else 1e6 * film,
        "land_film_min_time_s": summary.get("land_film_min_time"),
        "land_film_min_azimuth_deg": _deg(summary.get("land_film_min_azimuth")),
        "land_film_ratio_min": summary.get("land_film_ratio_min"),
        "land_roughness_um": None if roughness is None else 1e6 * roughness,
        "land_contact_film_um": None if contact_film is None else 1e6 * contact_film,
        "metal_contact_fraction": metal,
        "eps_mean": summary.get("cage_eps_mean"),
        "whirl_ratio": summary.get("cage_whirl_ratio"),
        "pocket_impacts": summary.get("pocket_impacts"),
        "pocket_impact_force_p95_N": summary.get("pocket_impact_force_p95"),
        "pocket_impact_regions_deg": None if regions is None else [_arc_deg(r[:2]) for r in regions],
        "pocket_impact_region_shares": None if regions is None else [r[2] for r in regions],
        "settled_from_s": window[0],
        "settled_revolutions": summary.get("settled_revolutions"),
        "screen": summary.get("crush_screen"),
        "non_guiding_gap_min_um": (None if summary.get("non_guiding_gap_min") is None
                                   else 1e6 * summary["non_guiding_gap_min"]),
    }
    verdict["guidance"] = guidance
    verdict["heat_sector_cage_deg"] = _arc_deg(summary.get("burn_zone_sector_cage"))
    verdict["pocket_force_p95_N"] = summary.get("pocket_force_p95")
    if guidance == "ball":
        _ball_guided(verdict, summary)
    verdict["text"] = verdict_sentence(verdict, summary.get("warnings") or [],
                                       LAND_NAMES.get(guidance, "guide land"))
    return verdict


def _ball_guided(verdict: dict, summary: dict) -> None:
    """A ball-guided cage touches no land: no land film, no metal contact, no burn zone; its
    risk is what the balls do to its pockets (the crush screen's regime: balls whose excursion
    the pockets and the cage's play cannot take squeeze the cage between them)."""
    for key in ("sector_deg", "heat_sector_deg", "heat_sector_cage_deg", "land_film_min_um", "land_film_ratio_min",
                "land_contact_film_um", "land_film_min_time_s", "land_film_min_azimuth_deg"):
        verdict[key] = None
    if verdict["class"] == "pressed":
        verdict["sector_deg"] = _arc_deg(summary.get("cage_offset_sector"))
        verdict["sector_source"] = "cage offset direction over the ball set, 80 % of the settled time"
    else:
        verdict["sector_source"] = None
    regime = (summary.get("crush_screen") or {}).get("regime")
    if regime == "crushed":
        verdict["risk"] = "high"
        verdict["risk_reasons"] = ["crush screen: the balls lead and lag by more than the pockets and the cage's "
                                   "play on the balls can take; they squeeze the cage between them"]
    elif regime == "pressed" and verdict["risk"] == "low":
        verdict["risk"] = "elevated"
        verdict["risk_reasons"] = ["crush screen: the balls push the cage off centre over its pockets' play"]


def verdict_sentence(v: dict, warnings: list[str] = (), land: str = "outer-race land") -> str:
    """One sentence: what the cage does, on which film, how risky, whether metal touches."""
    cls = v["class"]
    film = f"{format_film_um(v['land_film_min_um'])} µm" if v.get("land_film_min_um") is not None else None
    ratio = f"Λ {format_ratio(v['land_film_ratio_min'])}" if v.get("land_film_ratio_min") is not None else None
    film_text = f"{film} film ({ratio})" if film and ratio else (f"{film} film" if film else None)
    thinnest = f", thinnest land film {film}" + (f" ({ratio})" if ratio else "") if film else ""
    sector = format_arc(v.get("sector_deg"))
    eps = v.get("eps_mean")
    ball = v.get("guidance") == "ball"
    if ball:
        thinnest = ""
    if cls == "crushed":
        head = f"Cage crushed against the {land} at {sector}{thinnest}"
    elif cls == "pressed" and ball:
        head = (f"Cage pushed onto the balls at {sector}" + (f" (mean ε {eps:.2g} of its pockets' play)"
                                                              if eps is not None else ""))
    elif cls == "pressed":
        head = f"Cage pressed onto the {land} at {sector}" + (f" through a {film_text}" if film_text else "")
        if v.get("guidance") == "inner":
            head += (" (fixed frame; the land turns under it, its heat over "
                     f"{format_arc(v.get('heat_sector_deg'))} of its circumference)")
    elif cls == "whirling":
        whirl = v.get("whirl_ratio")
        head = "Cage whirling" + (f" at {abs(whirl):.2g}× the cage speed" if whirl is not None else "") + thinnest
    elif cls == "centred":
        head = ("Cage centred on the balls" if ball else "Cage centred on its film") + (
            f" (mean ε {eps:.2g})" if eps is not None else "") + thinnest
    else:
        head = "Cage motion chaotic" + (f" (mean ε {eps:.2g})" if eps is not None else "") + thinnest
    metal = v.get("metal_contact_fraction") or 0.0
    contact = ("no metal contact in the settled run" if metal <= 0.0
               else f"metal contact {format_percent(metal)} % of the settled run")
    if ball:
        p95 = v.get("pocket_force_p95_N")
        contact = "no land" + (f"; pocket loads p95 {p95:.3g} N" if p95 is not None else "")
    if metal > 0.0 and film and v.get("land_contact_film_um") is not None:
        # the land law counts metal contact from a film of eps0 C, far above the roughness
        # that Lambda measures: say so where both are printed
        contact += f" (the land law's, below a film of {format_film_um(v['land_contact_film_um'])} µm)"
    tail = ""
    if any(w.startswith("run too short to settle") for w in warnings):
        n = v.get("settled_revolutions")
        tail = "; run too short to settle" + (f" ({n:.1f} cage revolutions settled)" if n is not None else "")
    return f"{head}: {v['risk']} risk; {contact}{tail}."


def _temperature_text(t: dict | None) -> str:
    if not t:
        return ""
    parts = {t.get(k) for k in ("inner_ring", "outer_ring", "ball", "cage")}
    if len(parts) == 1:
        return f"parts at {parts.pop():g} °C"
    return (f"inner ring {t['inner_ring']:g} °C, outer ring {t['outer_ring']:g} °C, balls {t['ball']:g} °C, "
            f"cage {t['cage']:g} °C")


def screen_sentence(screen: dict | None) -> str | None:
    """The crush screen in one line: regime and margin at the operating clearances, the margin
    as drawn, and the crush probability over tolerances when the scene gives them."""
    if not screen:
        return None
    um = 1e6
    text = (f"crush screen at operating clearances (guide {screen['guide_clearance'] * um:.0f} µm, pocket "
            f"{screen['pocket_clearance'] * um:.0f} µm; {_temperature_text(screen.get('temperatures_degC'))}): "
            f"{screen['regime']}, crush margin {screen['crush_margin']:.2f}")
    if screen.get("crush_margin_at_reference_temperature") is not None:
        text += f" ({screen['crush_margin_at_reference_temperature']:.2f} with the clearances as drawn)"
    if screen.get("crush_probability") is not None:
        text += (f"; P(crushed) {100 * screen['crush_probability']:.3g} % ± "
                 f"{100 * screen['crush_probability_standard_error']:.2g} % over {screen['tolerance_samples']} "
                 f"tolerance stacks (5th-percentile margin {screen['margin_p5']:.2f})")
    return text


def impact_regions_text(regions: list, shares: list | None) -> str:
    """"77 % at 240–270°, 17 % at 60–120°": each region's share of the settled impacts with its
    arc, so that a region holding half of them does not read as all."""
    if not shares or len(shares) != len(regions):
        return ", ".join(format_arc(r) for r in regions)
    return ", ".join(f"{format_percent(s)} % at {format_arc(r)}" for r, s in zip(regions, shares))


def verdict_rows(v: dict) -> list[tuple[str, str, str]]:
    """(quantity, value, unit) rows of a verdict for people: the report's table and the
    command line."""
    def num(value, fmt="{:.3g}") -> str:
        return "—" if value is None else fmt.format(value)

    regions = v.get("pocket_impact_regions_deg")
    region_text = ("too few impacts" if regions is None else "all round the orbit" if not regions
                   else impact_regions_text(regions, v.get("pocket_impact_region_shares")))
    rows = [
        ("cage motion (class)", v["class"], ""),
        ("risk", v["risk"] + (f" — {'; '.join(v['risk_reasons'])}" if v.get("risk_reasons") else ""), ""),
        ("loaded sector (azimuth from +x towards +y)",
         format_arc(v.get("sector_deg")) + (f" ({v['sector_source']})" if v.get("sector_source") else ""), "deg"),
        ("land heat, 80 % arc (metal + film; on the land, in its own frame)", format_arc(v.get("heat_sector_deg")),
         "deg"),
        ("  on the cage rim, in the cage's frame", format_arc(v.get("heat_sector_cage_deg")), "deg"),
        ("thinnest land film", format_film_um(v.get("land_film_min_um")), "µm"),
        ("  when", num(v.get("land_film_min_time_s"), "{:.4g}"), "s"),
        ("  where (azimuth)", num(v.get("land_film_min_azimuth_deg"), "{:.0f}"), "deg"),
        (f"film-thickness ratio Λ_min = h_min/σ (σ = {num(v.get('land_roughness_um'))} µm)",
         format_ratio(v.get("land_film_ratio_min")), "-"),
        ("metal-contact fraction", format_percent(v.get("metal_contact_fraction") or 0.0), "%"),
        ("  counted by the land law below a film of ε0 C", format_film_um(v.get("land_contact_film_um")), "µm"),
        ("mean eccentricity ratio ε", num(v.get("eps_mean")), "-"),
        ("whirl ratio (whirl speed / cage speed)", num(v.get("whirl_ratio"), "{:.2g}"), "-"),
        ("pocket impacts", num(v.get("pocket_impacts"), "{:d}"), "count"),
        ("pocket impact force, 95th percentile", num(v.get("pocket_impact_force_p95_N")), "N"),
        ("pocket force over the settled run, 95th percentile (all balls)", num(v.get("pocket_force_p95_N")), "N"),
        ("where the impacts concentrate (share, orbital position)", region_text, "deg"),
        ("settled window from", num(v.get("settled_from_s"), "{:.4g}"), "s"),
        ("  cage revolutions in it", num(v.get("settled_revolutions"), "{:.1f}"), "rev"),
        ("least gap to the non-guiding land in the run (< 0: touching)", num(v.get("non_guiding_gap_min_um"), "{:.0f}"),
         "µm"),
    ]
    screen = v.get("screen")
    if screen:
        def um(key):
            value = screen.get(key)
            return "—" if value is None else f"{value * 1e6:.0f}"

        drawn = screen.get("crush_margin_at_reference_temperature")
        rows += [
            ("crush screen (quasi-static, docs/model.md §10.1)", screen["regime"], ""),
            ("  crush margin at operating clearances", f"{screen['crush_margin']:.2f}", "-"),
            ("  crush margin with the clearances as drawn", "—" if drawn is None else f"{drawn:.2f}", "-"),
            ("  operating temperatures", _temperature_text(screen.get("temperatures_degC")) or "—", ""),
            ("  guide clearance C, operating (as drawn)",
             f"{um('guide_clearance')} ({um('guide_clearance_at_reference_temperature')})", "µm"),
            ("  pocket clearance c_p, operating (as drawn)",
             f"{um('pocket_clearance')} ({um('pocket_clearance_at_reference_temperature')})", "µm"),
            ("  gap left to the non-guiding land (screen)", um("non_guiding_gap"), "µm"),
        ]
        if screen.get("crush_probability") is not None:
            rows += [("  P(crushed) over tolerance stacks",
                      f"{100 * screen['crush_probability']:.3g} ± {100 * screen['crush_probability_standard_error']:.2g} "
                      f"({screen['tolerance_samples']} stacks)", "%"),
                     ("  crush margin, 5th percentile over the stacks", f"{screen['margin_p5']:.2f}", "-")]
    return rows


def verdict_lines(summary: dict | None) -> list[str]:
    """What `bearingsim run` / `simulate` print at the end: the sentence, the main numbers
    on one line, and the warnings."""
    if not summary:
        return []
    v = summary.get("verdict")
    if not v:
        if "cage_speed_mean" not in summary:
            return ["verdict: no cage in this scene (no cage metrics)"]
        return ["verdict: none in this summary.json (written before verdicts existed); "
                "rerun the simulate stage with --force"]
    impacts = f"{v.get('pocket_impacts', 0)} pocket impacts"
    if v.get("pocket_impact_force_p95_N") is not None and v.get("pocket_impacts"):
        impacts += f" (p95 {v['pocket_impact_force_p95_N']:.3g} N"
        regions = v.get("pocket_impact_regions_deg")
        impacts += ("; " + impact_regions_text(regions, v.get("pocket_impact_region_shares")) + ")"
                    if regions else ")")
    film = ""
    if v.get("land_film_min_um") is not None:
        film = (f"thinnest land film {format_film_um(v['land_film_min_um'])} µm at t = "
                f"{v['land_film_min_time_s']:.4g} s, {v['land_film_min_azimuth_deg']:.0f}° "
                f"(Λ {format_ratio(v.get('land_film_ratio_min'))}); ")
    lines = [f"verdict: {v['text']}",
             f"  class {v['class']}, risk {v['risk']}; loaded sector {format_arc(v.get('sector_deg'))}; {film}"
             f"metal contact {format_percent(v.get('metal_contact_fraction') or 0.0)} %; whirl ratio "
             f"{(v.get('whirl_ratio') or 0.0):.2g}; {impacts}"]
    screen_line = screen_sentence(v.get("screen"))
    if screen_line:
        lines.append(f"  {screen_line}")
    lines += [f"  warning: {w}" for w in summary.get("warnings") or []]
    return lines


SHORT_RUN = "too short to settle"  # the words every display of a run that has not settled uses


def too_short_to_settle(summary: dict | None) -> bool:
    """Did the run end before its statistics settled (a `run too short to settle` warning of
    summary.json, pipeline.results.settled_window)?"""
    return any(str(w).startswith(f"run {SHORT_RUN}") for w in (summary or {}).get("warnings") or ())


def short_label(summary: dict | None) -> str:
    """"pressed, elevated risk" — or "pressed, elevated risk; too short to settle": the class
    and risk of a summary's verdict as the repr, the report and the figures' titles show them."""
    verdict = (summary or {}).get("verdict") or {}
    if not verdict.get("class"):
        return "no verdict"
    text = f"{verdict['class']}, {verdict.get('risk', '?')} risk"
    return text + (f"; {SHORT_RUN}" if too_short_to_settle(summary) else "")
