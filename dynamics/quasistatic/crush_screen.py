"""Cage crush screen: from the quasi-static load distribution, where the balls must push the
cage and whether its guide clearance can absorb them (docs/model.md §10.1, M.115–M.118).

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

from bearingsim.dynamics.journal.hybrid import ocvirk_force


@dataclass(frozen=True)
class CageScreen:
    """Result of `crush_screen` (SI units; azimuths in rad from +x towards +y)."""

    regime: str  # "free" | "pressed" | "crushed"
    excursion: np.ndarray  # s(psi_k) per ball [m], + ahead of a rigid cage at the mean speed
    excursion_peak_to_peak: float  # s_pp [m]
    first_harmonic: float  # s1 [m]
    pocket_clearance: float  # c_p = d_p - D [m]
    guide_clearance: float  # C [m]
    required_eccentricity: float  # e_req = max(0, s1 - c_p / 2) [m]
    push_azimuth: float  # direction the balls push the cage [rad]
    front_wall_azimuth: float  # orbital position where balls lead the cage most [rad]
    rear_wall_azimuth: float  # where they lag most [rad]
    film_push: float  # land film force at e_req (pressed) or at e = C (crushed) [N]
    crush_margin: float  # (C - e_req) / C: 1 free room, 0 at the crush threshold, < 0 crushed

    def to_json_dict(self) -> dict:
        deg = math.degrees
        return {
            "regime": self.regime,
            "excursion_peak_to_peak": self.excursion_peak_to_peak,
            "excursion_first_harmonic": self.first_harmonic,
            "pocket_clearance": self.pocket_clearance,
            "guide_clearance": self.guide_clearance,
            "required_eccentricity": self.required_eccentricity,
            "required_eccentricity_ratio": self.required_eccentricity / self.guide_clearance,
            "crush_margin": self.crush_margin,
            "push_azimuth_deg": deg(self.push_azimuth) % 360.0,
            "front_wall_azimuth_deg": deg(self.front_wall_azimuth) % 360.0,
            "rear_wall_azimuth_deg": deg(self.rear_wall_azimuth) % 360.0,
            "film_push": self.film_push,
            "excursion_per_ball": [float(x) for x in self.excursion],
            "units": {"lengths": "m", "film_push": "N", "azimuths": "deg"},
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


def crush_screen(azimuth, orbital_speed, cage_speed: float, *, pitch_radius: float, pocket_clearance: float,
                 guide_clearance: float, land_radius: float, land_length: float, lands: int,
                 eps0: float, viscosity: float) -> CageScreen:
    """The screen of M.115–M.118 (module docstring). `orbital_speed` [rad/s] per ball at its
    `azimuth` [rad]; lengths [m], viscosity [Pa s], cage_speed [rad/s]. Film force at e_req: the static short
    bearing with clearance C (1 + eps0) (the hybrid law of docs/model.md §8) and omega the
    cage speed (outer race fixed)."""
    s_balls, grid, s = orbital_excursion(azimuth, orbital_speed, pitch_radius)
    s_pp = float(s.max() - s.min())
    # first harmonic s ~ a1 cos psi + b1 sin psi; a cage shift d moves pocket psi by d . e_t(psi)
    a1 = 2.0 * np.mean(s * np.cos(grid))
    b1 = 2.0 * np.mean(s * np.sin(grid))
    s1 = math.hypot(a1, b1)
    front = float(grid[np.argmax(s)])
    rear = float(grid[np.argmin(s)])
    # -dx sin psi + dy cos psi = a1 cos psi + b1 sin psi  ->  d along (-b1, a1)
    push = math.atan2(a1, -b1)
    e_req = max(0.0, s1 - 0.5 * pocket_clearance) if s_pp > pocket_clearance else 0.0
    C = guide_clearance
    regime = "free" if s_pp <= pocket_clearance else ("pressed" if e_req <= C else "crushed")
    c_film = C * (1.0 + eps0)
    eps_h = min(e_req, C) / c_film
    f_n, f_t, _, _ = ocvirk_force(eps_h, viscosity, cage_speed, land_radius, land_length / lands, c_film)
    film_push = lands * math.hypot(f_n, f_t) if regime != "free" else 0.0
    return CageScreen(regime=regime, excursion=s_balls, excursion_peak_to_peak=s_pp, first_harmonic=s1,
                      pocket_clearance=pocket_clearance, guide_clearance=C, required_eccentricity=e_req,
                      push_azimuth=push, front_wall_azimuth=front, rear_wall_azimuth=rear,
                      film_push=film_push, crush_margin=(C - e_req) / C)
