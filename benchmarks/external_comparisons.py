"""Comparisons with published data for bearings other than the reference one (docs/validation.md §16).

    python -m benchmarks.external_comparisons [--out docs/validation] [--data benchmarks/data] [--reuse]

1. Quasi-static deflections of a 7-ball deep-groove bearing against the ISO/TS 16281 results of
   a commercial code (MASTA), as quoted for its six examples in the test data of the public
   ISO 16281 implementation github.com/minzhun/ISO16281 (Test_BallBearing.py, commit 1b0e9de):
   figure external_masta.png.
2. Cage speed of the 120-mm-bore turbine bearing of NASA's high-speed tests (Bamberger, Zaretsky &
   Signer, NASA TN D-7870, 1975) over shaft speed, at the published thrust of 22 240 N: the
   report's abstract gives skidding "generally increasing with speed at a given load", the
   highest, 6 percent, at the highest speed, 25 000 rpm. The scene's geometry is representative,
   not the tested bearing's (pipeline/scenes/turbine-thrust-120.toml): figure external_nasa_skid.png.

Skid is taken as NASA's: 1 - (measured cage speed) / (cage speed of pure rolling), the latter from
the epicyclic formula at the contact angles of the operating point. Both references below: the
nominal 20° and the quasi-static solution's (which carries the centrifugal and thrust changes of
the angles). Writes the figures to --out and the numbers, external_comparisons.json, to --data;
--reuse reads a run whose summary.json exists.
"""

from __future__ import annotations

import argparse
import json
import math
from pathlib import Path

# (label, diametral clearance [mm], radial [N], axial [N], moment [N m], kinematics, quantity, MASTA value)
MASTA_CASES = (
    ("1: radial, s 0", 0.0, 1000.0, 0.0, 0.0, "exact", "radial deflection [µm]", 15.1101),
    ("2: axial, s 0", 0.0, 0.0, 1000.0, 0.0, "exact", "axial deflection [µm]", 133.5381),
    ("3: radial, s 10 µm", 0.01, 1000.0, 0.0, 0.0, "exact", "radial deflection [µm]", 21.223),
    ("4: axial, s 10 µm", 0.01, 0.0, 1000.0, 0.0, "exact", "axial deflection [µm]", 149.1717),
    ("5: combined, radial", 0.01, 1000.0, 1000.0, 0.0, "linear", "radial deflection [µm]", 19.5923),
    ("5: combined, axial", 0.01, 1000.0, 1000.0, 0.0, "linear", "axial deflection [µm]", 146.4603),
    ("6: moment 1 N m", 0.0, 0.0, 0.0, 1.0, "exact", "tilt [mrad]", 3.6957),
)
NASA_SPEEDS_RPM = (10000.0, 15000.0, 20000.0, 25000.0)
NASA_SKID_MAX = (25000.0, 0.06)  # TN D-7870 abstract: the highest skid, 6 %, at 25 000 rpm
NASA_DURATION = 0.1  # s: the scene's own


def masta_comparison() -> list[dict]:
    from bearingsim.dynamics.geometry import BearingGeometry, Material
    from bearingsim.dynamics.operating_point import OperatingPoint
    from bearingsim.dynamics.quasistatic.options import QuasiStaticOptions
    from bearingsim.dynamics.quasistatic.solver import solve_quasistatic

    steel = Material(210e9, 0.3, 7850.0)
    rows = []
    for label, s_mm, fr, fa, m, kin, quantity, ref in MASTA_CASES:
        bearing = BearingGeometry.from_catalogue(11.5e-3, 7, 43.5e-3, 0.52, 0.53, s_mm * 1e-3)
        res = solve_quasistatic(bearing, steel, steel, OperatingPoint(radial=fr, axial=fa, moment=m),
                                QuasiStaticOptions(centrifugal=False, kinematics=kin))
        if quantity.startswith("tilt"):
            value = abs(res.inner_tilt[1]) * 1e3
        else:
            value = res.inner_displacement[0 if quantity.startswith("radial") else 2] * 1e6
        rows.append({"case": label, "quantity": quantity, "masta": ref, "bearingsim": float(value),
                     "difference": float(value / ref - 1.0)})
    return rows


def epicyclic_cage_speed(inner: float, ball: float, pitch: float, alpha_i: float, alpha_o: float) -> float:
    """Cage speed of pure rolling with the outer ring fixed (Harris & Kotzalas, vol. 1, ch. 8):
    omega_c = omega_i (1 - gamma_i) / ((1 - gamma_i) + (1 + gamma_o)), gamma = D cos(alpha) / d_m;
    equal angles give omega_i (1 - gamma) / 2."""
    gi, go = ball * math.cos(alpha_i) / pitch, ball * math.cos(alpha_o) / pitch
    return inner * (1.0 - gi) / ((1.0 - gi) + (1.0 + go))


