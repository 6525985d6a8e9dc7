"""The burn zone as one polar picture, centred on the hot sector (docs/model.md §11).

The guiding land seen along the bearing's axis: each sector's heat [J] as a bar at its
azimuth (metal friction over film shear), the arc holding 80 % of the heat as a shaded
wedge, the peak sector as a line. The hot sector points up, so the arc is drawn whole
wherever it lies: an arc across 0°/360° (e.g. 291–37°) is never split at the plot's edge.
Plain arrays in; the land's name comes from the caller (the cage's guiding ring), and a
ball-guided cage, which rubs no land, gets a picture that says so.
"""

from __future__ import annotations

import math

import numpy as np

from . import new_figure


def burn_zone_polar_figure(sector_energy: np.ndarray, metal: np.ndarray | None = None,
                           film: np.ndarray | None = None, arc: tuple[float, float] | None = None,
                           land: str | None = "outer-race land", title: str = ""):
    """Polar bars of the heat per land sector [J] (`sector_energy`, sector k spanning
    [k, k+1) 2π/S from +x towards +y; `metal` and `film` its two layers), the 80 % `arc`
    [start, end] rad shaded, rotated so that the peak sector points up. `land`: the guiding
    land's name ("outer-race land", "inner-ring land"); None for a cage without one (ball
    guided). Returns the Figure."""
    fig = new_figure(figsize=(5.4, 5.6))
    ax = fig.add_subplot(projection="polar")
    energy = np.asarray(sector_energy, dtype=float)
    if land is None or energy.size == 0 or float(energy.max(initial=0.0)) <= 0.0:
        ax.set_axis_off()
        why = ("a ball-guided cage rubs no race land: no land burn zone" if land is None
               else f"no heat on the {land} in this window")
        ax.text(0.5, 0.5, why, ha="center", va="center", transform=ax.transAxes, fontsize=10)
        ax.set_title(title, fontsize=10)
        return fig
    S = energy.size
    width = 2 * math.pi / S
    centres = (np.arange(S) + 0.5) * width
    peak = int(np.argmax(energy))
    # the peak sector up: theta on screen = azimuth + offset, counted anticlockwise from east
    ax.set_theta_offset(math.pi / 2 - centres[peak])
    if metal is not None and film is not None:
        ax.bar(centres, film, width=width, color="tab:orange", alpha=0.85, lw=0,
               label=f"film shear {float(np.sum(film)):.3g} J")
        ax.bar(centres, metal, width=width, bottom=film, color="tab:red", alpha=0.9, lw=0,
               label=f"metal friction {float(np.sum(metal)):.3g} J")
    else:
        ax.bar(centres, energy, width=width, color="tab:red", alpha=0.9, lw=0, label="land heat")
    top = float(energy.max()) * 1.15
    if arc is not None:
        a = np.linspace(arc[0], arc[1], max(2, int(math.degrees(arc[1] - arc[0])) + 1))
        ax.fill_between(a, 0.0, top, color="cyan", alpha=0.18, lw=0,
                        label=f"80 % of the heat: {math.degrees(arc[0]) % 360:.0f}–{math.degrees(arc[1]) % 360:.0f}°")
    ax.plot([centres[peak]] * 2, [0.0, top], color="tab:blue", lw=1.2, ls="--",
            label=f"peak sector {math.degrees(centres[peak]):.1f}°")
    ax.set_ylim(0.0, top)
    ax.set_thetagrids(range(0, 360, 30))
    ax.set_rlabel_position(math.degrees(centres[peak]) + 135.0)
    ax.tick_params(axis="y", labelsize=7)
    ax.set_title((title + "\n" if title else "") + f"burn zone: heat per {360 / S:g}° sector of the {land} [J]",
                 fontsize=9)
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.04), fontsize=7, ncols=2, frameon=False)
    return fig
