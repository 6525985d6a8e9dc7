"""Summary metrics of a dynamic run (`summary.json`, docs/outputs.md), from saved time series.

Conventions:

- **Settled window.** Every metric of the cage — time averages (cage speed, variation,
  eccentricity, metal-contact fraction, contact and offset spread, whirl ratio, land force,
  inner-race axial mean), the thinnest land film, pocket-impact counts and the burn zone —
  is taken over the *settled window*: from the end of the start-up transient, found from
  the series by the block rule of `pipeline.results.settled_window`, to the end of the
  run. The start-up is reported on its own (`startup`: its end, peak metal force, metal and
  film energy, peak land force, impacts), so a start-up crash is neither lost nor mistaken
  for the regime.
- **Drift check.** `settled_drift` gives a few metrics over the first and the second half of
  the settled window: values that differ a lot say the statistics still drift (run longer).
- **Warnings.** `warnings` lists what makes the numbers doubtful (a settled window shorter
  than 10 cage revolutions, a start-up that never ended, missing series).
- **Burn zone = where the land heats**, per angular sector of the land (360 sectors):
  the metal-contact friction energy at the contact azimuth (M.112) *plus* the viscous shear
  energy of the land film, spread round the land like the shear of (M.85): ~1/h on the
  converging half, ~h_min/h^2 on the cavitated half (M.114, see `film_heat_histogram`). Both
  layers are kept (`burn_zone_energy_metal`, `burn_zone_energy_film`; total
  `burn_zone_energy_total`, whose 80 % arc is `burn_zone_sector`).
- **Film-thickness ratio** Lambda = h_min / sigma, h_min the thinnest land film of the
  settled window and sigma the composite RMS roughness of cage rim and land,
  sigma = sqrt(Rq_rim^2 + Rq_land^2). Default 1.0e-6 m (`DEFAULT_LAND_ROUGHNESS`): a ground
  race land has Rq ~ 0.2-0.3 µm, a turned or ground bronze/brass cage rim Rq ~ 0.8-1.0 µm,
  so sigma ~ 1 µm. Lambda < 1: boundary lubrication (asperities carry load), 1-3: mixed,
  > 3: full film (the classic regimes of T. E. Tallian, "On competing failure modes in
  rolling contact", ASLE Trans. 10, 1967, and B. J. Hamrock, S. R. Schmid, B. O. Jacobson,
  *Fundamentals of Fluid Film Lubrication*, 2nd ed., 2004, on the film parameter). The
  hybrid land model's "metal contact" begins at eps = 1, i.e. at a film of eps0 C (12.5 µm
  for case b at its operating clearance; `land_contact_film`); Lambda says how close the
  film comes to the surfaces' real roughness, which the hybrid law does not see.
- Azimuths are measured in the global frame from +x towards +y (docs/model.md §1), in rad
  in `summary.json` (degrees only in the `verdict`); the heat maps of a land or rim that
  turns are in that body's frame, its azimuth at t = 0.

Keys written by `cage_summary` (SI units; time means are trapezoidal over the window):

=============================== ==========================================================
`settled_window`                [start, end] s; `settled_revolutions` cage revolutions in it
`cage_speed_mean`, `_variation` rad/s; (max - min) / mean
`cage_eps_mean`, `cage_eps_max` eccentricity ratio eps [-]
`cage_metal_contact_fraction`   share of the time with eps > 1 [-]
`cage_contact_angle_spread`     circular spread of the contact azimuth while eps > 1 [rad]
`cage_offset_azimuth_mean`      mean direction of the cage offset [rad]
`cage_offset_spread`            circular spread of the offset direction [rad] (pressed class)
`cage_offset_sector`            [start, end] rad: shortest arc holding 80 % of the time of
                                the contact azimuth (the land point facing the offset)
`cage_whirl_ratio`              whirl speed of the centre / cage speed [-]
`cage_land_force_mean`, `_max`  magnitude of the land force on the cage [N]
`land_film_min`                 thinnest land film [m], at `land_film_min_time` [s] and
                                `land_film_min_azimuth` [rad]
`land_roughness`                sigma [m] used; `land_film_ratio_min` = Lambda_min [-]
`land_contact_film`             eps0 C [m]: the film below which the land law counts metal
                                contact (eps > 1)
`inner_race_axial_mean`         m
`pocket_impacts`, `_force_p95`  count, N (settled window); `pocket_impact_regions`
                                [[start, end, share], ...] rad, rad, - (`impact_regions`)
`burn_zone_energy_metal/_film`  J; `burn_zone_energy_total` their sum
`burn_zone_sector`              80 % arc of the total heat [rad] on the land, in the land's
                                own frame (a land that turns, the inner ring's, carries its
                                heat round); `burn_zone_sector_metal` of the metal energy
                                only (None without metal contact); `burn_zone_sector_cage`
                                the 80 % arc on the cage rim, in the cage's frame
`pocket_force_max_mean`, `_p95` time mean of the largest ball-pocket force; 95th percentile
                                of every pocket's force over the samples [N]
`startup`                       {end_time, revolutions, block_length, limited_by,
                                max_metal_force, metal_energy, film_energy, land_force_peak,
                                metal_contact_fraction, pocket_impacts, pocket_impact_force_max}
`settled_drift`                 {key: [first half, second half]} of the settled window for
                                cage_eps_mean, cage_metal_contact_fraction,
                                cage_land_force_mean, cage_offset_azimuth_mean, land_film_min
`warnings`                      list of sentences
=============================== ==========================================================
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .settled_window import detect_settled_window, time_weights

DEFAULT_LAND_ROUGHNESS = 1.0e-6  # m, composite RMS roughness of cage rim and land (module docstring)
BURN_SECTORS = 360


def split_weights(t: np.ndarray, start: float | None) -> tuple[np.ndarray, np.ndarray]:
    """Trapezoidal weights of the start-up [t0, t_i] and of the settled window [t_i, t_end],
    t_i the first sample at or after `start`: each is the exact trapezoid rule of its own
    interval, they share the sample t_i, and they add up to `time_weights(t)`."""
    t = np.asarray(t, dtype=float)
    early, late = np.zeros_like(t), np.zeros_like(t)
    i = int(np.searchsorted(t, start, side="left")) if start is not None else 0
    i = min(i, t.size - 1)
    late[i:] = time_weights(t[i:]) if t.size - i > 1 else 0.0
    if i > 0:
        early[:i + 1] = time_weights(t[:i + 1])
    return early, late


def analysis_window(t: np.ndarray) -> np.ndarray:
    """Boolean mask of the last half of the run (the window of summaries before the
    settled window; kept for comparisons)."""
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
    return math.sqrt(max(0.0, -2.0 * math.log(r))) if r > 0.0 else float("inf")


def circular_mean(angles: np.ndarray, weights: np.ndarray | None = None) -> float:
    """Mean direction [rad] in [0, 2 pi) (Mardia & Jupp §2.2.1); NaN when undefined."""
    angles = np.asarray(angles, dtype=float)
    w = np.ones_like(angles) if weights is None else np.asarray(weights, dtype=float)
    if angles.size == 0 or w.sum() <= 0.0:
        return float("nan")
    c, s = float(np.sum(w * np.cos(angles))), float(np.sum(w * np.sin(angles)))
    return math.atan2(s, c) % (2.0 * math.pi) if math.hypot(c, s) > 1e-12 * w.sum() else float("nan")


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


def clearance_from_series(cage_xy: np.ndarray, eccentricity_ratio: np.ndarray) -> float | None:
    """Guide clearance C = |offset| / eps [m] (the definition of eps), median over samples
    with a measurable offset; None when the cage never leaves the centre."""
    xy = np.asarray(cage_xy, dtype=float)
    eps = np.asarray(eccentricity_ratio, dtype=float)
    ok = eps > 1e-3
    return float(np.median(np.hypot(xy[ok, 0], xy[ok, 1]) / eps[ok])) if ok.any() else None


def burn_zone_histogram(azimuth: np.ndarray, energy: np.ndarray, sectors: int = BURN_SECTORS) -> np.ndarray:
    """Energy [J] accumulated per angular sector of the guide land, each sample's energy in
    the sector of its azimuth (M.112: metal friction at the contact azimuth).

    `azimuth` [rad] is the contact direction at each sample, `energy` [J] the energy
    dissipated during that sample (power x sample weight).
    """
    edges_index = np.floor((np.mod(azimuth, 2.0 * math.pi)) / (2.0 * math.pi) * sectors).astype(int)
    edges_index = np.clip(edges_index, 0, sectors - 1)
    return np.bincount(edges_index, weights=np.asarray(energy, dtype=float), minlength=sectors)


def _film_cumulative(x: np.ndarray, k: np.ndarray, drag: np.ndarray) -> np.ndarray:
    """sqrt(1 - k^2) times the integral of the shear-heat density of `film_heat_histogram`
    from -pi to x, continued periodically (x relative to the thinnest film, any real).

    One sine, cosine and arctangent per point: the antiderivative of 1/h below is odd in x and
    the mirrored (drag < 0) branch reads it at -x, so both branches share them (three times
    as many would dominate a run's post-processing)."""
    s = np.sqrt(1.0 - k * k)
    beta = k / (1.0 + s)
    period = np.floor((x + math.pi) / (2.0 * math.pi))
    xr = x - 2.0 * math.pi * period  # in [-pi, pi)
    sin_x, cos_x = np.sin(xr), np.cos(xr)
    # s * integral of 1 / (1 - k cos) from 0 to xr; odd in xr
    one_over_h = xr + 2.0 * np.arctan2(beta * sin_x, 1.0 - beta * cos_x)
    # drag > 0: converging half [-pi, 0] full film 1/h, cavitated half (0, pi) striated
    # (1 - k)/(1 - k cos)^2; drag < 0 is its mirror image, G(x) = G_tot - G_+(-x)
    mirror = np.where(drag < 0, -1.0, 1.0)
    y = mirror * xr
    o_y = mirror * one_over_h  # the antiderivative at y = +-xr
    g = np.where(y <= 0.0, math.pi + o_y,
                 math.pi + (k * s * (mirror * sin_x) / (1.0 - k * cos_x) + o_y) / (1.0 + k))
    whole = math.pi * (2.0 + k) / (1.0 + k)
    g = np.where(drag < 0, whole - g, g) + whole * period
    if np.any(drag == 0):  # full film all round
        g = np.where(drag == 0, math.pi + one_over_h + 2.0 * math.pi * period, g)
    return g


def film_heat_histogram(azimuth: np.ndarray, film_ratio: np.ndarray, energy: np.ndarray,
                        sectors: int = BURN_SECTORS, chunk: int = 2048,
                        drag: np.ndarray | float = 0.0) -> np.ndarray:
    """Viscous shear energy of the land film [J] per angular sector of the land (M.114).

    In the film the shear stress is mu U / h, so the dissipation per unit land area is
    q(theta) = mu U^2 / h(theta) (Couette flow; the Poiseuille share, O(eps^2 L^2/R^2), is
    neglected as in (M.85)), with the film

        h(theta) = C_f - e cos(theta - phi) = C_f (1 - k cos(theta - phi)),   k = e / C_f,

    C_f = C (1 + eps0) the film clearance of the hybrid model (C of the hydrodynamic one),
    e = eps C the cage offset and phi the contact azimuth (the land point facing the offset,
    where the film is thinnest). Each sample's film energy (film power x weight, the model's
    f_C |T_hyd omega_rel|) is spread over the land with that density and normalised to it,
    so the sectors of one sample sum to its energy.

    The density follows the film torque (M.85) the energy comes from: full film, q ~ 1/h, on
    the converging half upstream of the thinnest film, and the striated film of the
    cavitated half downstream of it, fill fraction h_min/h, so q ~ h_min/h^2 there.
    "Downstream" is the direction the film is dragged in, `drag` = sign(omega_cage +
    omega_land) per sample (+1: towards +theta); `drag` = 0 spreads the full film 1/h over
    the whole land (direction unknown). Integrated round the land the density gives
    (M.85)'s (2 + k)/((1 + k) sqrt(1 - k^2)) (tested): the map and the film power agree.

    Exact per sector (no quadrature error however thin the film): with s = sqrt(1 - k^2),
    beta = k / (1 + s),

        s * integral of dx / (1 - k cos x)          = x + 2 atan2(beta sin x, 1 - beta cos x),
        s * integral of (1 - k) dx / (1 - k cos x)^2 = [k s sin x / (1 - k cos x)
                                                        + x + 2 atan2(beta sin x, 1 - beta cos x)] / (1 + k),

    the first from the Poisson kernel's Fourier series integrated term by term, the second
    from the reduction formula for the integral of (a + b cos x)^-2. k is clipped to
    [0, 1 - 1e-12]; as k -> 1 the whole energy goes to the sector of phi.

    `azimuth` phi [rad], `film_ratio` k = e / C_f [-], `energy` [J] per sample, `drag` [-]
    (scalar or per sample).
    """
    energy = np.asarray(energy, dtype=float)
    keep = energy != 0.0
    phi = np.asarray(azimuth, dtype=float)[keep]
    k = np.clip(np.asarray(film_ratio, dtype=float)[keep], 0.0, 1.0 - 1e-12)  # k -> 1: all at phi
    drag = np.sign(np.broadcast_to(np.asarray(drag, dtype=float), keep.shape)[keep])
    energy = energy[keep]
    total = math.pi * (2.0 + k) / (1.0 + k)  # s * the integral over one period, drag != 0
    total = np.where(drag == 0, 2.0 * math.pi, total)
    edges = np.linspace(0.0, 2.0 * math.pi, sectors + 1)
    hist = np.zeros(sectors)
    for s in range(0, energy.size, chunk):
        sl = slice(s, s + chunk)
        g = _film_cumulative(edges[None, :] - phi[sl, None], k[sl, None], drag[sl, None])
        hist += (energy[sl, None] / total[sl, None] * np.diff(g, axis=1)).sum(axis=0)
    return hist


def burn_zone_sector(hist: np.ndarray, share: float = 0.8) -> tuple[float, float] | None:
    """Shortest circular arc of sectors holding `share` of the energy, as [start, end]
    azimuths in rad (start in [0, 2 pi), end = start + width). None without energy."""
    hist = np.asarray(hist, dtype=float)
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


def land_heat(t: np.ndarray, contact_azimuth: np.ndarray, eccentricity_ratio: np.ndarray,
              friction_power: np.ndarray, film_power: np.ndarray | None, land_boundary: float,
              start: float | None = None, sectors: int = BURN_SECTORS,
              drag: np.ndarray | float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    """(metal, film) energy per land sector [J] over t >= `start` (None: the whole run):
    the two layers of the burn zone (module docstring). `land_boundary` is eps0 of the
    hybrid law (film clearance C (1 + eps0); 0 for the hydrodynamic model); `drag` the
    direction the film is dragged in, sign(omega_cage + omega_land) (0: unknown, full film
    all round; see `film_heat_histogram`). A run without a film-power series has an
    all-zero film layer."""
    w = split_weights(t, start)[1]
    azimuth = np.asarray(contact_azimuth, dtype=float)
    metal = burn_zone_histogram(azimuth, np.asarray(friction_power, dtype=float) * w, sectors)
    if film_power is None:
        return metal, np.zeros(sectors)
    ratio = np.asarray(eccentricity_ratio, dtype=float) / (1.0 + land_boundary)
    film = film_heat_histogram(azimuth, ratio, np.asarray(film_power, dtype=float) * w, sectors, drag=drag)
    return metal, film


def impact_regions(orbital_position: np.ndarray, bins: int = 36, factor: float = 2.0,
                   min_impacts: int = 10, max_regions: int = 3) -> list[list[float]] | None:
    """Orbital regions where pocket impacts concentrate: [start, end, share] (rad, rad, -),
    largest share first. Impacts are counted in `bins` sectors of the orbit (10°); a region
    is a run of neighbouring sectors each holding at least `factor` times the uniform count
    m (twice as many impacts as if they were spread evenly round the orbit) and at least
    m + 3 sqrt(m), three Poisson standard deviations above it, so that a few impacts in an
    otherwise even spread do not make a region. [] when no sector stands out (impacts all
    round), None with fewer than `min_impacts` impacts."""
    pos = np.mod(np.asarray(orbital_position, dtype=float), 2.0 * math.pi)
    if pos.size < min_impacts:
        return None
    counts = np.bincount(np.minimum((pos / (2.0 * math.pi) * bins).astype(int), bins - 1), minlength=bins)
    uniform = pos.size / bins
    dense = counts >= max(factor * uniform, uniform + 3.0 * math.sqrt(uniform))
    if not dense.any():
        return []
    if dense.all():
        return [[0.0, 2.0 * math.pi, 1.0]]
    first = int(np.argmin(dense))  # start scanning at a sparse sector: runs do not wrap in the scan
    regions, run = [], []
    for j in range(first, first + bins + 1):
        i = j % bins
        if dense[i] and j < first + bins:
            run.append(j)
        elif run:
            share = float(sum(counts[r % bins] for r in run)) / pos.size
            step = 2.0 * math.pi / bins
            begin = (run[0] % bins) * step
            regions.append([begin, begin + len(run) * step, share])
            run = []
    regions.sort(key=lambda r: -r[2])
    return regions[:max_regions]


def _pocket_load_keys(pocket_force, t: np.ndarray, start: float) -> dict:
    """The balls' steady load on their pockets over the settled window: the time mean of the
    largest pocket force and the 95th percentile of every ball's force over the samples [N]
    (what carries a ball-guided cage, and pushes any cage round)."""
    if pocket_force is None:
        return {}
    force = np.asarray(pocket_force, dtype=float)
    late = t >= start
    if late.sum() < 2:
        late = np.ones_like(t, dtype=bool)
    w = time_weights(t[late])
    largest = force[late].max(axis=1)
    return {"pocket_force_max_mean": float(np.sum(w * largest) / max(w.sum(), 1e-300)),
            "pocket_force_p95": float(np.percentile(force[late], 95))}


def _f(value) -> float | None:
    """A JSON number: float, or None for missing / NaN."""
    if value is None:
        return None
    value = float(value)
    return value if math.isfinite(value) else None


def _window_metrics(t, w, eps, metal, offset_az, force_norm, film) -> dict:
    """Mean eps, metal fraction, mean land force, mean offset direction and thinnest film
    over the samples of one window (`w` their trapezoid weights)."""
    span = float(w.sum())
    if span <= 0.0:
        return {}
    return {
        "cage_eps_mean": float(np.sum(w * eps) / span),
        "cage_metal_contact_fraction": float(np.sum(w * metal) / span),
        "cage_land_force_mean": _f(np.sum(w * force_norm) / span) if force_norm is not None else None,
        "cage_offset_azimuth_mean": _f(circular_mean(offset_az, w)),
        "land_film_min": _f(np.min(film)) if film is not None and film.size else None,
    }


@dataclass(frozen=True)
class CageSeries:
    """The series `cage_summary` reads, at the sample times `t` [s]: `cage_xy` (n, 2) [m],
    `cage_speed` [rad/s], `eccentricity_ratio` [-], `contact_azimuth` [rad], `friction_power`
    (metal) [W], `inner_race_z` [m], and optionally `film_power` [W] and `min_film` [m] of the
    land film, `land_force` (n, 2) [N], `metal_force` [N]."""

    t: np.ndarray
    cage_xy: np.ndarray
    cage_speed: np.ndarray
    eccentricity_ratio: np.ndarray
    contact_azimuth: np.ndarray
    friction_power: np.ndarray
    inner_race_z: np.ndarray
    film_power: np.ndarray | None = None
    min_film: np.ndarray | None = None
    land_force: np.ndarray | None = None
    metal_force: np.ndarray | None = None
    land_angle: np.ndarray | None = None  # [rad] the guiding land has turned (None: fixed land)
    cage_angle: np.ndarray | None = None  # [rad] the cage has turned (its rim's heat map)
    pocket_force: np.ndarray | None = None  # (n, Z) [N] ball-pocket normal forces


@dataclass(frozen=True)
class PocketImpacts:
    """Pocket impacts: `peak_forces` [N] with their `times` [s] and `orbital_positions` [rad]
    (without times, every impact counts as settled)."""

    peak_forces: np.ndarray
    times: np.ndarray | None = None
    orbital_positions: np.ndarray | None = None


@dataclass(frozen=True)
class GuideLand:
    """The guiding land: `clearance` C [m] (None: from the series), `boundary` eps0 [-] of the
    hybrid law (0 for the hydrodynamic model), `roughness` sigma [m] (composite RMS roughness
    of cage rim and land); `film` False for a land model without film (dry contact only: no
    film layer, no film keys); `speed` [rad/s] the guiding race's speed (the film is dragged
    by cage and land together, which sets the cavitated side of the film heat)."""

    clearance: float | None = None
    boundary: float = 0.05
    roughness: float = DEFAULT_LAND_ROUGHNESS
    film: bool = True
    speed: float = 0.0


def cage_summary(series: CageSeries, impacts: PocketImpacts, land: GuideLand = GuideLand(), *,
                 sectors: int = BURN_SECTORS, settled_start: float | None = None) -> dict:
    """The cage, land and impact keys of `summary.json` (module docstring), from the cage's
    `series`, the pocket `impacts` and the guiding `land`; `sectors` of the burn-zone
    histograms; `settled_start` [s] overrides the detected end of the start-up (tests,
    comparisons)."""
    t, cage_xy, cage_speed = series.t, series.cage_xy, series.cage_speed
    eccentricity_ratio, contact_azimuth, friction_power = series.eccentricity_ratio, series.contact_azimuth, \
        series.friction_power
    inner_race_z, film_power, min_film = series.inner_race_z, series.film_power, series.min_film
    land_force, metal_force = series.land_force, series.metal_force
    impact_peak_forces, impact_times, impact_orbital_positions = impacts.peak_forces, impacts.times, \
        impacts.orbital_positions
    guide_clearance, land_boundary, land_roughness = land.clearance, land.boundary, land.roughness
    land_film, land_speed = land.film, land.speed

    t = np.asarray(t, dtype=float)
    xy = np.asarray(cage_xy, dtype=float)[:, :2]
    speed_all = np.asarray(cage_speed, dtype=float)
    eps_all = np.asarray(eccentricity_ratio, dtype=float)
    az_all = np.asarray(contact_azimuth, dtype=float)
    fric_all = np.asarray(friction_power, dtype=float)
    warnings: list[str] = []
    if guide_clearance is None or not guide_clearance > 0.0:
        guide_clearance = clearance_from_series(xy, eps_all)
    window = detect_settled_window(t, eps_all, xy, speed_all, guide_clearance)
    if settled_start is not None:
        window = type(window)(float(settled_start), window.end, window.block, window.revolution,
                              ("given",), ())
        if math.isfinite(window.revolution) and window.revolutions < 10.0:
            warnings.append(f"run too short to settle: the settled window holds {window.revolutions:.1f} "
                            "cage revolutions (< 10)")
    warnings += list(window.warnings)
    win = window.mask(t)
    if win.sum() < 2:  # a run of one or two samples: use what there is
        win = np.ones_like(t, dtype=bool)
    tw = t[win]
    w = time_weights(tw)
    span = max(tw[-1] - tw[0], 1e-300)
    speed = speed_all[win]
    mean_speed = float(np.sum(w * speed) / span)
    eps = eps_all[win]
    metal = eps > 1.0
    azim = az_all[win]
    offset_az = np.arctan2(xy[win, 1], xy[win, 0])
    force_norm = np.hypot(*np.asarray(land_force, dtype=float)[:, :2].T) if land_force is not None else None
    if not land_film:
        film_all, film_power = None, None
    elif min_film is not None:
        film_all = np.asarray(min_film, dtype=float)
    elif guide_clearance is not None:  # the hybrid model's thinnest film, C (1 + eps0) - e
        film_all = np.maximum(guide_clearance * (1.0 + land_boundary - eps_all), 0.0)
        warnings.append("no land-film series (cage_race/min_film): thinnest film from eps as C (1 + eps0 - eps)")
    else:
        film_all = None
    if film_power is None and land_film:
        warnings.append("no film-power series (cage_race/film_power): the burn zone holds metal friction only")

    # burn zone: both layers over the settled window, on the land in its own frame (a turning
    # land carries its heat round with it) and on the cage rim; the start-up's share apart
    drag = np.sign(speed_all + land_speed)
    land_turn = 0.0 if series.land_angle is None else np.asarray(series.land_angle, dtype=float)
    metal_hist, film_hist = land_heat(t, az_all - land_turn, eps_all, fric_all, film_power, land_boundary,
                                      window.start, sectors, drag=drag)
    total_hist = metal_hist + film_hist
    rim_sector = None
    if series.cage_angle is not None:
        rim_metal, rim_film = land_heat(t, az_all - np.asarray(series.cage_angle, dtype=float), eps_all, fric_all,
                                        film_power, land_boundary, window.start, sectors, drag=drag)
        rim_sector = burn_zone_sector(rim_metal + rim_film)
    w_early = split_weights(t, window.start)[0]
    early = ~window.mask(t)
    sector = burn_zone_sector(total_hist)
    sector_metal = burn_zone_sector(metal_hist)
    offset_sector = burn_zone_sector(burn_zone_histogram(azim, w, sectors))

    # thinnest land film of the settled window, when and where
    film = film_all[win] if film_all is not None else None
    film_keys = {"land_film_min": None, "land_film_min_time": None, "land_film_min_azimuth": None,
                 "land_roughness": float(land_roughness), "land_film_ratio_min": None,
                 "land_contact_film": (float(guide_clearance * land_boundary)
                                       if land_film and guide_clearance is not None else None)}
    if film is not None and film.size:
        i = int(np.argmin(film))
        h_min = float(film[i])
        film_keys.update(land_film_min=h_min, land_film_min_time=float(tw[i]),
                         land_film_min_azimuth=float(np.mod(azim[i], 2.0 * math.pi)),
                         land_film_ratio_min=max(h_min, 0.0) / land_roughness)

    # pocket impacts: settled window, start-up apart
    peaks = np.asarray(impact_peak_forces, dtype=float)
    if impact_times is not None:
        late_impact = np.asarray(impact_times, dtype=float) >= window.start
    else:
        late_impact = np.ones(peaks.size, dtype=bool)
    settled_peaks = peaks[late_impact]
    regions = None
    if impact_orbital_positions is not None:
        regions = impact_regions(np.asarray(impact_orbital_positions, dtype=float)[late_impact])

    # drift: the same metrics over the first and second half of the settled window
    half = tw[0] + 0.5 * (tw[-1] - tw[0])
    drift: dict[str, list] = {}
    parts = []
    for part in (tw < half, tw >= half):
        if part.sum() < 2:
            parts.append({})
            continue
        parts.append(_window_metrics(
            tw[part], time_weights(tw[part]), eps[part], metal[part], offset_az[part],
            force_norm[win][part] if force_norm is not None else None,
            film[part] if film is not None else None))
    for key in ("cage_eps_mean", "cage_metal_contact_fraction", "cage_land_force_mean",
                "cage_offset_azimuth_mean", "land_film_min"):
        drift[key] = [parts[0].get(key), parts[1].get(key)]
    whole = _window_metrics(tw, w, eps, metal, offset_az,
                            force_norm[win] if force_norm is not None else None, film)

    startup_film = float(np.sum(np.asarray(film_power, dtype=float) * w_early)) if film_power is not None else None
    startup = {
        "end_time": float(window.start),
        "revolutions": _f((window.start - t[0]) / window.revolution) if math.isfinite(window.revolution) else None,
        "block_length": _f(window.block),
        "limited_by": list(window.limited_by),
        "max_metal_force": (_f(np.max(np.asarray(metal_force, dtype=float)[early], initial=0.0))
                            if metal_force is not None else None),
        "metal_energy": float(np.sum(fric_all * w_early)),
        "film_energy": startup_film,
        "land_force_peak": _f(np.max(force_norm[early], initial=0.0)) if force_norm is not None else None,
        "metal_contact_fraction": _f(np.sum(w_early * (eps_all > 1.0)) / w_early.sum()) if w_early.sum() > 0.0 else 0.0,
        "pocket_impacts": int(np.sum(~late_impact)),
        "pocket_impact_force_max": float(np.max(peaks[~late_impact], initial=0.0)),
    }
    return {
        "settled_window": [float(window.start), float(window.end)],
        "settled_revolutions": _f(window.revolutions),
        "cage_speed_mean": mean_speed,
        "cage_speed_variation": float((speed.max() - speed.min()) / mean_speed) if mean_speed else float("nan"),
        "cage_eps_mean": whole.get("cage_eps_mean"),
        "cage_eps_max": float(np.max(eps)),
        "cage_metal_contact_fraction": float(np.sum(w * metal) / span),
        "cage_contact_angle_spread": circular_spread(azim[metal], w[metal]) if metal.any() else None,
        "cage_offset_azimuth_mean": whole.get("cage_offset_azimuth_mean"),
        "cage_offset_spread": _f(circular_spread(offset_az, w)),
        "cage_offset_sector": list(offset_sector) if offset_sector is not None else None,
        "cage_whirl_ratio": whirl_ratio(tw, xy[win, 0], xy[win, 1], speed),
        "cage_land_force_mean": whole.get("cage_land_force_mean"),
        "cage_land_force_max": _f(np.max(force_norm[win])) if force_norm is not None else None,
        **film_keys,
        "inner_race_axial_mean": float(np.sum(w * np.asarray(inner_race_z, dtype=float)[win]) / span),
        "pocket_impacts": int(settled_peaks.size),
        "pocket_impact_force_p95": float(np.percentile(settled_peaks, 95)) if settled_peaks.size else 0.0,
        "pocket_impact_regions": regions,
        "burn_zone_sector": list(sector) if sector is not None else None,
        "burn_zone_sector_metal": list(sector_metal) if sector_metal is not None else None,
        "burn_zone_energy_metal": float(np.sum(metal_hist)),
        "burn_zone_energy_film": float(np.sum(film_hist)),
        "burn_zone_energy_total": float(np.sum(total_hist)),
        "burn_zone_sector_cage": list(rim_sector) if rim_sector is not None else None,
        **_pocket_load_keys(series.pocket_force, t, window.start),
        "startup": startup,
        "settled_drift": drift,
        "warnings": warnings,
    }
