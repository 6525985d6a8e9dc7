"""The sweep's results table: one row per point, from the points' records on disk.

Columns: `point_id`, `status` (done | failed | pending), one column per varied scene key,
`cage_class` and `risk` (`pipeline.scene.cage_classes`), `too_short_to_settle` (the
point's run ended before its cage settled: its class is a transient's), the summary metrics of
docs/scenes.md (with `burn_zone_sector` split into `burn_zone_start` / `burn_zone_end`), run
counters, `warnings` (the run's own, joined by "; "), `error` (the message of a failed point) and
`run_dir`. `warnings` also holds the stages' validity warnings (a contact pressure beyond the
rating, truncated ellipses, a crush screen whose premise fails). Angles are in degrees,
azimuths 0–360 from +x towards +y (`summary.json` keeps rad). The CSV header carries each column's unit, `name [unit]` (`read_table` strips it);
written as CSV, and as parquet too when pyarrow is installed.
"""

from __future__ import annotations

import csv
import io
import math
import os
import tempfile
from pathlib import Path
from typing import Any

from ..staging.artefacts import atomic_write_text
from ..scene.cage_classes import CageClassThresholds, classify_cage, risk_level

SUMMARY_COLUMNS = (
    "cage_speed_mean", "kinematic_cage_speed", "cage_speed_variation",
    "cage_metal_contact_fraction", "cage_contact_angle_spread", "cage_whirl_ratio",
    "cage_eps_mean", "cage_offset_azimuth_mean", "cage_offset_spread", "cage_land_force_mean",
    "land_film_min", "land_film_ratio_min",
    "inner_race_axial_mean", "pocket_impacts", "pocket_impact_force_p95",
    "burn_zone_start", "burn_zone_end", "burn_zone_energy_total",
    "duration", "steps", "rejected_steps", "newton_iterations", "wall_time",
)
CSV_FILE, PARQUET_FILE = "results.csv", "results.parquet"
POSITION_COLUMNS = ("cage_offset_azimuth_mean", "burn_zone_start", "burn_zone_end")  # deg, 0–360
ANGLE_COLUMNS = ("cage_contact_angle_spread", "cage_offset_spread")  # widths, deg


def column_unit(column: str) -> str | None:
    """The unit of a results column (UDUNITS strings, "1" for ratios and counts), None for text."""
    from ..results.summary_keys import unit_of

    if column in POSITION_COLUMNS or column in ANGLE_COLUMNS:
        return "degree"
    if column in SUMMARY_COLUMNS:
        return unit_of(column)
    if "." in column:
        return scene_key_unit(column)
    return None


def scene_key_unit(key: str) -> str | None:
    """The unit of a dotted scene key from its section's metadata (None when unknown)."""
    from ..scene.schema import field_unit

    section, _, name = key.rpartition(".")
    cls = _section_classes().get(section.split(".")[0])
    if cls is None:
        return None
    from ..results.named_arrays import udunits

    unit = field_unit(cls, name)
    return udunits(unit) if unit else None


def _section_classes() -> dict[str, type]:
    from ...dynamics.geometry import BearingGeometry, CageGeometry, Material

    from ..scene.sections import Hinge, Load, Output, Physics, SolverSettings, Speed

    return {"bearing": BearingGeometry, "cage": CageGeometry, "materials": Material, "load": Load,
            "speed": Speed, "hinge": Hinge, "solver": SolverSettings, "physics": Physics, "output": Output}


SHORT_RUN = "run too short to settle"  # how summary.json's warnings begin for such a run


def short_run_warning(rows: list[dict[str, Any]]) -> str | None:
    """The sweep-wide warning when points ran too short to settle, else None."""
    short = sum(1 for r in rows if r.get("too_short_to_settle") in (True, "True"))
    if not short:
        return None
    return (f"{short} of {len(rows)} points ran too short to settle (fewer than 10 cage revolutions in the "
            f"settled window): their classes describe a start-up transient, not a regime; lengthen "
            f"solver.duration")


