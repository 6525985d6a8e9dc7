"""The clearances that decide the cage verdict, cold (as drawn) and at operating temperatures.

Used by `bearingsim check` (printed side by side), the quasi-static stage (the crush screen and
`quasistatic.json`) and the simulate stage's summary (docs/model.md §2.1, §10.1).

A scene or parts argument is a `pipeline.scene.load.Scene` or `Parts`, not imported here: the
scene's own display (pipeline.scene.display) shows these clearances.
"""

from __future__ import annotations

import math

from ...dynamics.journal.land_laws import LAWS as LAND_LAWS
from ...dynamics.quasistatic.crush_screen import CageClearances, LandFilm


def cage_clearances(parts) -> CageClearances:
    """Pocket, guide and non-guiding clearances and the run-out of one state of the parts."""
    b, c = parts.bearing, parts.cage
    return CageClearances(pocket=c.pocket_diameter - b.ball_diameter, guide=c.guide_clearance(b),
                          pocket_circle_eccentricity=c.pocket_circle_eccentricity,
                          pocket_index_range=c.pocket_index_range(), non_guiding=c.non_guiding_clearance(b))


def land_film(scene) -> LandFilm:
    """The guide lands of the operating cage as the screen's short journal bearing (none for
    a ball-guided cage: a film of no length, which pushes nothing). The land law decides
    (`land_laws`): a law without film pushes nothing (viscosity 0), and the film clearance is
    C (1 + eps0) only for a law with a boundary layer (C otherwise)."""
    b, c = scene.operating.bearing, scene.operating.cage
    law = LAND_LAWS[scene.physics.cage_race]
    viscosity = scene.lubricant.eta0 if scene.lubricant is not None and law.film else 0.0
    eps0 = scene.physics.cage_race_boundary if law.flags["boundary"] else 0.0
    if c.guide_ring is None:
        return LandFilm(radius=0.5 * c.mean_diameter, length=0.0, lands=1, eps0=eps0, viscosity=0.0)
    return LandFilm(radius=0.5 * c.guide_land_diameter(b), length=c.guide_land_length(b),
                    lands=scene.physics.cage_race_lands if c.guide_land_count(b) == 2 else 1,
                    eps0=eps0, viscosity=viscosity)


def _operating(scene):
    return scene.operating


# (key, label, function of the parts) for the table
_ROWS = (
    ("diametral_clearance", "diametral clearance P_d", lambda p: p.bearing.diametral_clearance),
    ("free_contact_angle", "free contact angle alpha_0", lambda p: p.bearing.free_contact_angle),
    ("pitch_diameter", "pitch diameter d_m", lambda p: p.bearing.pitch_diameter),
    ("guide_clearance", "cage guide clearance C (radial)",
     lambda p: p.cage.guide_clearance(p.bearing) if p.cage is not None else None),
    ("pocket_clearance", "pocket clearance c_p = d_p - D",
     lambda p: p.cage.pocket_diameter - p.bearing.ball_diameter if p.cage is not None else None),
    ("non_guiding_clearance", "non-guiding gap C_n (radial, parts centred)",
     lambda p: p.cage.non_guiding_clearance(p.bearing) if p.cage is not None else None),
    ("guide_land_length", "guide land length L (both lands)",
     lambda p: p.cage.guide_land_length(p.bearing) if p.cage is not None else None),
)


def clearance_table(scene) -> dict:
    """{key: {"reference": value, "operating": value}} in SI (m, rad), plus the temperatures
    [°C]; keys without a value (no cage, no land) are left out."""
    ops, cold = scene.operating, scene.nominal
    out: dict = {}
    for key, _, f in _ROWS:
        try:
            ref, op = f(cold), f(ops)
        except ValueError:  # e.g. no land diameter
            continue
        if ref is not None and op is not None:
            out[key] = {"reference": float(ref), "operating": float(op)}
    t = scene.temperatures
    out["temperatures_degC"] = {"reference": t.reference, "inner_ring": t.inner_ring, "outer_ring": t.outer_ring,
                                "ball": t.ball, "cage": t.cage}
    out["units"] = {"lengths": "m", "free_contact_angle": "rad", "temperatures_degC": "degC"}
    return out


def clearance_rows(scene) -> list[tuple[str, str, str, str]]:
    """(quantity, at reference temperature, operating, unit) for people: µm, mm, deg."""
    table = clearance_table(scene)
    rows = []
    for key, label, _ in _ROWS:
        if key not in table:
            continue
        ref, op = table[key]["reference"], table[key]["operating"]
        if key == "free_contact_angle":
            rows.append((label, f"{math.degrees(ref):.3f}", f"{math.degrees(op):.3f}", "deg"))
        elif key in ("pitch_diameter", "guide_land_length"):
            rows.append((label, f"{ref * 1e3:.4f}", f"{op * 1e3:.4f}", "mm"))
        else:
            rows.append((label, f"{ref * 1e6:.1f}", f"{op * 1e6:.1f}", "µm"))
    return rows
