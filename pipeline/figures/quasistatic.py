"""Figure: ball load and contact angle against ball azimuth (MODEL.md §11)."""

from __future__ import annotations

import math
from pathlib import Path



def plot_load_distribution(result: dict, path: Path, title: str = "") -> None:
    """Two panels sharing the azimuth axis: contact loads [N], contact angles [deg]."""
    from . import new_figure, save_png

    balls = result["balls"]
    az = [math.degrees(b["azimuth"]) % 360.0 for b in balls]
    order = sorted(range(len(az)), key=az.__getitem__)
    az = [az[i] for i in order]
    pick = lambda key, scale=1.0: [balls[i][key] * scale for i in order]  # noqa: E731
    fig = new_figure(figsize=(7.5, 6.0))
    ax_q, ax_a = fig.subplots(2, 1, sharex=True)
    ax_q.plot(az, pick("inner_load"), "o-", label="inner race")
    ax_q.plot(az, pick("outer_load"), "s--", label="outer race")
    ax_q.set_ylabel("contact load Q [N]")
    ax_q.legend()
    ax_q.grid(alpha=0.3)
    deg = 180.0 / math.pi
    ax_a.plot(az, pick("inner_contact_angle", deg), "o-", label="inner race")
    ax_a.plot(az, pick("outer_contact_angle", deg), "s--", label="outer race")
    ax_a.set_xlabel("ball azimuth ψ [deg] (from +x towards +y)")
    ax_a.set_ylabel("contact angle α [deg]")
    ax_a.set_xlim(0, 360)
    ax_a.set_xticks(range(0, 361, 45))
    ax_a.legend()
    ax_a.grid(alpha=0.3)
    fig.suptitle(f"Quasi-static load distribution — {title}" if title else "Quasi-static load distribution")
    save_png(fig, Path(path), dpi=120)
