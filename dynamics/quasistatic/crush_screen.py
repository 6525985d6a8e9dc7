"""Cage crush screen: from the quasi-static load distribution, where the balls must push the
cage and whether its guide clearance can absorb them (docs/model.md §10.1, M.115–M.118, M.123–M.124).

Under a moment the contact angles vary round the bearing, so each ball's pure-rolling orbital
speed omega_m(psi) varies with its orbital position psi. Against a rigid cage turning at the
mean speed, a ball leads and lags by the excursion (arc at the pitch radius r_p)

    s(psi) = r_p int_0^psi (omega_m(psi')/omega_c - 1) dpsi'   (zero mean)        (M.115)

A ball floats in its pocket while |s| stays inside the pocket clearance; a cage whose centre
moves by d shifts each pocket along the orbit by d . e_t(psi), which cancels the first harmonic
of s. So with c_p = d_p - D the pocket clearance, C the radial guide clearance and s1 the
amplitude of the first harmonic of s, the screen reads (M.116):

    free     s_pp <= c_p                  balls never reach both walls: no steady push
    pressed  c_p < s_pp, e_req <= C       the cage must sit off-centre by e_req = s1 - c_p/2
                                          towards the push direction, held there by its film
    crushed  e_req > C                    the cage cannot make room: balls force it onto the
                                          land (metal contact, the burn of case b on the rig)

Balls reach the front wall where s is largest and the rear wall where it is smallest; the
pair pushes the cage along e_t at the front-wall position (M.117). The steady push of a
pressed cage is the land film's force at e_req (Ocvirk, docs/model.md §8), an estimate of
the least push the balls must exert (M.118). Pure rolling ignores slip, cage speed
variation and the cage's axial motion; docs/validation.md compares the screen with the
dynamic runs.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..journal.short_bearing import EPS_CLIP, ocvirk_force


@dataclass(frozen=True)
class CageClearances:
    """The clearances the screen weighs (SI, at the scene's operating temperatures)."""

    pocket: float  # c_p = d_p - D [m]
    guide: float  # C [m]
    pocket_circle_eccentricity: float = 0.0  # e_r, cage run-out [m]
    pocket_index_range: float = 0.0  # spread of the pocket pitch errors [m]
    non_guiding: float | None = None  # C_n, gap to the other ring's land, parts centred [m]

    @property
    def effective_pocket(self) -> float:
        """c_p less the pocket pitch-error spread [m]."""
        return self.pocket - self.pocket_index_range


@dataclass(frozen=True)
class LandFilm:
    """The guide lands as a short journal bearing (docs/model.md §8), for the film push."""

    radius: float  # land radius R [m]
    length: float  # L, both lands together [m]
    lands: int  # the number of lands L is split into
    eps0: float  # boundary-layer width of the hybrid law / C [-]
    viscosity: float  # land film viscosity [Pa s]


@dataclass(frozen=True)
class CageScreen:
    """Result of `crush_screen` (SI units; azimuths in rad from +x towards +y)."""

    regime: str  # "free" | "pressed" | "crushed"
    excursion: np.ndarray  # s(psi_k) per ball [m], + ahead of a rigid cage at the mean speed
    excursion_peak_to_peak: float  # s_pp [m]
    first_harmonic: float  # s1 [m]
    clearances: CageClearances
    required_eccentricity: float  # e_req at the cage's worst orientation (M.116, M.123) [m]
    required_eccentricity_min: float  # at its best orientation (differs with run-out) [m]
    push_azimuth: float  # direction the balls push the cage [rad]
    front_wall_azimuth: float  # orbital position where balls lead the cage most [rad]
    rear_wall_azimuth: float  # where they lag most [rad]
    film_push: float  # land film force at e_req (pressed) or at e = C (crushed) [N]
    crush_margin: float  # (C - e_req) / C: 1 free room, 0 at the crush threshold, < 0 crushed
    non_guiding_gap: float | None  # C_n - e_req - inner-ring offset [m] (< 0: the cage touches it)
    residual_peak_to_peak: float = 0.0  # s less its first harmonic, peak to peak [m] (Excursion)

    @property
    def pocket_clearance(self) -> float:
        return self.clearances.pocket

    @property
    def guide_clearance(self) -> float:
        return self.clearances.guide

    def to_json_dict(self) -> dict:
        deg = math.degrees
        c = self.clearances
        return {
            "regime": self.regime,
            "excursion_peak_to_peak": self.excursion_peak_to_peak,
            "excursion_first_harmonic": self.first_harmonic,
            "excursion_residual_peak_to_peak": self.residual_peak_to_peak,
            "pocket_clearance": c.pocket,
            "guide_clearance": c.guide,
            "pocket_circle_eccentricity": c.pocket_circle_eccentricity,
            "pocket_index_range": c.pocket_index_range,
            "non_guiding_clearance": c.non_guiding,
            "required_eccentricity": self.required_eccentricity,
            "required_eccentricity_min": self.required_eccentricity_min,
            "required_eccentricity_ratio": self.required_eccentricity / c.guide,
            "crush_margin": self.crush_margin,
            "non_guiding_gap": self.non_guiding_gap,
            "push_azimuth_deg": deg(self.push_azimuth) % 360.0,
            "front_wall_azimuth_deg": deg(self.front_wall_azimuth) % 360.0,
            "rear_wall_azimuth_deg": deg(self.rear_wall_azimuth) % 360.0,
            "film_push": self.film_push,
            "excursion_per_ball": [float(x) for x in self.excursion],
            "units": {"lengths": "m", "film_push": "N", "azimuths": "degree", "crush_margin": "1"},
        }


def orbital_excursion(azimuth: np.ndarray, orbital_speed: np.ndarray, pitch_radius: float,
                      nodes: int = 720) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """s(psi) of M.115 from the balls' pure-rolling orbital speeds at their azimuths.

    omega_m is periodic in psi and sampled at the Z ball positions; its Fourier series is
    integrated term by term (the mean term is the cage speed and drops out). Returns (s at
    the balls [m], psi on a fine grid, s on that grid)."""
    az = np.asarray(azimuth, float)
    speed = np.asarray(orbital_speed, float)
    mean = float(np.mean(speed))
    # rings at rest: the balls do not orbit, so none leads or lags the cage (s = 0, "free")
    rel = speed / mean - 1.0 if mean != 0.0 else np.zeros_like(speed)
    Z = az.size
    order = np.argsort(np.mod(az, 2 * math.pi))
    az, rel = np.mod(az[order], 2 * math.pi), rel[order]
    n_max = (Z - 1) // 2  # harmonics the Z samples resolve
    n = np.arange(1, n_max + 1)
    a = 2.0 / Z * np.cos(np.outer(n, az)) @ rel
    b = 2.0 / Z * np.sin(np.outer(n, az)) @ rel

    def s(psi):
        psi = np.asarray(psi, float)
        # int (a cos n psi + b sin n psi) = (a sin n psi - b cos n psi) / n
        return pitch_radius * ((a / n) @ np.sin(np.outer(n, psi)) - (b / n) @ np.cos(np.outer(n, psi)))

    grid = np.linspace(0.0, 2 * math.pi, nodes, endpoint=False)
    at_balls = np.empty(Z)
    at_balls[order] = s(az)
    return at_balls, grid, s(grid)


def required_offset(first_harmonic, peak_to_peak, clearances: CageClearances, cage_angle=None):
    """e_req of M.116/M.123 [m] and whether the balls press the cage (numpy, broadcasts).

    With `cage_angle` [rad] (array), e_req at those cage orientations; without it, the pair
    (best, worst) over a cage revolution. `pressed` is True where the balls reach both pocket
    walls at some orientation: s_pp + 2 e_r > c_p - pitch-error spread."""
    s1, s_pp = np.asarray(first_harmonic, float), np.asarray(peak_to_peak, float)
    e_r, c_eff = clearances.pocket_circle_eccentricity, clearances.effective_pocket
    e_r, c_eff = np.asarray(e_r, float), np.asarray(c_eff, float)
    pressed = s_pp + 2.0 * e_r > c_eff
    if cage_angle is not None:
        th = np.asarray(cage_angle, float)
        dist = np.hypot(s1 - e_r * np.cos(th), e_r * np.sin(th))  # d* along +x in the push frame
        return np.where(pressed, np.maximum(0.0, dist - 0.5 * c_eff), 0.0), pressed
    worst = np.where(pressed, np.maximum(0.0, s1 + e_r - 0.5 * c_eff), 0.0)
    best = np.where(pressed, np.maximum(0.0, np.abs(s1 - e_r) - 0.5 * c_eff), 0.0)
    return (best, worst), pressed


def crush_margin(first_harmonic, peak_to_peak, clearances: CageClearances):
    """(C - e_req) / C at the worst cage orientation, and the regime code (0 free, 1 pressed,
    2 crushed); numpy, broadcasts over arrays of clearances (the tolerance analysis)."""
    (_, worst), pressed = required_offset(first_harmonic, peak_to_peak, clearances)
    return margin_and_regime(worst, pressed, clearances.guide)


def margin_and_regime(worst_offset, pressed, guide_clearance):
    """(C - e_req) / C and the regime code (0 free, 1 pressed, 2 crushed) of a worst-orientation
    required offset (numpy, broadcasts)."""
    C = np.asarray(guide_clearance, float)
    return (C - worst_offset) / C, np.where(pressed, np.where(worst_offset > C, 2, 1), 0)


REGIMES = ("free", "pressed", "crushed")


@dataclass(frozen=True)
class Excursion:
    """The balls' excursion against a rigid cage (M.115) and its first harmonic."""

    at_balls: np.ndarray  # s(psi_k) [m]
    peak_to_peak: float  # s_pp [m]
    first_harmonic: float  # s1 [m]
    push_azimuth: float  # [rad]
    front_wall_azimuth: float  # [rad]
    rear_wall_azimuth: float  # [rad]
    residual_peak_to_peak: float = 0.0  # peak to peak of s less its first harmonic [m]


def excursion_of(azimuth, orbital_speed, pitch_radius: float) -> Excursion:
    """s_pp, s1 and the push direction of M.115–M.117 from the balls' orbital speeds, and
    the residual the cage's offset cannot take: s less its first harmonic, peak to peak.
    Where that residual exceeds the pocket clearance no cage position gives the balls room,
    and the screen's premise (a translation cancels the push) does not hold."""
    s_balls, grid, s = orbital_excursion(azimuth, orbital_speed, pitch_radius)
    # first harmonic s ~ a1 cos psi + b1 sin psi; a cage shift d moves pocket psi by d . e_t(psi)
    a1 = 2.0 * np.mean(s * np.cos(grid))
    b1 = 2.0 * np.mean(s * np.sin(grid))
    # -dx sin psi + dy cos psi = a1 cos psi + b1 sin psi  ->  d along (-b1, a1)
    residual = s - (a1 * np.cos(grid) + b1 * np.sin(grid))
    return Excursion(at_balls=s_balls, peak_to_peak=float(s.max() - s.min()), first_harmonic=math.hypot(a1, b1),
                     push_azimuth=math.atan2(a1, -b1), front_wall_azimuth=float(grid[np.argmax(s)]),
                     rear_wall_azimuth=float(grid[np.argmin(s)]),
                     residual_peak_to_peak=float(residual.max() - residual.min()))


def non_guiding_gap(clearance, offset, push_azimuth, land_shift=None):
    """g of M.124 [m] (numpy, broadcasts over stacks): the cage `offset` [m] along
    `push_azimuth` [rad]; `land_shift` (..., k, 2) [m] the guiding-land centre minus the
    non-guiding land centre at the cage's k ends (None: both centred)."""
    offset, azimuth = np.asarray(offset, float), np.asarray(push_azimuth, float)
    shift = np.zeros((1, 2)) if land_shift is None else np.asarray(land_shift, float)
    direction = np.stack([np.cos(azimuth), np.sin(azimuth)], axis=-1)[..., None, :]
    dist = np.linalg.norm(offset[..., None, None] * direction + shift, axis=-1)
    return np.asarray(clearance, float) - dist.max(axis=-1)


def crush_screen(excursion: Excursion, cage_speed: float, clearances: CageClearances, film: LandFilm,
                 land_shift=None) -> CageScreen:
    """The screen of M.115–M.124 (module docstring). `cage_speed` [rad/s]; `land_shift` as in
    `non_guiding_gap`. Film force at e_req: the static short bearing with clearance
    C (1 + eps0) (the hybrid law of docs/model.md §8; eps0 = 0 for a law without boundary
    layer, whose film is then evaluated at most at the clip EPS_CLIP) and omega the cage speed
    (outer race fixed)."""
    x = excursion
    (best, worst), pressed = required_offset(x.first_harmonic, x.peak_to_peak, clearances)
    margin, code = margin_and_regime(worst, pressed, clearances.guide)
    regime = REGIMES[int(code)]
    C = clearances.guide
    c_film = C * (1.0 + film.eps0)
    e_req = float(worst)
    eps_h = min(min(e_req, C) / c_film, EPS_CLIP)
    f_n, f_t, _, _ = ocvirk_force(eps_h, film.viscosity, cage_speed, film.radius, film.length / film.lands, c_film)
    gap = None
    if clearances.non_guiding is not None:
        gap = float(non_guiding_gap(clearances.non_guiding, min(e_req, C), x.push_azimuth, land_shift))
    return CageScreen(regime=regime, excursion=x.at_balls, excursion_peak_to_peak=x.peak_to_peak,
                      first_harmonic=x.first_harmonic, clearances=clearances, required_eccentricity=e_req,
                      required_eccentricity_min=float(best), push_azimuth=x.push_azimuth,
                      front_wall_azimuth=x.front_wall_azimuth, rear_wall_azimuth=x.rear_wall_azimuth,
                      film_push=film.lands * math.hypot(f_n, f_t) if regime != "free" else 0.0,
                      crush_margin=float(margin), non_guiding_gap=gap,
                      residual_peak_to_peak=x.residual_peak_to_peak)
