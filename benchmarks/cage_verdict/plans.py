"""The run plans of the cage-verdict study (docs/validation.md): (name, scene, --set list)."""

from __future__ import annotations

B = "helicopter-b-given-hinge"  # reference bearing, hand-given hinge: no FE stage per run
NO_HINGE = "benchmarks/cage_verdict/scenes/helicopter-b-no-hinge.toml"  # run from the repository root
MOMENTS = (0, 100, 200, 300, 430, 500, 550, 600, 700)


COLD = ["thermal.parts_degC=20"]  # every part at the drawing's reference temperature


def moment_sweep():
    """At operating temperatures (the default: every part at the oil's 100 °C)."""
    return [(f"m{m:03d}", B, [f"load.moment={m}"]) for m in MOMENTS]


def moment_sweep_cold():
    """The same sweep with Table 1's clearances as drawn (parts at 20 °C)."""
    return [(f"cold-m{m:03d}", B, [f"load.moment={m}"] + COLD) for m in MOMENTS]


def paper_land():
    """The paper's land law (one journal, static film) at L = 7.6 mm (the cage-land overlap) and
    L = w_c = 25.4 mm (the length the paper's L/D remark suggests), beside the defaults."""
    out = []
    for m, tag in ((100, "a"), (430, "b")):
        out.append((f"{tag}-default", B, [f"load.moment={m}"]))
        for length, name in ((0.0076, "L7.6"), (0.0254, "L25.4")):
            out.append((f"{tag}-paper-{name}", B, [f"load.moment={m}", "physics.cage_race_film=static",
                                                    "physics.cage_race_lands=1", f"cage.land_length={length}"]))
    return out


def run_out():
    """Case b with a cage run-out (pocket-circle eccentricity) of 50 and 100 µm, and pitch errors."""
    pitch = [0.0] * 22
    pitch[5], pitch[16] = 20e-6, -20e-6
    return [(f"b-runout-{e}um", B, ["load.moment=430", f"cage.pocket_circle_eccentricity={e * 1e-6}"])
            for e in (50, 100)] + [("b-pitch-40um", B, ["load.moment=430", f"cage.pocket_index_errors={pitch}"])]


def confirm():
    """Dynamic confirmation of the tolerance analyses (data/tolerances_b*.json): the nominal
    operating stack of case b and the stack at the 5th percentile of margin of each set."""
    import json

    from . import DATA

    out = [("b-nominal", B, ["load.moment=430"])]
    for name, tag in (("tolerances_b", "b-p5"), ("tolerances_b_table1", "b-table1-p5")):
        found = json.loads((DATA / f"{name}.json").read_text())
        out.append((tag, B, ["load.moment=430"] + found["stack_at_p5_overrides"]))
    return out


def moment_sweep_static():
    """The same sweep with the paper's static land film and single journal (ablation)."""
    return [(f"static-m{m:03d}", B, [f"load.moment={m}", "physics.cage_race_film=static",
                                     "physics.cage_race_lands=1"]) for m in MOMENTS]


# each uncertain input the reference does not give, at the ends of its documented range
# (sources in docs/validation.md, table "Inputs the reference does not give")
SENSITIVITY = {
    "pocket_friction": ["physics.pocket_friction=0.03", "physics.pocket_friction=0.3"],
    "pocket_restitution": ["physics.pocket_restitution=0.3", "physics.pocket_restitution=0.95"],
    "eyring_stress": ["lubricant.eyring_stress=2.5e6", "lubricant.eyring_stress=1e7"],
    "oil_temperature": ["lubricant.temperature_degC=80", "lubricant.temperature_degC=130"],
    "eps0": ["physics.cage_race_boundary=0.02", "physics.cage_race_boundary=0.1"],
    "land_friction": ["physics.cage_race_friction=0.05", "physics.cage_race_friction=0.3"],
    "lands": ["physics.cage_race_lands=1"],
    "land_film": ["physics.cage_race_film=static"],
    "guide_clearance_hot": ["cage.radial_thickness=0.007506"],   # C 0.290 -> 0.247 mm (bronze vs steel, +80 K)
    "pocket_clearance": ["cage.pocket_diameter=0.02003", "cage.pocket_diameter=0.02043"],  # +/- 0.2 mm
    "contact_damping": ["physics.contact_damping_ratio=0.01", "physics.contact_damping_ratio=0.2"],
    "hinge_stiff": ["hinge.bending=[8.75e6, 8.75e6]", "hinge.translational=[6.55e8, 6.55e8, 5.26e8]"],
}


def _sens(moment: int, tag: str):
    out = [(f"{tag}-base", B, [f"load.moment={moment}"])]
    for name, values in SENSITIVITY.items():
        if name == "hinge_stiff":  # both keys at once: the FE-identified hinge of helicopter-b
            out.append((f"{tag}-{name}", B, [f"load.moment={moment}"] + values))
            continue
        for i, v in enumerate(values):
            out.append((f"{tag}-{name}-{'lo' if i == 0 and len(values) > 1 else 'hi' if len(values) > 1 else 'on'}",
                        B, [f"load.moment={moment}", v]))
    return out


def sensitivity_a():
    return _sens(100, "a")


def sensitivity_b():
    return _sens(430, "b")


def ablations():
    out = []
    for m, tag in ((100, "a"), (430, "b")):
        out += [(f"{tag}-no-hinge", NO_HINGE, [f"load.moment={m}"]),
                (f"{tag}-hydrodynamic", B, [f"load.moment={m}", "physics.cage_race=hydrodynamic"]),
                (f"{tag}-dry", B, [f"load.moment={m}", "physics.cage_race=dry"])]
    return out


def repeat():
    """Run-to-run spread: the same scenes at other tolerances (rounding-level perturbations)."""
    out = []
    for m, tag in ((100, "a"), (430, "b")):
        for atol in ("5e-10", "2e-9"):
            out.append((f"{tag}-atol{atol}", B, [f"load.moment={m}", f"solver.atol={atol}"]))
    return out


PLANS = {"moment_sweep": moment_sweep, "moment_sweep_cold": moment_sweep_cold, "paper_land": paper_land,
         "run_out": run_out, "confirm": confirm, "moment_sweep_static": moment_sweep_static,
         "sensitivity_a": sensitivity_a, "sensitivity_b": sensitivity_b, "ablations": ablations,
         "repeat": repeat}
