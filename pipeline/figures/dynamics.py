"""Figures of a dynamic run (docs/model.md §11), drawn from saved time series only.

Each `*_figure` function takes plain arrays and returns a matplotlib Figure (what `run.plot`
gives and the report embeds); the function of the same name without `_figure` writes it as
one PNG atomically (matplotlib, Agg).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from . import new_figure, save_png


def _subplots(nrows=1, ncols=1, figsize=(8, 4), **kw):
    fig = new_figure(figsize=figsize)
    return fig, fig.subplots(nrows, ncols, **kw)


def _save(fig, path: Path) -> None:
    save_png(fig, Path(path))


def _settled(t, settled_from: float | None) -> np.ndarray:
    """Samples of the settled window (t >= its start; the whole run without one)."""
    t = np.asarray(t, dtype=float)
    return t >= (settled_from if settled_from is not None else -np.inf)


def _startup_label(settled_from: float | None) -> str:
    return f"start-up (t < {settled_from:.3g} s)" if settled_from is not None else "start-up"


def cage_orbit_figure(xy: np.ndarray, clearance: float | None, title: str = "", t=None,
                      settled_from: float | None = None, film_factor: float | None = None,
                      sector_deg: list[float] | None = None, thinnest: tuple | None = None):
    """Cage-centre orbit [µm] inside the guide clearance C (ε = 1, metal contact begins) and,
    with `film_factor` = 1 + ε0, the film clearance; the start-up grey, the settled window
    (from `settled_from` [s], the verdict's) coloured, the loaded sector (`sector_deg`) as a
    wedge and the thinnest film (`thinnest` = (index, label)) as a star. Returns the Figure."""
    fig, ax = _subplots(figsize=(6.2, 6.0))
    xy = np.asarray(xy, dtype=float)[:, :2] * 1e6
    th = np.linspace(0, 2 * math.pi, 361)
    lim = 1.05 * float(np.abs(xy).max(initial=1.0))
    if clearance:
        c = clearance * 1e6
        ax.plot(c * np.cos(th), c * np.sin(th), "k--", lw=1, label=f"guide clearance C = {c:.0f} µm (ε = 1)")
        lim = max(lim, 1.15 * c)
        if film_factor:
            ax.plot(c * film_factor * np.cos(th), c * film_factor * np.sin(th), "k:", lw=0.8,
                    label=f"film clearance C(1 + ε0), ε0 = {film_factor - 1.0:g}")
            lim = max(lim, 1.15 * c * film_factor)
        if sector_deg:
            a = np.radians(np.linspace(sector_deg[0], sector_deg[1], 60))
            ax.fill(np.r_[0.0, c * np.cos(a), 0.0], np.r_[0.0, c * np.sin(a), 0.0], color="tab:red", alpha=0.15,
                    label=f"loaded sector {sector_deg[0] % 360:.0f}–{sector_deg[1] % 360:.0f}°")
    late = _settled(t if t is not None else np.arange(len(xy)), settled_from)
    if (~late).any():
        ax.plot(xy[~late, 0], xy[~late, 1], color="0.65", lw=0.5, label=_startup_label(settled_from))
    ax.plot(xy[late, 0], xy[late, 1], color="C0", lw=0.6,
            label="settled window" if settled_from is not None else "whole run")
    if thinnest is not None:
        i, label = thinnest
        ax.plot(xy[i, 0], xy[i, 1], "*", color="tab:red", ms=12, label=label)
    ax.set_aspect("equal")
    ax.set_xlim(-lim, lim)
    ax.set_ylim(-lim, lim)
    ax.set_xlabel("cage centre x [µm]")
    ax.set_ylabel("cage centre y [µm]")
    ax.legend(loc="upper right", fontsize=7)
    ax.grid(alpha=0.3)
    ax.set_title(f"Cage centre orbit {title}".strip(), fontsize=10)
    return fig


def cage_orbit(xy: np.ndarray, clearance: float, path: Path, title: str = "", t=None,
               settled_from: float | None = None) -> None:
    """`cage_orbit_figure` as a PNG."""
    _save(cage_orbit_figure(xy, clearance, title, t=t, settled_from=settled_from), path)


def cage_speed_figure(t: np.ndarray, speed: np.ndarray, kinematic: float | None = None, title: str = "",
                      settled_from: float | None = None):
    """Cage rotation speed [rev/min] with its mean and relative variation over the settled
    window (the verdict's; the last half of the run without one). Returns the Figure."""
    t = np.asarray(t, dtype=float)
    rpm = np.asarray(speed, dtype=float) * 60.0 / (2 * math.pi)
    late = _settled(t, settled_from if settled_from is not None else t[0] + 0.5 * (t[-1] - t[0]))
    window = "settled" if settled_from is not None else "last half"
    mean = rpm[late].mean()
    var = (rpm[late].max() - rpm[late].min()) / mean if mean else float("nan")
    fig, ax = _subplots(figsize=(8, 4))
    ax.plot(t, rpm, lw=0.7, label="cage speed")
    ax.axhline(mean, color="C1", lw=1, label=f"mean ({window}) {mean:.1f} rev/min, variation {100 * var:.2f} % p-p")
    if settled_from is not None:
        ax.axvline(settled_from, color="0.5", ls="--", lw=0.8, label=f"settled from {settled_from:.3g} s")
    if kinematic is not None:
        ax.axhline(kinematic * 60 / (2 * math.pi), color="k", ls=":", lw=1, label="epicyclic (pure rolling)")
    ax.set_xlabel("time [s]")
    ax.set_ylabel("cage speed [rev/min]")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    ax.set_title(f"Cage speed {title}".strip())
    return fig


def cage_speed(t: np.ndarray, speed: np.ndarray, path: Path, kinematic: float | None = None,
               title: str = "", settled_from: float | None = None) -> None:
    """`cage_speed_figure` as a PNG."""
    _save(cage_speed_figure(t, speed, kinematic, title, settled_from), path)


def phase_portraits(t, positions: dict[str, np.ndarray], velocities: dict[str, np.ndarray],
                    path: Path, title: str = "") -> None:
    """Phase portraits (x, y, z) of each body: position [µm] vs velocity [mm/s]."""
    names = list(positions)
    fig, axes = _subplots(len(names), 3, figsize=(11, 3.3 * len(names)),
                             squeeze=False)
    for row, name in enumerate(names):
        for col, axis in enumerate("xyz"):
            ax = axes[row, col]
            ax.plot(positions[name][:, col] * 1e6, velocities[name][:, col] * 1e3, lw=0.4)
            ax.set_xlabel(f"{axis} [µm]")
            ax.set_ylabel(f"d{axis}/dt [mm/s]")
            ax.set_title(f"{name}: {axis}", fontsize=9)
            ax.grid(alpha=0.3)
    fig.suptitle(f"Phase portraits {title}")
    _save(fig, path)


def cage_race_force(t, force_norm, metal_force, eps, path: Path, title: str = "") -> None:
    """Cage–guiding-race force [N] and eccentricity ratio against time."""
    fig, (a1, a2) = _subplots(2, 1, sharex=True, figsize=(8, 5.5))
    a1.plot(t, force_norm, lw=0.6, label="total |F|")
    a1.plot(t, metal_force, lw=0.6, label="metal-to-metal normal force")
    a1.set_ylabel("force [N]")
    a1.legend(fontsize=8)
    a1.grid(alpha=0.3)
    a2.plot(t, eps, lw=0.6)
    a2.axhline(1.0, color="k", ls="--", lw=0.8)
    a2.set_ylabel("eccentricity ratio ε")
    a2.set_xlabel("time [s]")
    a2.grid(alpha=0.3)
    fig.suptitle(f"Cage–race contact {title}")
    _save(fig, path)


def pocket_impacts_figure(times, orbital_position, peak_force, title: str = "",
                          settled_from: float | None = None):
    """Ball–pocket impacts: peak force against time and against orbital position [deg,
    0–360], start-up and settled window apart (the verdict counts the settled ones). Returns
    the Figure."""
    times, peak_force = np.asarray(times, dtype=float), np.asarray(peak_force, dtype=float)
    position = np.degrees(np.mod(np.asarray(orbital_position, dtype=float), 2 * math.pi))
    late = _settled(times, settled_from)
    fig, (a1, a2) = _subplots(1, 2, figsize=(11, 4))
    if len(times):
        for part, colour, label in ((~late, "0.6", _startup_label(settled_from)),
                                    (late, "C0", "settled window" if settled_from is not None else "whole run")):
            if part.any():
                a1.scatter(times[part], peak_force[part], s=4, color=colour, label=f"{label}: {part.sum()}")
                a2.scatter(position[part], peak_force[part], s=4, color=colour)
        a1.legend(fontsize=8)
    else:
        for ax in (a1, a2):
            ax.text(0.5, 0.5, "no impacts", ha="center", va="center", transform=ax.transAxes)
    a1.set_xlabel("time [s]")
    a2.set_xlabel("orbital position of the ball [deg]")
    a2.set_xlim(0, 360)
    a2.set_xticks(range(0, 361, 45))
    for ax in (a1, a2):
        ax.set_ylabel("impact peak force [N]")
        ax.grid(alpha=0.3)
    count = (f"{int(late.sum())} settled + {int((~late).sum())} start-up" if settled_from is not None
             else f"{len(times)}")
    fig.suptitle(f"Ball–pocket impacts ({count}) {title}".strip())
    return fig


def pocket_impacts(times, orbital_position, peak_force, path: Path, title: str = "",
                   settled_from: float | None = None) -> None:
    """`pocket_impacts_figure` as a PNG."""
    _save(pocket_impacts_figure(times, orbital_position, peak_force, title, settled_from), path)
