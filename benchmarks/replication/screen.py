"""What a rig would have to measure to settle case b: the crush margin of the screen
(docs/model.md §10.1) against each measurable input, its slope, and the value of the input at
which the margin reaches 0 (the bearing becomes crushed). About a second on one core.

Each input is changed alone from `helicopter-b` as shipped (every part at the oil's 100 °C).
"""

from __future__ import annotations

from .plan import OUTER_GROOVE_CENTRE

SCENE = "helicopter-b"

BALL = 0.01905         # m, Table 1
CAGE_OUTSIDE = 0.16542  # m, d_c + e_c of Table 1
PD_DRAWN = 118.0        # µm, the diametral clearance of Table 1's diameters

# label, scene key, base value, step of the key, unit shown, the quantity shown (a function of
# the key's value: what a rig measures), how the key sets it
INPUTS = (
    ("diametral clearance P_d (as drawn)", "bearing.outer_groove_center_diameter", OUTER_GROOVE_CENTRE, 10e-6,
     "µm", lambda v: PD_DRAWN + (v - OUTER_GROOVE_CENTRE) * 1e6,
     "through the outer groove's curvature-centre diameter (one for one)"),
    ("guide clearance C (radial, as drawn)", "bearing.outer_shoulder_diameter", 0.166, 20e-6,
     "µm", lambda v: 0.5e6 * (v - CAGE_OUTSIDE), "through the outer land's diameter"),
    ("pocket clearance c_p (as drawn)", "cage.pocket_diameter", 0.02023, 10e-6,
     "µm", lambda v: 1e6 * (v - BALL), "through the pocket diameter"),
    ("cage temperature", "thermal.cage_degC", 100.0, 10.0, "°C", lambda v: v, "the other parts at the oil's 100 °C"),
    ("outer-ring temperature", "thermal.outer_ring_degC", 100.0, 10.0, "°C", lambda v: v, ""),
    ("inner-ring temperature", "thermal.inner_ring_degC", 100.0, 10.0, "°C", lambda v: v, ""),
    ("ball temperature", "thermal.ball_degC", 100.0, 10.0, "°C", lambda v: v, ""),
    ("every part's temperature", "thermal.parts_degC", 100.0, 10.0, "°C", lambda v: v, "a common rise"),
    ("cage run-out e_r", "cage.pocket_circle_eccentricity", 0.0, 10e-6, "µm", lambda v: 1e6 * v,
     "the pocket circle's offset from the rim's centre"),
    ("moment", "load.moment", 430.0, 10.0, "N·m", lambda v: v, "what the rig applies"),
    ("land length L", "cage.land_length", 0.0076, 1e-3, "mm", lambda v: 1e3 * v, "the film's length"),
)


def crush_margin(overrides: list[str]) -> dict:
    from bearingsim.pipeline.scene.load import load_scene
    from bearingsim.pipeline.stages.quasistatic import cage_screen, solve

    scene = load_scene(SCENE, overrides)
    s = cage_screen(scene, solve(scene))
    return {"margin": s.crush_margin, "regime": s.regime}


def _crossing(key: str, base: float, step: float, slope_per_step: float, margin0: float) -> float | None:
    """The key's value at which the margin reaches 0, by bisection within 30 steps of `base` on
    the side the slope points to (nearer where the scene stops being valid, e.g. a cage that no
    longer fits its land); None when the margin does not reach 0 there."""
    from bearingsim.pipeline.scene.schema import SceneError

    if slope_per_step == 0.0:
        return None
    direction = -1.0 if (slope_per_step > 0) == (margin0 > 0) else 1.0
    lo, hi = base, base + direction * 30.0 * step
    for _ in range(12):
        try:
            far = crush_margin([f"{key}={hi!r}"])["margin"]
            break
        except SceneError:
            hi = base + 0.5 * (hi - base)
    else:
        return None
    if (far > 0) == (margin0 > 0):
        return None
    for _ in range(30):
        mid = 0.5 * (lo + hi)
        if (crush_margin([f"{key}={mid!r}"])["margin"] > 0) == (margin0 > 0):
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def sensitivities() -> dict:
    """For each input: the margin's change per step (central difference) and where it reaches 0."""
    base = crush_margin([])
    rows = []
    for label, key, value, step, unit, shown, note in INPUTS:
        up = crush_margin([f"{key}={value + step!r}"])["margin"]
        down = crush_margin([f"{key}={value - step!r}"])["margin"] if value - step >= 0.0 else base["margin"]
        span = 2.0 if value - step >= 0.0 else 1.0
        slope = (up - down) / span
        crossing = _crossing(key, value, step, slope, base["margin"])
        rows.append({"label": label, "key": key, "base": value, "step": step, "unit": unit, "note": note,
                     "base_shown": shown(value), "step_shown": shown(value + step) - shown(value),
                     "margin_per_step": slope, "crushed_at": crossing,
                     "crushed_at_shown": None if crossing is None else shown(crossing)})
    return {"scene": SCENE, "base": base, "inputs": rows}
