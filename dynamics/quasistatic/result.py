"""Result of the quasi-static solve (docs/model.md §10) and the dynamic stage's initial state.

Sign conventions (all SI, global frame of docs/model.md §1):
- inner_displacement = (u_x, u_y, u_z) [m] of the inner-race centre and inner_tilt =
  (θ_x, θ_y) [rad] (small rotation vector), both measured from the centred position
  (axes coincident, groove curvature-centre planes coplanar) — so the clearance take-up
  is part of the displacement.
- Loads on the inner race: axial along +z, radial along +x, moment about +y. A positive
  θ_y moves the inner groove at azimuth ψ = 0 (+x) towards −z, so with +z thrust and a
  positive moment the balls near ψ = π (−x side) carry the most.
- Contact angles are signed (dynamics.contact.race convention): positive when the
  contact line carries a +z thrust on the inner race; a ball pressed against the other
  groove flanks reports negative angles.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np


@dataclass(frozen=True)
class QuasiStaticResult:
    """Quasi-static equilibrium of a ball bearing (docs/model.md §10). Arrays are per ball (Z,)."""

    converged: bool
    iterations: int  # Newton iterations on the inner race, all continuation/kinematic passes
    inner_displacement: np.ndarray  # (3,) [m]
    inner_tilt: np.ndarray  # (2,) [rad]
    azimuth: np.ndarray  # [rad], ball k at 2πk/Z from +x towards +y
    inner_load: np.ndarray  # [N]
    outer_load: np.ndarray  # [N]
    inner_contact_angle: np.ndarray  # [rad], signed
    outer_contact_angle: np.ndarray  # [rad], signed
    inner_deflection: np.ndarray  # Hertz approach δ_i [m] (negative: gap)
    outer_deflection: np.ndarray  # [m]
    max_pressure_inner: np.ndarray  # p_max [Pa]
    max_pressure_outer: np.ndarray  # [Pa]
    semi_major_inner: np.ndarray  # contact-ellipse semi-axis a along the groove [m]
    semi_major_outer: np.ndarray  # [m]
    truncation_margin_inner: np.ndarray  # r(θ_land − |α|) − a [m]; < 0: ellipse cut by land; NaN: no shoulder
    truncation_margin_outer: np.ndarray  # [m]
    stiffness: np.ndarray  # (5, 5), order (dx, dy, dz, rx, ry): N/m, N/rad, N·m/m, N·m/rad
    ball_positions: np.ndarray  # (Z, 3) global [m]
    ball_angular_velocity: np.ndarray  # (Z, 3) global [rad/s], pure rolling + race control
    ball_orbital_speed: np.ndarray  # (Z,) [rad/s], each ball's own pure-rolling ω_m
    cage_speed: float  # mean ball orbital speed [rad/s]
    inner_speed: float  # [rad/s] about +z
    outer_speed: float  # [rad/s]
    applied_load: np.ndarray  # (5,) (F_x, F_y, F_z [N], M_x, M_y [N·m]) on the inner race
    residual: float  # max |load residual| at the solution [N, N·m / (d_i/2)]
    stiffness_asymmetry: float  # ‖K − Kᵀ‖ / ‖K‖ (non-zero because k_h depends on α)
    warnings: tuple[str, ...] = field(default_factory=tuple)

    @property
    def ball_count(self) -> int:
        return int(self.azimuth.shape[0])

    def to_json_dict(self) -> dict:
        """The `bearingsim quasistatic --json` object of docs/scenes.md (NaN → null)."""

        def num(x: float):
            x = float(x)
            return x if math.isfinite(x) else None

        balls = [
            {
                "azimuth": num(self.azimuth[k]),
                "inner_load": num(self.inner_load[k]),
                "outer_load": num(self.outer_load[k]),
                "inner_contact_angle": num(self.inner_contact_angle[k]),
                "outer_contact_angle": num(self.outer_contact_angle[k]),
                "max_pressure_inner": num(self.max_pressure_inner[k]),
                "max_pressure_outer": num(self.max_pressure_outer[k]),
                "truncation_margin_inner": num(self.truncation_margin_inner[k]),
                "truncation_margin_outer": num(self.truncation_margin_outer[k]),
            }
            for k in range(self.ball_count)
        ]
        return {
            "inner_race": {
                "displacement": [num(v) for v in self.inner_displacement],
                "tilt": [num(v) for v in self.inner_tilt],
            },
            "balls": balls,
            "stiffness": [[num(v) for v in row] for row in self.stiffness],
            "stiffness_order": ["dx", "dy", "dz", "rx", "ry"],
            "cage_speed": num(self.cage_speed),
            "converged": bool(self.converged),
            "iterations": int(self.iterations),
            "warnings": list(self.warnings),
            "units": {
                "displacement": "m", "tilt": "rad", "azimuth": "rad", "load": "N",
                "contact_angle": "rad", "pressure": "Pa", "truncation_margin": "m",
                "stiffness": "N/m, N/rad, N m/m, N m/rad", "cage_speed": "rad/s",
            },
        }


def tilt_rotation_matrix(tilt: np.ndarray) -> np.ndarray:
    """Rotation matrix of the rotation vector (θ_x, θ_y, 0) (Rodrigues' formula)."""
    theta = np.array([tilt[0], tilt[1], 0.0])
    angle = float(np.linalg.norm(theta))
    if angle == 0.0:
        return np.eye(3)
    k = theta / angle
    kx = np.array([[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]])
    return np.eye(3) + math.sin(angle) * kx + (1.0 - math.cos(angle)) * kx @ kx


def initial_state(result: QuasiStaticResult, geometry=None) -> dict[str, np.ndarray | float]:
    """Initial state of the dynamic stage from a quasi-static solution (docs/model.md §10).

    Positions from the solution; velocities from pure rolling with every ball orbiting
    at the cage speed ω_c (mean of the balls' own pure-rolling orbital speeds), each
    ball spinning with its own pure-rolling angular velocity. Plain arrays, SI:
    ball_positions (Z,3) [m], ball_velocities (Z,3) [m/s] = ω_c e_z × x_b,
    ball_angular_velocities (Z,3) [rad/s], cage_angular_speed [rad/s] (about +z),
    inner_race_displacement (3) [m], inner_race_tilt (2) [rad], inner_race_rotation
    (3×3, rotation vector (θ_x, θ_y, 0)), inner_race_angular_velocity (3) [rad/s],
    outer_race_angular_velocity (3) [rad/s]. geometry (optional BearingGeometry) is only
    checked for consistency (same ball count).
    """
    if geometry is not None and geometry.ball_count != result.ball_count:
        raise ValueError(f"geometry has {geometry.ball_count} balls but the quasi-static result has "
                         f"{result.ball_count}: pass the geometry the result was solved for")
    x = np.array(result.ball_positions, dtype=float)
    w_c = float(result.cage_speed)
    velocities = np.column_stack([-w_c * x[:, 1], w_c * x[:, 0], np.zeros(len(x))])
    return {
        "ball_positions": x,
        "ball_velocities": velocities,
        "ball_angular_velocities": np.array(result.ball_angular_velocity, dtype=float),
        "cage_angular_speed": w_c,
        "inner_race_displacement": np.array(result.inner_displacement, dtype=float),
        "inner_race_tilt": np.array(result.inner_tilt, dtype=float),
        "inner_race_rotation": tilt_rotation_matrix(np.asarray(result.inner_tilt)),
        "inner_race_angular_velocity": np.array([0.0, 0.0, result.inner_speed]),
        "outer_race_angular_velocity": np.array([0.0, 0.0, result.outer_speed]),
    }
