"""The runs of docs/replication.md: the reference cases as shipped, with the reference paper's
modelling choices (the built-in scenes `helicopter-a-paper`, `helicopter-b-paper`), and with one
departure of the default model from the paper undone at a time.

Each run is (name, scene, overrides). Every run lasts the scenes' 0.8 s, the paper's duration,
at the product's solver defaults; figures are skipped (`output.figures = false`: the results are
the same) to save their drawing time.
"""

from __future__ import annotations

CASES = {"a": "helicopter-a", "b": "helicopter-b"}            # as shipped: FE-identified hinge
PRESETS = {"a": "helicopter-a-paper", "b": "helicopter-b-paper"}  # the paper's stated choices
MOMENTS = {"a": 100.0, "b": 430.0}

CAGE_WIDTH = 0.0254  # m, the cage width w_c of Table 1: the land length the paper's L/D remark suggests
# Table 1's curvature-centre diameters are given to 0.1 mm, so the diametral clearance P_d is known
# to +-0.1 mm; P_d = d_o + 2 r_o - (d_i - 2 r_i) - 2 D moves one for one with d_o (docs/model.md §2)
OUTER_GROOVE_CENTRE = 0.1573  # m, Table 1
PD_TABLE1 = 118e-6            # m, the P_d Table 1's rounded diameters give
PD_CRUSHED = 185e-6           # m, a clearance inside that uncertainty, past the screen's crush threshold

FIGURES_OFF = ["output.figures=false"]

# one departure of the default model from the paper, undone: the keys that set the paper's choice
DEPARTURES = {
    "cold": ["thermal.parts_degC=20"],
    "static-film": ["physics.cage_race_film=static"],
    "one-land": ["physics.cage_race_lands=1"],
    "step": ["solver.max_step=2e-6"],
    "no-damping": ["physics.contact_damping_ratio=0"],
    "restitution": ["physics.pocket_restitution=1"],
    "paper-hinge": ["hinge.source=given", "hinge.translational=[1e9, 1e9, 1e9]", "hinge.bending=[1e5, 1e5]",
                    "hinge.damping_ratio_time=1e-6"],
    "land-wc": [f"cage.land_length={CAGE_WIDTH}"],
    "rtol": ["solver.rtol=1e-7"],
}


def runs() -> list[tuple[str, str, list[str]]]:
    """Every run of the page, in the order they are made."""
    out = []
    for case in ("b", "a"):
        scene, moment = CASES[case], MOMENTS[case]
        out.append((f"{case}-shipped", scene, []))
        # run-to-run spread: the same bearing with the moment changed by 1e-6 of its value
        # (docs/validation.md §13's method), far below what a rig holds its load to
        out.append((f"{case}-repeat", scene, [f"load.moment={moment * (1.0 + 1e-6)!r}"]))
        out.append((f"{case}-paper", PRESETS[case], []))
        out.append((f"{case}-paper-land-wc", PRESETS[case], [f"cage.land_length={CAGE_WIDTH}"]))
        out.append((f"{case}-no-hinge", scene, ["hinge.source=none"]))
        for name, overrides in DEPARTURES.items():
            out.append((f"{case}-{name}", scene, list(overrides)))
    d_o = OUTER_GROOVE_CENTRE + (PD_CRUSHED - PD_TABLE1)
    out.append(("b-pd185", CASES["b"], [f"bearing.outer_groove_center_diameter={d_o:.6f}"]))
    return out
