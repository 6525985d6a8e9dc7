"""What every number of `summary.json` is: its unit (the `units` map written into the file)
and how a person reads it (the report's metrics table).

`summary.json` keeps SI units (angles in rad, azimuth from +x towards +y, docs/model.md §1),
except its `verdict`, which repeats the numbers in the units a reader uses (degrees, µm).
Unit strings follow UDUNITS ("1" for a ratio or a count, "N m", "degree"), so a netCDF or
pint user can parse them. A key missing here has no unit in the file: the summary-units tests (tests/test_render_stage.py, tests/test_api.py)
fails on it, so a new summary key needs a line here.

For people (`METRICS`): a label, the unit shown, a factor from SI and a format; angular
*positions* (azimuths, sectors) are shown in degrees 0–360, the one convention of every
user-facing table, plot and CSV.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

# the crush screen's block (pipeline.results.simulation_output.screen_summary), repeated in the verdict
_SCREEN_UNITS = {
    "crush_margin": "1", "crush_margin_at_reference_temperature": "1", "guide_clearance": "m",
    "pocket_clearance": "m", "non_guiding_gap": "m", "guide_clearance_at_reference_temperature": "m",
    "pocket_clearance_at_reference_temperature": "m", "temperatures_degC.*": "degC", "crush_probability": "1",
    "crush_probability_standard_error": "1", "tolerance_samples": "1", "margin_p5": "1",
}

# dotted key (nested tables joined by ".", "*" any key of that table) -> UDUNITS unit
SUMMARY_UNITS: dict[str, str] = {
    "duration": "s", "wall_time": "s", "integration_wall_time": "s", "kernel_load_time": "s",
    "steps": "1", "rejected_steps": "1", "newton_failures": "1", "newton_iterations": "1",
    "factorizations": "1", "residual_evaluations": "1", "min_step_accepts": "1",
    "energy.*": "J", "kinematic_cage_speed": "rad/s",
    "settled_window": "s", "settled_revolutions": "1",
    "cage_speed_mean": "rad/s", "cage_speed_variation": "1",
    "cage_eps_mean": "1", "cage_eps_max": "1", "cage_metal_contact_fraction": "1",
    "cage_contact_angle_spread": "rad", "cage_offset_azimuth_mean": "rad", "cage_offset_spread": "rad",
    "cage_offset_sector": "rad", "cage_whirl_ratio": "1",
    "cage_land_force_mean": "N", "cage_land_force_max": "N",
    "land_film_min": "m", "land_film_min_time": "s", "land_film_min_azimuth": "rad",
    "land_roughness": "m", "land_film_ratio_min": "1", "land_contact_film": "m",
    "inner_race_axial_mean": "m",
    "pocket_impacts": "1", "pocket_impact_force_p95": "N",
    "pocket_impact_regions": "rad, rad, 1 (start, end, share)",
    "burn_zone_sector": "rad", "burn_zone_sector_metal": "rad", "burn_zone_sector_cage": "rad",
    "pocket_force_max_mean": "N", "pocket_force_p95": "N",
    "burn_zone_energy_metal": "J", "burn_zone_energy_film": "J", "burn_zone_energy_total": "J",
    "startup.end_time": "s", "startup.revolutions": "1", "startup.block_length": "s",
    "startup.max_metal_force": "N", "startup.metal_energy": "J", "startup.film_energy": "J",
    "startup.land_force_peak": "N", "startup.metal_contact_fraction": "1",
    "startup.pocket_impacts": "1", "startup.pocket_impact_force_max": "N",
    "settled_drift.cage_eps_mean": "1", "settled_drift.cage_metal_contact_fraction": "1",
    "settled_drift.cage_land_force_mean": "N", "settled_drift.cage_offset_azimuth_mean": "rad",
    "settled_drift.land_film_min": "m",
    "verdict.sector_deg": "degree", "verdict.heat_sector_deg": "degree", "verdict.heat_sector_cage_deg": "degree",
    "verdict.pocket_force_p95_N": "N",
    "verdict.land_film_min_um": "um", "verdict.land_film_min_time_s": "s",
    "verdict.land_film_min_azimuth_deg": "degree", "verdict.land_film_ratio_min": "1",
    "verdict.land_roughness_um": "um", "verdict.land_contact_film_um": "um",
    "verdict.metal_contact_fraction": "1", "verdict.eps_mean": "1",
    "verdict.whirl_ratio": "1", "verdict.pocket_impacts": "1", "verdict.pocket_impact_force_p95_N": "N",
    "verdict.pocket_impact_regions_deg": "degree (start, end)",
    "verdict.pocket_impact_region_shares": "1",
    "verdict.settled_from_s": "s", "verdict.settled_revolutions": "1",
    "non_guiding_clearance": "m", "non_guiding_gap_min": "m", "non_guiding_gap_min_time": "s",
    "non_guiding_contact_fraction": "1", "verdict.non_guiding_gap_min_um": "um",
    **{f"{block}.{key}": unit for block in ("crush_screen", "verdict.screen") for key, unit in _SCREEN_UNITS.items()},
}


def _is_number(value: Any) -> bool:
    if isinstance(value, bool):
        return False
    if isinstance(value, (int, float)):
        return True
    return isinstance(value, (list, tuple)) and any(_is_number(v) for v in value)


def numeric_keys(summary: dict, prefix: str = "") -> list[str]:
    """Dotted keys of every number (or list holding numbers) in `summary`, nested tables
    included; `units` itself is not walked."""
    keys = []
    for key, value in summary.items():
        if not prefix and key == "units":
            continue
        if isinstance(value, dict):
            keys += numeric_keys(value, f"{prefix}{key}.")
        elif _is_number(value):
            keys.append(f"{prefix}{key}")
    return keys


def unit_of(key: str) -> str | None:
    """The unit of a dotted summary key (None when it has none here)."""
    if key in SUMMARY_UNITS:
        return SUMMARY_UNITS[key]
    table = key.rsplit(".", 1)[0]
    return SUMMARY_UNITS.get(f"{table}.*") if "." in key else None


def summary_units(summary: dict) -> dict[str, str]:
    """The `units` map of a summary: dotted key -> unit for every number it holds. Keys with
    no unit here are left out (the test of the summary's units names them)."""
    out = {}
    for key in numeric_keys(summary):
        unit = unit_of(key)
        if unit is not None:
            out[key] = unit
    return out


@dataclass(frozen=True)
class Metric:
    """How the report shows one summary key: label, unit shown, factor from SI, format; kind
    "position" (an azimuth, shown 0–360°), "arc" ([start, end] shown as 'a–b°') or "value"."""

    label: str
    unit: str
    factor: float = 1.0
    fmt: str = "{:.4g}"
    kind: str = "value"


DEG = 180.0 / math.pi
METRICS: dict[str, Metric] = {
    "duration": Metric("simulated time", "s", fmt="{:.4g}"),
    "kinematic_cage_speed": Metric("cage speed, kinematic (pure rolling)", "rev/min", 30.0 / math.pi, "{:.1f}"),
    "settled_window": Metric("settled window", "s", kind="arc", fmt="{:.4g}"),
    "settled_revolutions": Metric("cage revolutions in the settled window", "", fmt="{:.2f}"),
    "cage_speed_mean": Metric("cage speed, mean", "rev/min", 30.0 / math.pi, "{:.1f}"),
    "cage_speed_variation": Metric("cage speed variation (max − min) / mean", "%", 100.0, "{:.2f}"),
    "cage_eps_mean": Metric("eccentricity ratio ε, mean", "", fmt="{:.3f}"),
    "cage_eps_max": Metric("eccentricity ratio ε, max", "", fmt="{:.3f}"),
    "cage_metal_contact_fraction": Metric("metal-contact fraction (ε > 1)", "%", 100.0, "{:.1f}"),
    "cage_contact_angle_spread": Metric("spread of the metal-contact azimuth", "deg", DEG, "{:.1f}"),
    "cage_offset_azimuth_mean": Metric("cage offset direction, mean", "deg", DEG, "{:.0f}", "position"),
    "cage_offset_spread": Metric("spread of the cage offset direction", "deg", DEG, "{:.1f}"),
    "cage_offset_sector": Metric("sector of the offset (80 % of the time)", "deg", DEG, kind="arc"),
    "cage_whirl_ratio": Metric("whirl ratio (whirl speed / cage speed)", "", fmt="{:.2g}"),
    "cage_land_force_mean": Metric("land force on the cage, mean", "N", fmt="{:.3g}"),
    "cage_land_force_max": Metric("land force on the cage, max", "N", fmt="{:.3g}"),
    "land_film_min": Metric("thinnest land film", "µm", 1e6, "{:.3g}"),
    "land_film_min_time": Metric("  at time", "s", fmt="{:.4g}"),
    "land_film_min_azimuth": Metric("  at azimuth", "deg", DEG, "{:.0f}", "position"),
    "land_roughness": Metric("composite land roughness σ", "µm", 1e6, "{:.3g}"),
    "land_film_ratio_min": Metric("film-thickness ratio Λ_min = h_min/σ", "", fmt="{:.3g}"),
    "land_contact_film": Metric("film below which the land law counts metal contact (ε0 C)", "µm", 1e6, "{:.3g}"),
    "inner_race_axial_mean": Metric("inner-race axial position, mean", "µm", 1e6, "{:.2f}"),
    "pocket_impacts": Metric("pocket impacts (settled window)", "", fmt="{:d}"),
    "pocket_impact_force_p95": Metric("pocket impact force, 95th percentile", "N", fmt="{:.3g}"),
    "burn_zone_sector": Metric("land heat, 80 % arc (metal + film)", "deg", DEG, kind="arc"),
    "burn_zone_sector_metal": Metric("land heat, 80 % arc (metal only)", "deg", DEG, kind="arc"),
    "burn_zone_energy_metal": Metric("land heat, metal contact", "J", fmt="{:.3g}"),
    "burn_zone_energy_film": Metric("land heat, film shear", "J", fmt="{:.3g}"),
    "burn_zone_energy_total": Metric("land heat, total", "J", fmt="{:.3g}"),
    "energy.drive": Metric("energy put in by the drive", "J", fmt="{:.4g}"),
    "energy.external": Metric("work of the external loads", "J", fmt="{:.3g}"),
    "energy.dissipated": Metric("energy dissipated", "J", fmt="{:.4g}"),
    "energy.stored_change": Metric("change of kinetic and elastic energy", "J", fmt="{:.3g}"),
    "energy.balance_residual": Metric("energy balance residual (integrator damping)", "J", fmt="{:.3g}"),
    "non_guiding_gap_min": Metric("least gap to the non-guiding land (< 0: touching)", "µm", 1e6, "{:.0f}"),
    "non_guiding_contact_fraction": Metric("time touching the non-guiding land", "%", 100.0, "{:.2g}"),
    "startup.end_time": Metric("start-up: ends at", "s", fmt="{:.4g}"),
    "startup.revolutions": Metric("start-up: cage revolutions", "", fmt="{:.2f}"),
    "startup.block_length": Metric("start-up: block length of the settling test", "s", fmt="{:.3g}"),
    "startup.max_metal_force": Metric("start-up: largest metal-contact force", "N", fmt="{:.3g}"),
    "startup.metal_energy": Metric("start-up: metal-contact energy", "J", fmt="{:.3g}"),
    "startup.film_energy": Metric("start-up: film shear energy", "J", fmt="{:.3g}"),
    "startup.land_force_peak": Metric("start-up: peak land force", "N", fmt="{:.3g}"),
    "startup.metal_contact_fraction": Metric("start-up: metal-contact fraction", "%", 100.0, "{:.1f}"),
    "startup.pocket_impacts": Metric("start-up: pocket impacts", "", fmt="{:d}"),
    "startup.pocket_impact_force_max": Metric("start-up: largest pocket impact force", "N", fmt="{:.3g}"),
}


def wrap_degrees(angle_deg: float) -> float:
    """An azimuth in [0, 360)."""
    return float(angle_deg) % 360.0


def metric_text(metric: Metric, value: Any) -> str:
    """The value of one metric as the report shows it ('—' for none)."""
    if value is None:
        return "—"
    if metric.kind == "arc":
        a, b = (float(v) * metric.factor for v in value)
        if metric.unit == "deg":
            if b - a >= 359.5:
                return "all round"
            return f"{wrap_degrees(a):.0f}–{wrap_degrees(b):.0f}"
        return f"{metric.fmt.format(a)}–{metric.fmt.format(b)}"
    if isinstance(value, float) and math.isnan(value):
        return "—"
    x = value * metric.factor
    if metric.kind == "position":
        x = wrap_degrees(x)
    if metric.fmt == "{:d}":
        return f"{int(round(x))}"
    return metric.fmt.format(x)


def angle_difference(a: float, b: float) -> float:
    """|a − b| on the circle [rad], in [0, π]: 6.27 and 0.007 rad are 0.02 rad apart."""
    d = (float(b) - float(a)) % (2.0 * math.pi)
    return min(d, 2.0 * math.pi - d)
