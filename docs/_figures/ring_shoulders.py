"""Draw docs/images/ring_shoulders.png: which side of each ring carries which thrust, and how a
shoulder pair [side toward +z, side toward -z] is read (docs/scene-guide.md, *Ring shoulders*).

Run from the repository root: `python docs/_figures/ring_shoulders.py`. The section is the
built-in scene acbb-7210-inner-guided's, drawn to scale in the (z, r) half plane."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

import bearingsim

OUT = Path(__file__).resolve().parents[1] / "images" / "ring_shoulders.png"


def _groove(centre_z, centre_r, radius, a_from, a_to, sign):
    """Points of a groove arc: r = centre_r + sign * radius cos(a), z = centre_z + sign * radius sin(a)."""
    a = np.linspace(a_from, a_to, 60)
    return centre_z + sign * radius * np.sin(a), centre_r + sign * radius * np.cos(a)


def _edge(radius, centre_r, land_r, sign):
    return math.acos(max(-1.0, min(1.0, sign * (land_r - centre_r) / radius)))


def main() -> None:
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    scene = bearingsim.load_scene("acbb-7210-inner-guided")
    b = scene.nominal.bearing
    mm = 1e3
    half = 0.5 * b.width * mm
    fig = Figure(figsize=(8.2, 5.6), layout="constrained")
    FigureCanvasAgg(fig)
    ax = fig.subplots()
    alpha = b.free_contact_angle
    # rings in their own frames, groove planes at z = 0; the ball where a +z thrust puts it
    rci, ri = 0.5 * b.inner_groove_center_diameter * mm, b.inner_groove_radius * mm
    rco, ro = 0.5 * b.outer_groove_center_diameter * mm, b.outer_groove_radius * mm
    for ring, centre, radius, sign, rim in (("inner", rci, ri, -1.0, 0.5 * b.inner_bore_diameter * mm),
                                           ("outer", rco, ro, 1.0, 0.5 * b.outer_outside_diameter * mm)):
        up, down = (0.5 * d * mm for d in b.shoulders(ring))
        a_up, a_down = _edge(radius, centre, up, sign), _edge(radius, centre, down, sign)
        # the groove from the -z land to the +z land (z = sign * r sin a: the inner ring's arc runs backwards)
        lo, hi = (-a_down, a_up) if sign > 0 else (-a_up, a_down)
        z, r = _groove(0.0, centre, radius, lo, hi, sign)
        order = np.argsort(z)
        z, r = z[order], r[order]
        outline_z = np.r_[-half, -half, z[0], z, z[-1], half, half]
        outline_r = np.r_[rim, down, down, r, up, up, rim]
        ax.fill(outline_z, outline_r, color="#c8d3e0", ec="k", lw=1.0)
        for side, land, z_text in ((1, up, 0.5 * (z[-1] + half)), (-1, down, 0.5 * (z[0] - half))):
            high = land == (min(up, down) if ring == "outer" else max(up, down))
            ax.annotate(f"{ring} shoulder, side toward {'+z' if side > 0 else '−z'}\n"
                        f"{2 * land:.1f} mm ({'high' if high else 'low'})",
                        (z_text, land), xytext=(z_text, 20.5 if ring == "inner" else 47.0),
                        ha="center", fontsize=8, arrowprops={"arrowstyle": "-", "lw": 0.6})
    # the ball on the contact line at alpha: the inner contact on the -z side, the outer on the +z side
    rb = 0.5 * b.ball_diameter * mm
    pitch = 0.5 * b.pitch_diameter * mm
    ax.add_patch(__import__("matplotlib.patches", fromlist=["Circle"]).Circle((0.0, pitch), rb, fc="#f2c14e",
                                                                                ec="k", lw=1.0))
    dz, dr = math.sin(alpha), math.cos(alpha)
    ax.plot([-1.15 * rb * dz, 1.15 * rb * dz], [pitch - 1.15 * rb * dr, pitch + 1.15 * rb * dr], "r-", lw=1.6)
    ax.text(-rb - 0.5, pitch + 0.3 * rb, f"contact line,\nα = {math.degrees(alpha):.0f}°", color="r",
            fontsize=8, ha="right")
    ax.annotate("", (half + 7.0, 27.0), (half + 0.5, 27.0), arrowprops={"arrowstyle": "-|>", "lw": 2.0})
    ax.text(half + 0.7, 28.0, "load.axial > 0\non the inner ring", fontsize=8)
    ax.annotate("", (half + 7.0, 37.0), (half + 2.0, 37.0), arrowprops={"arrowstyle": "-|>", "lw": 1.0})
    ax.text(half + 7.3, 36.6, "+z", fontsize=9)
    ax.set_xlim(-half - 6.0, half + 12.0)
    ax.set_ylim(18.0, 51.0)
    ax.set_aspect("equal")
    ax.set_xlabel("axial position z [mm] (the bearing axis, groove planes at 0)")
    ax.set_ylabel("radius r [mm]")
    ax.set_title("acbb-7210-inner-guided: thrust along +z on the inner ring presses the inner ring's side "
                 "toward −z\nand the outer ring's side toward +z (positive contact angles); give each shoulder "
                 "as [side toward +z, side toward −z]", fontsize=9)
    OUT.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(OUT, dpi=110)
    print(OUT)


if __name__ == "__main__":
    main()
