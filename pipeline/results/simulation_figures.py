"""The figures of a dynamic run (docs/model.md §11) from its saved series."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..figures import dynamics as fig

FIGURES = ("cage_orbit.png", "cage_speed.png", "phase_portraits.png", "cage_race_force.png",
           "pocket_impacts.png")


def draw_simulation_figures(out_dir: Path, series: dict, run, params, start, title: str,
                            settled_from: float | None = None) -> list[str]:
    """The PNGs of FIGURES; `settled_from` [s]: start of the verdict's settled window, which
    the figures mark as the verdict does (start-up / settled)."""
    t = series["time"].data
    written = []
    positions = {"inner race": series["inner_race/position"].data - series["inner_race/position"].data[0]}
    velocities = {"inner race": series["inner_race/velocity"].data}
    if params.has_cage:
        xy = series["cage/position"].data[:, :2]
        fig.cage_orbit(xy, params.guide_clearance, out_dir / FIGURES[0], title, t=t, settled_from=settled_from)
        fig.cage_speed(t, series["cage/speed"].data, out_dir / FIGURES[1],
                       kinematic=float(start["cage_angular_speed"]), title=title, settled_from=settled_from)
        positions["cage"] = series["cage/position"].data
        velocities["cage"] = series["cage/velocity"].data
        force = np.linalg.norm(series["cage_race/force"].data, axis=1)
        fig.cage_race_force(t, force, series["cage_race/metal_force"].data,
                            series["cage_race/eccentricity_ratio"].data, out_dir / FIGURES[3], title)
        imp = run.impacts
        fig.pocket_impacts(imp[:, 0] if len(imp) else [], imp[:, 2] if len(imp) else [],
                           imp[:, 3] if len(imp) else [], out_dir / FIGURES[4], title, settled_from=settled_from)
        written += [FIGURES[0], FIGURES[1], FIGURES[3], FIGURES[4]]
    fig.phase_portraits(t, positions, velocities, out_dir / FIGURES[2], title)
    written.append(FIGURES[2])
    return written
