"""What the burn-zone renders show, as plain arrays (no plotting here).

Two layers on the outer race (docs/model.md §8, §6.1, §11), both over the *settled window*
of the run (t >= end of the start-up, `summary.json` `settled_window`; the start-up's metal
energy is reported apart, `summary.json` `startup`):

- **Burn zone = land heat** on the guiding land [J] per angular sector: the cage's
  metal-contact friction energy, E_k = sum over samples of P_f · w (friction power times
  the trapezoidal sample weight) in the sector of the contact azimuth (M.112), *plus* the
  viscous shear energy of the land film, each sample's film power spread round the land
  like the shear of the film torque (M.85): ~1/h(theta) on the converging side of the
  thinnest film, ~h_min/h^2 on the cavitated side (M.114,
  `cage_metrics.film_heat_histogram`). It reuses
  `cage_metrics.land_heat` of the summary, so the map and `summary.json`
  (`burn_zone_sector`, `burn_zone_energy_metal` / `_film` / `_total`) agree by
  construction. Default resolution: 360 sectors (1°). The model gives only the azimuth of
  the heat, not where along the axis it goes, so each sector's energy is spread uniformly
  over the land overlap of the cage (both lands, axial length L = `guide_land_length`);
  the areal density is then E_k / (R_land · Δφ · L).
- **Contact tracks** on the raceway: where the balls run. The ball–outer-race contact
  lies on the line from the groove curvature centre through the ball centre, at the
  groove radius r_o from the centre (§6.1): in the ball's azimuth plane it is at radius
  d_o/2 + r_o cos α_o and axial position r_o sin α_o, α_o the outer contact angle (the
  outer race is fixed with its groove plane at z = 0, §1). Each contact is spread across
  the groove over its Hertz ellipse (semi-major axis a along the groove, §6.2), so the
  band shows the running track's width and how much of it rides over the land edge.
  The density is load × time [N·s] per (azimuth, groove-angle) bin: unloaded balls leave
  no track. Default bins: 360 in azimuth × 96 over the raceway profile.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..results.cage_metrics import burn_zone_histogram, burn_zone_sector, land_heat, time_weights

BURN_SECTORS = 360  # 1° sectors, as summary.json
TRACK_AZIMUTH_BINS = 360
TRACK_ANGLE_BINS = 96  # over the whole raceway profile (≈ 1.3° of contact angle each here)


@dataclass(frozen=True)
class OuterRaceProfile:
    """Axial profile of the outer race's bore surface, SI units (m, rad).

    The groove (radius r_o about the curvature-centre circle of radius d_o/2) meets the
    land cylinder (radius R_land) at ±z_land, i.e. at profile angle ±theta_land.
    """

    land_radius: float  # R_land = outer shoulder diameter / 2
    groove_center_radius: float  # d_o / 2
    groove_radius: float  # r_o
    half_width: float  # B / 2
    cage_half_width: float  # w_c / 2: the cage overlaps the lands over z_land < |z| < w_c/2

    @classmethod
    def from_scene(cls, bearing, cage) -> "OuterRaceProfile":
        missing = [k for k in ("outer_shoulder_diameter", "width") if getattr(bearing, k) is None]
        if missing:
            raise ValueError(f"the burn-zone render needs bearing.{missing[0]} [m]; give "
                             + " and ".join(f"bearing.{k}" for k in missing) + " in the scene")
        if cage is not None and cage.guidance != "outer":
            raise ValueError(f"cage.guidance = {cage.guidance!r}: the burn-zone render maps the "
                             "outer race's lands only (an inner-race-guided cage rubs a rotating "
                             "land); set cage.guidance = 'outer' to render it")
        profile = cls(0.5 * bearing.outer_shoulder_diameter, 0.5 * bearing.outer_groove_center_diameter,
                      bearing.outer_groove_radius, 0.5 * bearing.width,
                      0.5 * cage.width if cage is not None else 0.0)
        if not 0.0 < profile.land_radius - profile.groove_center_radius < profile.groove_radius:
            raise ValueError(f"bearing.outer_shoulder_diameter = {bearing.outer_shoulder_diameter:g} m "
                             "does not cut the outer groove: it must lie between d_o and d_o + 2 r_o")
        return profile

    @property
    def theta_land(self) -> float:
        """Profile angle where groove and land meet [rad] (cos = (R_land - d_o/2)/r_o)."""
        return math.acos((self.land_radius - self.groove_center_radius) / self.groove_radius)

    @property
    def z_land(self) -> float:
        """Axial distance of the groove–land edge from the groove plane [m] (≈ 8.90 mm, §2)."""
        return self.groove_radius * math.sin(self.theta_land)

    @property
    def land_overlap(self) -> float:
        """Axial length L of cage–land overlap, both lands together [m] (≈ 7.6 mm, §2)."""
        return max(0.0, 2.0 * (self.cage_half_width - self.z_land))

    def groove_point(self, alpha: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(radius, z) [m] of the groove surface at profile (contact) angle alpha [rad]."""
        return (self.groove_center_radius + self.groove_radius * np.cos(alpha),
                self.groove_radius * np.sin(alpha))


