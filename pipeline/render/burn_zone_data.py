"""What the burn-zone renders show, as plain arrays (no plotting here).

Two layers on the race whose land guides the cage — the outer ring, or the inner ring in the
frame that turns with it — (docs/model.md §8, §6.1, §11), both over the *settled window*
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
  over the land overlap of the cage (the guiding lands, axial length L = `guide_land_length`);
  the areal density is then E_k / (R_land · Δφ · L). The inner ring's land turns with it,
  so its map is in the ring's frame: the contact azimuth less the angle the ring has turned
  (`inner_race/angle`).
- **Contact tracks** on the raceway: where the balls run. A ball–race contact lies on the
  line from the groove curvature centre through the ball centre, at the groove radius r from
  the centre (§6.1): in the ball's azimuth plane the outer one is at radius d_o/2 + r_o cos α_o
  and axial position r_o sin α_o, the inner one at d_i/2 - r_i cos α_i and -r_i sin α_i (the
  groove planes at z = 0 in each ring's frame, §1). Each contact is spread across
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
class RaceProfile:
    """Axial profile of the guiding race's land surface, SI units (m, rad): the outer ring's
    bore (`ring` "outer") or the inner ring's outside ("inner").

    The groove (radius r about the curvature-centre circle of radius d/2) meets each land
    cylinder at axial distance z_land from the groove plane, one value a side (`z_lands`:
    toward +z, toward -z); `land_sides` are the sides whose land guides the cage (+1, -1).
    """

    ring: str  # "outer" | "inner"
    land_radius: float  # R_land: the guiding land's diameter / 2
    groove_center_radius: float  # d / 2
    groove_radius: float  # r
    half_width: float  # B / 2
    cage_half_width: float  # w_c / 2: the cage overlaps a guiding land over z_land < |z| < w_c/2
    z_lands: tuple[float, float]  # (side toward +z, side toward -z) [m]
    land_sides: tuple[int, ...] = (1, -1)
    land_radii: tuple[float, float] | None = None  # (side toward +z, toward -z) [m]; None: land_radius both

    @classmethod
    def from_scene(cls, bearing, cage) -> "RaceProfile":
        ring = cage.guide_ring if cage is not None else "outer"
        if ring is None:
            raise ValueError("cage.guidance = 'ball': a ball-guided cage runs on no land, so it has no burn zone")
        missing = [k for k in (f"{ring}_shoulder_diameter", "width") if getattr(bearing, k) is None]
        if missing:
            raise ValueError(f"the burn-zone render needs bearing.{missing[0]} [m]; give "
                             + " and ".join(f"bearing.{k}" for k in missing) + " in the scene")
        centre = 0.5 * getattr(bearing, f"{ring}_groove_center_diameter")
        r = getattr(bearing, f"{ring}_groove_radius")
        sign = 1.0 if ring == "outer" else -1.0
        z = []
        for side in (1, -1):
            depth = sign * (0.5 * bearing.shoulder(ring, side) - centre)
            if not 0.0 < depth < r:
                raise ValueError(f"bearing.{ring}_shoulder_diameter = {bearing.shoulder(ring, side):g} m "
                                 f"does not cut the {ring} groove: it must lie between d and d {'+' if sign > 0 else '-'}"
                                 " 2 r of that groove")
            z.append(r * math.sin(math.acos(depth / r)))
        sides = cage.guide_sides(bearing) if cage is not None else (1, -1)
        return cls(ring, 0.5 * bearing.shoulder(ring, sides[0]), centre, r, 0.5 * bearing.width,
                   0.5 * cage.width if cage is not None else 0.0, (z[0], z[1]), tuple(sides),
                   tuple(0.5 * d for d in bearing.shoulders(ring)))

    @property
    def sign(self) -> float:
        """+1: the outer ring's bore (the groove bulges outwards), -1: the inner ring's outside."""
        return 1.0 if self.ring == "outer" else -1.0

    def land_radius_at(self, side: int) -> float:
        """The land's radius on `side` [m] (the guiding land's where the sides are alike)."""
        return self.land_radius if self.land_radii is None else self.land_radii[0 if side > 0 else 1]

    def z_land(self, side: int) -> float:
        """Axial distance of the groove–land edge from the groove plane on `side` [m] (≈ 8.90 mm, §2)."""
        return self.z_lands[0 if side > 0 else 1]

    @property
    def land_overlap(self) -> float:
        """Axial length L of the cage's overlap with the guiding lands together [m] (≈ 7.6 mm, §2)."""
        return sum(max(0.0, self.cage_half_width - self.z_land(side)) for side in self.land_sides)

    @property
    def alpha_limits(self) -> tuple[float, float]:
        """(lowest, highest) contact angle [rad] whose contact point lies on the raceway, between
        the lands: a positive angle presses the outer ring's +z side and the inner ring's -z side."""
        up, down = (math.asin(min(1.0, z / self.groove_radius)) for z in self.z_lands)
        return (-down, up) if self.ring == "outer" else (-up, down)

    def groove_point(self, alpha: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(radius, z) [m] of the groove surface where a contact of angle alpha [rad] sits."""
        alpha = np.asarray(alpha, dtype=float)
        return (self.groove_center_radius + self.sign * self.groove_radius * np.cos(alpha),
                self.sign * self.groove_radius * np.sin(alpha))


@dataclass(frozen=True)
class BurnZoneMap:
    """Burn-zone energy per land sector and ball-track density on the raceway."""

    profile: RaceProfile
    sector_energy: np.ndarray  # (S,) J per sector, sector k spans [k, k+1) * 2 pi / S
    sector: tuple[float, float] | None  # [start, end] rad of the 80 % arc (summary.json)
    track_density: np.ndarray  # (A, K) N·s per (azimuth, contact-angle) bin
    track_alpha_edges: np.ndarray  # (K + 1,) rad, spanning the profile's alpha_limits
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


def race_contact_points(ball_xyz: np.ndarray, angle: np.ndarray, profile: RaceProfile,
                        race_turn: np.ndarray | float = 0.0) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(azimuth [rad] in [0, 2 pi), radius [m], z [m]) of each ball's contact with the guiding
    race, the azimuth in the race's own frame (`race_turn` [rad]: the angle it has turned, per
    sample, for a race that turns).

    The contact lies in the plane through the axis and the ball centre (§6.1, gamma =
    atan2(Y, X)), at the groove point of its contact angle.
    """
    xyz = np.asarray(ball_xyz, dtype=float)
    turn = np.asarray(race_turn, dtype=float)
    phi = np.arctan2(xyz[..., 1], xyz[..., 0]) - (turn[..., None] if turn.ndim else turn)
    radius, z = profile.groove_point(np.asarray(angle, dtype=float))
    return np.mod(phi, 2.0 * math.pi), radius, z


def race_semi_major_axis(bearing, ball, race, angle: np.ndarray, load: np.ndarray, ring: str = "outer") -> np.ndarray:
    """Hertz semi-major axis a = c_a(alpha) Q^{1/3} [m] of the ball contacts with `ring`,
    along the groove (§6.2, exact constants tabulated in alpha by `dynamics.contact.hertz`)."""
    from ...dynamics.geometry import effective_modulus
    from ...dynamics.contact.hertz import race_hertz_table, semi_axis_coefficients

    table = race_hertz_table(bearing, effective_modulus(ball, race), outer=ring == "outer")
    c_a, _ = semi_axis_coefficients(table, np.ascontiguousarray(angle, dtype=float))
    return c_a * np.cbrt(np.clip(np.asarray(load, dtype=float), 0.0, None))


def _band_cdf(u: np.ndarray) -> np.ndarray:
    """Share of a Hertz ellipse's load below u = s/a across it: the line load across the
    ellipse (pressure integrated along the rolling direction) is (3/4)(1 - u^2)."""
    u = np.clip(u, -1.0, 1.0)
    # u * u * u, not u**3: NumPy's power has fast paths for squares and roots only, and the
    # generic one made this the largest cost of the report
    return 0.25 * (2.0 + 3.0 * u - u * u * u)


def contact_track_density(t: np.ndarray, ball_xyz: np.ndarray, angle: np.ndarray,
                          load: np.ndarray, profile: RaceProfile,
                          semi_axis: np.ndarray | None = None,
                          azimuth_bins: int = TRACK_AZIMUTH_BINS,
                          angle_bins: int = TRACK_ANGLE_BINS,
                          chunk: int = 65536, race_turn: np.ndarray | float = 0.0) -> tuple[np.ndarray, np.ndarray, float]:
    """Load × time [N·s] of the ball contacts with the guiding race per (azimuth, groove-angle)
    bin, the azimuth in the race's frame (`race_turn`, as `race_contact_points`).

    Each contact's load × time is spread across the groove over its Hertz ellipse, the
    profile angles alpha ± a/r (a = `semi_axis` [m], along the groove), with the
    ellipse's line-load share per bin; without `semi_axis` each contact is a point.
    Returns (density (azimuth_bins, angle_bins), angle edges [rad] over the raceway
    (the profile's `alpha_limits`), share of load × time lying beyond a land edge: the
    truncated part of the ellipse, not drawn).
    """
    phi, _, _ = race_contact_points(ball_xyz, angle, profile, race_turn)
    weight = np.clip(np.asarray(load, dtype=float), 0.0, None) * time_weights(t)[:, None]
    loaded = weight > 0.0
    phi, w = phi[loaded], weight[loaded]
    alpha = np.asarray(angle, dtype=float)[loaded]
    half = (np.zeros_like(alpha) if semi_axis is None
            else np.asarray(semi_axis, dtype=float)[loaded] / profile.groove_radius)
    half = np.maximum(half, 1e-12)  # a point contact: a step of the cumulative share
    edges = np.linspace(*profile.alpha_limits, angle_bins + 1)
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


def burn_zone_map(series: dict, profile: RaceProfile, sectors: int = BURN_SECTORS,
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
    # a land that turns (the inner ring's) is mapped in its own frame: it carries its heat round
    turn = (np.asarray(series["inner_race/angle"].data, dtype=float)
            if profile.ring == "inner" and "inner_race/angle" in series else np.zeros_like(t))
    if "cage_race/friction_power" in series:
        eps = (series["cage_race/eccentricity_ratio"].data if "cage_race/eccentricity_ratio" in series
               else np.zeros_like(t))
        film = series["cage_race/film_power"].data if "cage_race/film_power" in series else None
        drag = (np.sign(np.asarray(series["cage/speed"].data, dtype=float) + land_speed)
                if "cage/speed" in series else 0.0)
        metal, film_heat = land_heat(t, np.asarray(series["cage_race/contact_azimuth"].data) - turn, eps,
                                     series["cage_race/friction_power"].data, film, land_boundary, start,
                                     sectors, drag=drag)
    else:
        metal, film_heat = np.zeros(sectors), np.zeros(sectors)
    energy = metal + film_heat
    late = t >= start
    ball_xyz = np.asarray(series["balls/position"].data)[late]
    angle = np.asarray(series[f"contacts/{profile.ring}_contact_angle"].data)[late]
    load = np.asarray(series[f"contacts/{profile.ring}_load"].data)[late]
    axis = None if semi_axis is None else np.asarray(semi_axis)[late]
    density, edges, outside = contact_track_density(t[late], ball_xyz, angle, load, profile, axis,
                                                    race_turn=turn[late])
    sector = tuple(summary_sector) if summary_sector is not None else burn_zone_sector(energy)
    return BurnZoneMap(profile, energy, sector, density, edges, outside, metal, film_heat,
                       (start, float(t[-1])), startup_metal_energy)