def nasa_comparison(out: Path, reuse: bool) -> list[dict]:
    import bearingsim
    from bearingsim.pipeline.quasistatic.solution import solve

    rows = []
    for rpm in NASA_SPEEDS_RPM:
        overrides = [f"speed.inner_rpm={rpm!r}", f"solver.duration={NASA_DURATION!r}", "output.figures=false"]
        run_dir = out / "runs" / f"turbine-{int(rpm)}"
        summary_file = run_dir / "simulate" / "summary.json"
        if not (reuse and summary_file.exists()):
            bearingsim.run("turbine-thrust-120", run_dir, ["simulate"], overrides=overrides)
        summary = json.loads(summary_file.read_text(encoding="utf-8"))
        scene = bearingsim.load_scene("turbine-thrust-120", overrides)
        qs = solve(scene)
        b, w_i = scene.operating.bearing, scene.speed.inner
        nominal = epicyclic_cage_speed(w_i, b.ball_diameter, b.pitch_diameter, b.free_contact_angle,
                                       b.free_contact_angle)
        operating = epicyclic_cage_speed(w_i, b.ball_diameter, b.pitch_diameter, float(qs.inner_contact_angle.mean()),
                                         float(qs.outer_contact_angle.mean()))
        cage = summary["cage_speed_mean"]
        rows.append({"inner_rpm": rpm, "cage_speed": cage, "cage_speed_variation": summary["cage_speed_variation"],
                     "settled_window_s": summary["settled_window"],
                     "pure_rolling_nominal": nominal, "pure_rolling_operating": operating,
                     "contact_angle_inner_deg": math.degrees(float(qs.inner_contact_angle.mean())),
                     "contact_angle_outer_deg": math.degrees(float(qs.outer_contact_angle.mean())),
                     "skid_nominal": 1.0 - cage / nominal, "skid_operating": 1.0 - cage / operating,
                     "verdict": summary["verdict"].get("text", "") if isinstance(summary["verdict"], dict) else ""})
    return rows


def figures(out: Path, masta: list[dict], nasa: list[dict]) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7.0, 3.6))
    labels = [f"{r['case']}\n{r['quantity']}" for r in masta]
    x = range(len(masta))
    ax.bar([i - 0.2 for i in x], [r["masta"] for r in masta], 0.4, label="MASTA (ISO/TS 16281)")
    ax.bar([i + 0.2 for i in x], [r["bearingsim"] for r in masta], 0.4, label="bearingsim quasi-static")
    for i, r in zip(x, masta):
        ax.annotate(f"{100 * r['difference']:+.2f} %", (i, max(r["masta"], r["bearingsim"])), ha="center",
                    va="bottom", fontsize=7)
    ax.set_yscale("log")
    ax.set_xticks(list(x), labels, fontsize=6)
    ax.set_ylabel("deflection [µm] or tilt [mrad]")
    ax.set_title("7-ball deep-groove bearing (D 11.5 mm, d_m 43.5 mm): ISO/TS 16281 examples", fontsize=9)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out / "external_masta.png", dpi=130)
    plt.close(fig)

    fig, ax = plt.subplots(figsize=(6.0, 3.6))
    rpm = [r["inner_rpm"] for r in nasa]
    ax.plot(rpm, [100 * r["skid_nominal"] for r in nasa], "o-", label="bearingsim, against pure rolling at 20°")
    ax.plot(rpm, [100 * r["skid_operating"] for r in nasa], "s-",
            label="bearingsim, against pure rolling at the operating angles")
    ax.plot([NASA_SKID_MAX[0]], [100 * NASA_SKID_MAX[1]], "k*", markersize=12,
            label="NASA TN D-7870: highest measured skid")
    ax.axhline(0.0, color="0.6", lw=0.8)
    ax.set_xlabel("shaft speed [rev/min]")
    ax.set_ylabel("skid = 1 - cage speed / pure rolling [%]")
    ax.set_title("120-mm-bore turbine bearing, 22 240 N thrust (representative geometry)", fontsize=9)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out / "external_nasa_skid.png", dpi=130)
    plt.close(fig)


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=Path("docs/validation"))
    parser.add_argument("--data", type=Path, default=Path("benchmarks/data"))
    parser.add_argument("--runs", type=Path, default=Path("runs/external_comparisons"))
    parser.add_argument("--reuse", action="store_true")
    args = parser.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)
    masta = masta_comparison()
    nasa = nasa_comparison(args.runs, args.reuse)
    figures(args.out, masta, nasa)
    args.data.mkdir(parents=True, exist_ok=True)
    (args.data / "external_comparisons.json").write_text(json.dumps({"masta": masta, "nasa": nasa}, indent=1) + "\n",
                                                       encoding="utf-8")
    for r in masta:
        print(f"{r['case']:<22}{r['quantity']:<24}{r['masta']:>10.4f}{r['bearingsim']:>10.4f}{100 * r['difference']:>+9.3f} %")
    for r in nasa:
        print(f"{r['inner_rpm']:>8.0f} rpm  cage {r['cage_speed']:.1f} rad/s  pure rolling {r['pure_rolling_nominal']:.1f} "
              f"(20°) / {r['pure_rolling_operating']:.1f} (operating {r['contact_angle_inner_deg']:.1f}°/"
              f"{r['contact_angle_outer_deg']:.1f}°)  skid {100 * r['skid_nominal']:+.2f} % / {100 * r['skid_operating']:+.2f} %")


if __name__ == "__main__":
    main()