def result_row(point, record: dict | None, run_dir: Path, limits: CageClassThresholds,
               values: dict[str, Any] | None = None) -> dict[str, Any]:
    """One table row of `point` (a SweepPoint) from its record (None: not run yet); `values`:
    the point's value of every varied key [default: its own overrides]."""
    status = record.get("status", "failed") if record else "pending"
    summary = (record or {}).get("summary") if status == "done" else None
    row: dict[str, Any] = {"point_id": point.id, "status": status}
    row.update(values if values is not None else dict(point.overrides))
    row["cage_class"] = classify_cage(summary, limits) if status != "pending" else "pending"
    row["risk"] = (risk_level(summary, limits, row["cage_class"])[0]
                   if summary is not None and row["cage_class"] in ("centred", "whirling", "pressed", "crushed", "chaotic")
                   else None)
    # a class read from a transient is no regime: say so in the row itself
    row["too_short_to_settle"] = (any(str(w).startswith(SHORT_RUN) for w in summary.get("warnings") or ())
                                  if summary is not None else None)
    flat = dict(summary or {})
    sector = flat.pop("burn_zone_sector", None) or (None, None)
    flat["burn_zone_start"], flat["burn_zone_end"] = sector
    for k in POSITION_COLUMNS + ANGLE_COLUMNS:
        if flat.get(k) is not None:
            flat[k] = math.degrees(flat[k]) % 360.0 if k in POSITION_COLUMNS else math.degrees(flat[k])
    if flat.get("burn_zone_end") is not None and flat["burn_zone_end"] < flat["burn_zone_start"]:
        flat["burn_zone_end"] += 360.0  # an arc across 0°: end = start + width
    row.update({k: flat.get(k) for k in SUMMARY_COLUMNS})
    # the run's own warnings, then what the stages flagged as outside the model's validity
    warned = [str(w) for w in flat.get("warnings") or []] + [str(w) for w in (record or {}).get("validity") or []]
    row["warnings"] = "; ".join(warned) or None
    row["error"] = (record or {}).get("error")
    row["run_dir"] = str(run_dir)
    return row


def write_table(rows: list[dict[str, Any]], sweep_dir: Path) -> list[Path]:
    """Write the rows as `results.csv` (and `results.parquet` with pyarrow), atomically."""
    if not rows:
        return []
    columns = list(dict.fromkeys(c for row in rows for c in row))  # every row's, in order
    text = io.StringIO()
    writer = csv.DictWriter(text, fieldnames=columns, lineterminator="\n")
    units = {c: column_unit(c) for c in columns}
    writer.writerow({c: f"{c} [{units[c]}]" if units[c] else c for c in columns})
    for row in rows:
        writer.writerow({k: ("" if row.get(k) is None else row.get(k)) for k in columns})
    atomic_write_text(sweep_dir / CSV_FILE, text.getvalue())
    written = [sweep_dir / CSV_FILE]
    try:
        import pyarrow
        import pyarrow.parquet
    except ImportError:  # parquet is optional; the CSV holds the same table
        return written
    fd, tmp = tempfile.mkstemp(prefix=f".{PARQUET_FILE}.", dir=sweep_dir)
    os.close(fd)
    pyarrow.parquet.write_table(pyarrow.Table.from_pylist(rows), tmp)
    os.replace(tmp, sweep_dir / PARQUET_FILE)
    return written + [sweep_dir / PARQUET_FILE]


def read_table(path: Path) -> list[dict[str, Any]]:
    """Rows of a `results.csv`: numbers as floats in the columns that hold numbers (a unit in
    the header, or a scene key), text as text (a point id such as `489815446e53` is not
    4.9e61), empty cells as None."""
    with open(path, newline="", encoding="utf-8") as fh:
        return [{_column_name(k): _cell(v, numeric=k.endswith("]") or "." in k) for k, v in row.items()}
                for row in csv.DictReader(fh)]


def _column_name(header: str) -> str:
    """`load.moment [N m]` -> `load.moment`."""
    name, bracket, _ = header.partition(" [")
    return name if bracket and header.endswith("]") else header


def _cell(text: str, numeric: bool) -> Any:
    if text == "":
        return None
    if not numeric:
        return text
    try:
        return float(text)
    except ValueError:
        return text
