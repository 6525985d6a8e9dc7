"""Figure: ball load and contact angle against ball azimuth (docs/model.md §11)."""

from __future__ import annotations

import math
from pathlib import Path



def plot_load_distribution(result: dict, path: Path, title: str = "") -> None:
    """`load_distribution_figure` as a PNG (the quasistatic stage's load_distribution.png)."""
    from . import save_png

    save_png(load_distribution_figure(result, title), Path(path), dpi=120)


def load_distribution_figure(result: dict, title: str = ""):
    """Two panels sharing the azimuth axis: contact loads [N], contact angles [deg] (and the
    crush screen when `result` has one). Returns the Figure."""
    from . import new_figure

    balls = result["balls"]
    az = [math.degrees(b["azimuth"]) % 360.0 for b in balls]
    order = sorted(range(len(az)), key=az.__getitem__)
    az = [az[i] for i in order]
    pick = lambda key, scale=1.0: [balls[i][key] * scale for i in order]  # noqa: E731
    screen = result.get("cage_screen")
    fig = new_figure(figsize=(7.5, 8.6 if screen else 6.0))
    axes = fig.subplots(3 if screen else 2, 1, sharex=True)
    ax_q, ax_a = axes[0], axes[1]
    ax_q.plot(az, pick("inner_load"), "o-", label="inner race")
    ax_q.plot(az, pick("outer_load"), "s--", label="outer race")
    ax_q.set_ylabel("contact load Q [N]")
    ax_q.legend()
    ax_q.grid(alpha=0.3)
    deg = 180.0 / math.pi
    ax_a.plot(az, pick("inner_contact_angle", deg), "o-", label="inner race")
    ax_a.plot(az, pick("outer_contact_angle", deg), "s--", label="outer race")
    ax_a.set_xlabel("" if screen else "ball azimuth ψ [deg] (from +x towards +y)")
    ax_a.set_ylabel("contact angle α [deg]")
    ax_a.set_xlim(0, 360)
    ax_a.set_xticks(range(0, 361, 45))
    ax_a.legend()
    ax_a.grid(alpha=0.3)
    if screen:
        _plot_excursion(axes[2], az, [screen["excursion_per_ball"][i] for i in order], screen)
    fig.suptitle(f"Quasi-static load distribution — {title}" if title else "Quasi-static load distribution")
    return fig


def ball_load_polar_figure(result: dict, title: str = ""):
    """The ball loads round the bearing, seen along the axis: each ball's inner- and
    outer-race contact load [N] as a radius at its azimuth (from +x towards +y), so the loaded
    zone of the moment reads at a glance. Returns the Figure."""
    import numpy as np

    from . import new_figure

    balls = result["balls"]
    az = np.array([b["azimuth"] for b in balls], dtype=float) % (2 * math.pi)
    order = np.argsort(az)
    az = az[order]
    fig = new_figure(figsize=(5.2, 5.2))
    ax = fig.add_subplot(projection="polar")
    closed = np.r_[az, az[0] + 2 * math.pi]
    for key, style, label in (("inner_load", "o-", "inner race"), ("outer_load", "s--", "outer race")):
        q = np.array([balls[i][key] for i in order], dtype=float)
        ax.plot(closed, np.r_[q, q[0]], style, ms=4, lw=1, label=label)
    heaviest = max(balls, key=lambda b: b["inner_load"])
    ax.set_title(f"Ball loads [N] round the bearing{' — ' + title if title else ''}\n"
                 f"heaviest {heaviest['inner_load']:.0f} N at {math.degrees(heaviest['azimuth']) % 360:.0f}°", fontsize=9)
    ax.set_theta_zero_location("E")  # azimuth 0 along +x, counted towards +y
    ax.set_rlabel_position(112.5)
    ax.legend(loc="lower left", bbox_to_anchor=(-0.12, -0.12), fontsize=8, frameon=False)
    return fig


def _plot_excursion(ax, az, s, screen: dict) -> None:
    """The crush screen (docs/model.md §10.1): each ball's lead over a rigid centred cage
    against the pocket walls, and where the cage must move to make room."""
    um = 1e3  # mm
    half = 0.5 * screen["pocket_clearance"] * um
    ax.plot(az, [x * um for x in s], "o-", color="k", label="ball lead over a centred cage")
    ax.axhspan(half, max(half, max(s) * um) + 0.05, color="#f9dcdc", lw=0)
    ax.axhspan(min(-half, min(s) * um) - 0.05, -half, color="#f9dcdc", lw=0)
    ax.axhline(half, color="r", lw=0.8, label="pocket walls, cage centred (±c_p/2)")
    ax.axhline(-half, color="r", lw=0.8)
    ax.set_ylabel("lead in pocket [mm]")
    ax.set_xlabel("ball azimuth ψ [deg] (from +x towards +y)")
    ax.grid(alpha=0.3)
    ax.set_title(f"crush screen: {screen['regime']} (push towards {round(screen['push_azimuth_deg']) % 360}°, "
                 f"required offset {screen['required_eccentricity_ratio']:.2f} C)", fontsize=9)
    # outside the axes: the curve reaches the walls, where a legend inside would hide it
    ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(0.0, -0.22), ncols=2, frameon=False)