@dataclass(frozen=True)
class BurnZoneMap:
    """Burn-zone energy per land sector and ball-track density on the raceway."""

    profile: OuterRaceProfile
    sector_energy: np.ndarray  # (S,) J per sector, sector k spans [k, k+1) * 2 pi / S
    sector: tuple[float, float] | None  # [start, end] rad of the 80 % arc (summary.json)
    track_density: np.ndarray  # (A, K) N·s per (azimuth, contact-angle) bin
    track_alpha_edges: np.ndarray  # (K + 1,) rad, spanning [-theta_land, theta_land]
    track_outside_fraction: float  # share of load × time whose contact lies beyond a land edge
    metal_energy: np.ndarray | None = None  # (S,) J per sector: metal friction layer of sector_energy
    film_energy: np.ndarray | None = None  # (S,) J per sector: film shear layer of sector_energy
    window: tuple[float, float] | None = None  # [start, end] s of the time the map covers
    startup_metal_energy: float | None = None  # J of metal friction before `window` (not drawn)

    @property
    def sectors(self) -> int:
        return self.sector_energy.size

    @property
    def peak_sector(self) -> int | None:
        """Index of the sector holding most energy (the first of equals), None if no rub."""
        return int(np.argmax(self.sector_energy)) if self.sector_energy.max(initial=0.0) > 0.0 else None

    def sector_center(self, index: int) -> float:
        """Azimuth of a sector's centre [rad]."""
        return (index + 0.5) * 2.0 * math.pi / self.sectors

    @property
    def areal_density_factor(self) -> float:
        """1 / (R_land Δφ L) [1/m²]: J per sector -> J/m² over the land overlap."""
        area = self.profile.land_radius * (2.0 * math.pi / self.sectors) * self.profile.land_overlap
        return 1.0 / area if area > 0.0 else float("nan")


def sector_energy(t: np.ndarray, azimuth: np.ndarray, friction_power: np.ndarray,
                  sectors: int = BURN_SECTORS) -> np.ndarray:
    """E_k [J]: metal-contact friction energy P_f · w per land sector (as cage_summary)."""
    energy = np.asarray(friction_power, dtype=float) * time_weights(t)
    return burn_zone_histogram(np.asarray(azimuth, dtype=float), energy, sectors)


