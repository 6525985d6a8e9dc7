"""Summary metrics of a dynamic run (SCENE.md `summary.json`), from saved time series.

Conventions (documented in the README):
- Time averages (cage speed, variation, metal-contact fraction, contact spread, whirl ratio,
  inner-race axial mean) are taken over the *analysis window*, the last half of the run,
  where the start-up transient from the quasi-static state has died out.
- Accumulated quantities (pocket impacts, burn-zone energy) use the whole run.
- Azimuths are measured in the global frame from +x towards +y (MODEL.md §1).
"""

from __future__ import annotations

import math

import numpy as np


def time_weights(t: np.ndarray) -> np.ndarray:
    """Trapezoidal quadrature weights of samples at times `t` (sum = t[-1] - t[0])."""
    t = np.asarray(t, dtype=float)
    if t.size < 2:
        return np.ones_like(t)
    w = np.zeros_like(t)
    dt = np.diff(t)
    w[:-1] += 0.5 * dt
    w[1:] += 0.5 * dt
    return w


def analysis_window(t: np.ndarray) -> np.ndarray:
    """Boolean mask of the last half of the run."""
    t = np.asarray(t, dtype=float)
    return t >= t[0] + 0.5 * (t[-1] - t[0])


def circular_spread(angles: np.ndarray, weights: np.ndarray | None = None) -> float:
    """Circular standard deviation sqrt(-2 ln R) [rad] (Mardia & Jupp, Directional
    Statistics, 2000, §2.3.4); 0 for identical angles, NaN when there are none."""
    angles = np.asarray(angles, dtype=float)
    if angles.size == 0:
        return float("nan")
    w = np.ones_like(angles) if weights is None else np.asarray(weights, dtype=float)
    if w.sum() <= 0.0:
        return float("nan")
    c = np.sum(w * np.cos(angles)) / w.sum()
    s = np.sum(w * np.sin(angles)) / w.sum()
    r = min(1.0, math.hypot(c, s))
    return math.sqrt(-2.0 * math.log(r)) if r > 0.0 else float("inf")


def whirl_ratio(t: np.ndarray, x: np.ndarray, y: np.ndarray, cage_speed: np.ndarray) -> float:
    """Mean whirl speed of the cage centre (d/dt of its unwrapped azimuth) over the mean
    cage spin speed. +1: the centre orbits once per cage turn in the sense of rotation."""
    t = np.asarray(t, dtype=float)
    if t.size < 2 or t[-1] <= t[0]:
        return float("nan")
    phase = np.unwrap(np.arctan2(y, x))
    whirl = (phase[-1] - phase[0]) / (t[-1] - t[0])
    spin = float(np.sum(time_weights(t) * cage_speed) / (t[-1] - t[0]))
    return whirl / spin if spin != 0.0 else float("nan")


def burn_zone_histogram(azimuth: np.ndarray, energy: np.ndarray, sectors: int = 360) -> np.ndarray:
    """Metal-contact energy [J] accumulated per angular sector of the guide land.

    `azimuth` [rad] is the contact direction at each sample, `energy` [J] the friction
    energy dissipated during that sample (friction power x sample weight).
    """
    edges_index = np.floor((np.mod(azimuth, 2.0 * math.pi)) / (2.0 * math.pi) * sectors).astype(int)
    edges_index = np.clip(edges_index, 0, sectors - 1)
    return np.bincount(edges_index, weights=np.asarray(energy, dtype=float), minlength=sectors)


def burn_zone_sector(hist: np.ndarray, share: float = 0.8) -> tuple[float, float] | None:
    """Shortest circular arc of sectors holding `share` of the energy, as [start, end]
    azimuths in rad (start in [0, 2 pi), end = start + width). None without metal contact."""
    total = float(np.sum(hist))
    if total <= 0.0:
        return None
    n = hist.size
    doubled = np.concatenate([hist, hist])
    cumulative = np.concatenate([[0.0], np.cumsum(doubled)])
    target = share * total
    best = (n + 1, 0)
    for start in range(n):
        # smallest width w with sum(hist[start:start+w]) >= target
        w = int(np.searchsorted(cumulative[start + 1: start + n + 1] - cumulative[start],
                                target * (1.0 - 1e-12))) + 1
        if w < best[0]:
            best = (w, start)
    width, start = best
    sector = 2.0 * math.pi / n
    return start * sector, (start + width) * sector


def cage_summary(
    t: np.ndarray,
    cage_xy: np.ndarray,
    cage_speed: np.ndarray,
    eccentricity_ratio: np.ndarray,
    contact_azimuth: np.ndarray,
    friction_power: np.ndarray,
    inner_race_z: np.ndarray,
    impact_peak_forces: np.ndarray,
    sectors: int = 360,
) -> dict:
    """The cage and impact keys of SCENE.md `summary.json` (see module docstring)."""
    t = np.asarray(t, dtype=float)
    win = analysis_window(t)
    tw = t[win]
    w = time_weights(tw)
    span = max(tw[-1] - tw[0], 1e-300)
    speed = np.asarray(cage_speed, dtype=float)[win]
    mean_speed = float(np.sum(w * speed) / span)
    metal = np.asarray(eccentricity_ratio, dtype=float)[win] > 1.0
    azim = np.asarray(contact_azimuth, dtype=float)[win]
    energy = np.asarray(friction_power, dtype=float) * time_weights(t)
    hist = burn_zone_histogram(contact_azimuth, energy, sectors)
    sector = burn_zone_sector(hist)
    peaks = np.asarray(impact_peak_forces, dtype=float)
    return {
        "cage_speed_mean": mean_speed,
        "cage_speed_variation": float((speed.max() - speed.min()) / mean_speed) if mean_speed else float("nan"),
        "cage_metal_contact_fraction": float(np.sum(w * metal) / span),
        "cage_contact_angle_spread": circular_spread(azim[metal], w[metal]) if metal.any() else None,
        "cage_whirl_ratio": whirl_ratio(tw, cage_xy[win, 0], cage_xy[win, 1], speed),
        "inner_race_axial_mean": float(np.sum(w * np.asarray(inner_race_z)[win]) / span),
        "pocket_impacts": int(peaks.size),
        "pocket_impact_force_p95": float(np.percentile(peaks, 95)) if peaks.size else 0.0,
        "burn_zone_sector": list(sector) if sector is not None else None,
        "burn_zone_energy_total": float(np.sum(hist)),
    }