def outer_contact_points(ball_xyz: np.ndarray, outer_angle: np.ndarray,
                         profile: OuterRaceProfile) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(azimuth [rad] in [0, 2 pi), radius [m], z [m]) of each ball–outer-race contact.

    The contact lies in the plane through the axis and the ball centre (§6.1, gamma =
    atan2(Y, X)), at the groove point of profile angle alpha_o.
    """
    xyz = np.asarray(ball_xyz, dtype=float)
    phi = np.mod(np.arctan2(xyz[..., 1], xyz[..., 0]), 2.0 * math.pi)
    radius, z = profile.groove_point(np.asarray(outer_angle, dtype=float))
    return phi, radius, z


def outer_semi_major_axis(bearing, ball, race, outer_angle: np.ndarray, outer_load: np.ndarray) -> np.ndarray:
    """Hertz semi-major axis a = c_a(alpha) Q^{1/3} [m] of the ball–outer contacts, along
    the groove (§6.2, exact constants tabulated in alpha by `dynamics.contact.hertz`)."""
    from ...dynamics.geometry import effective_modulus
    from ...dynamics.contact.hertz import race_hertz_table, semi_axis_coefficients

    table = race_hertz_table(bearing, effective_modulus(ball, race), outer=True)
    c_a, _ = semi_axis_coefficients(table, np.ascontiguousarray(outer_angle, dtype=float))
    return c_a * np.cbrt(np.clip(np.asarray(outer_load, dtype=float), 0.0, None))


def _band_cdf(u: np.ndarray) -> np.ndarray:
    """Share of a Hertz ellipse's load below u = s/a across it: the line load across the
    ellipse (pressure integrated along the rolling direction) is (3/4)(1 - u^2)."""
    u = np.clip(u, -1.0, 1.0)
    # u * u * u, not u**3: NumPy's power has fast paths for squares and roots only, and the
    # generic one made this the largest cost of the report
    return 0.25 * (2.0 + 3.0 * u - u * u * u)


def contact_track_density(t: np.ndarray, ball_xyz: np.ndarray, outer_angle: np.ndarray,
                          outer_load: np.ndarray, profile: OuterRaceProfile,
                          semi_axis: np.ndarray | None = None,
                          azimuth_bins: int = TRACK_AZIMUTH_BINS,
                          angle_bins: int = TRACK_ANGLE_BINS,
                          chunk: int = 65536) -> tuple[np.ndarray, np.ndarray, float]:
    """Load × time [N·s] of ball–outer contacts per (azimuth, groove-angle) bin.

    Each contact's load × time is spread across the groove over its Hertz ellipse, the
    profile angles alpha_o ± a/r_o (a = `semi_axis` [m], along the groove), with the
    ellipse's line-load share per bin; without `semi_axis` each contact is a point.
    Returns (density (azimuth_bins, angle_bins), angle edges [rad] over the raceway
    [-theta_land, theta_land], share of load × time lying beyond a land edge: the
    truncated part of the ellipse, not drawn).
    """
    phi, _, _ = outer_contact_points(ball_xyz, outer_angle, profile)
    weight = np.clip(np.asarray(outer_load, dtype=float), 0.0, None) * time_weights(t)[:, None]
    loaded = weight > 0.0
    phi, w = phi[loaded], weight[loaded]
    alpha = np.asarray(outer_angle, dtype=float)[loaded]
    half = (np.zeros_like(alpha) if semi_axis is None
            else np.asarray(semi_axis, dtype=float)[loaded] / profile.groove_radius)
    half = np.maximum(half, 1e-12)  # a point contact: a step of the cumulative share
    edges = np.linspace(-profile.theta_land, profile.theta_land, angle_bins + 1)
    step = edges[1] - edges[0]
    # each contact touches only the W bins its ellipse spans: evaluate the share there
    width = int(math.ceil(2.0 * float(half.max(initial=0.0)) / step)) + 2
    first = np.floor((alpha - half - edges[0]) / step).astype(int)
    i = np.clip((phi / (2.0 * math.pi) * azimuth_bins).astype(int), 0, azimuth_bins - 1)
    density = np.zeros(azimuth_bins * angle_bins)
    drawn = 0.0
    for s in range(0, alpha.size, chunk):
        sl = slice(s, s + chunk)
        k = first[sl, None] + np.arange(width + 1)[None, :]  # edge indices of the window
        cdf = _band_cdf((edges[0] + k * step - alpha[sl, None]) / half[sl, None])
        share = np.diff(cdf, axis=1) * w[sl, None]  # bin k[:, j] holds share[:, j]
        inside = (k[:, :-1] >= 0) & (k[:, :-1] < angle_bins)
        index = i[sl, None] * angle_bins + k[:, :-1]
        density += np.bincount(index[inside], weights=share[inside], minlength=density.size)
        drawn += float(share[inside].sum())
    total = float(w.sum())
    outside = 1.0 - drawn / total if total > 0.0 else 0.0
    outside = outside if outside > 1e-9 else 0.0  # round-off of the shares is not truncation
    return density.reshape(azimuth_bins, angle_bins), edges, outside


def burn_zone_map(series: dict, profile: OuterRaceProfile, sectors: int = BURN_SECTORS,
                  summary_sector: list | None = None, semi_axis: np.ndarray | None = None, *,
                  start: float | None = None, land_boundary: float = 0.05, land_speed: float = 0.0,
                  startup_metal_energy: float | None = None) -> BurnZoneMap:
    """Both layers from the saved time series (`read_timeseries` names, see
    `pipeline/results/simulation_output.py`) over t >= `start` (None: the whole run). The
    land heat is metal friction plus film shear (`cage_metrics.land_heat`, `land_boundary`
    eps0 of the hybrid law, the film dragged towards sign(cage speed + `land_speed`); without
    `cage/speed` the film heat is spread as a full film); a series without
    `cage_race/film_power` gives metal only. The
    80 % arc is `summary_sector` (from `summary.json`) when given, else recomputed the same
    way. A run without a cage has no burn zone (all-zero sectors) but still has contact
    tracks."""
    t = np.asarray(series["time"].data, dtype=float)
    start = float(t[0]) if start is None else float(start)
    if "cage_race/friction_power" in series:
        eps = (series["cage_race/eccentricity_ratio"].data if "cage_race/eccentricity_ratio" in series
               else np.zeros_like(t))
        film = series["cage_race/film_power"].data if "cage_race/film_power" in series else None
        drag = (np.sign(np.asarray(series["cage/speed"].data, dtype=float) + land_speed)
                if "cage/speed" in series else 0.0)
        metal, film_heat = land_heat(t, series["cage_race/contact_azimuth"].data, eps,
                                     series["cage_race/friction_power"].data, film, land_boundary, start,
                                     sectors, drag=drag)
    else:
        metal, film_heat = np.zeros(sectors), np.zeros(sectors)
    energy = metal + film_heat
    late = t >= start
    ball_xyz = np.asarray(series["balls/position"].data)[late]
    angle = np.asarray(series["contacts/outer_contact_angle"].data)[late]
    load = np.asarray(series["contacts/outer_load"].data)[late]
    axis = None if semi_axis is None else np.asarray(semi_axis)[late]
    density, edges, outside = contact_track_density(t[late], ball_xyz, angle, load, profile, axis)
    sector = tuple(summary_sector) if summary_sector is not None else burn_zone_sector(energy)
    return BurnZoneMap(profile, energy, sector, density, edges, outside, metal, film_heat,
                       (start, float(t[-1])), startup_metal_energy)
