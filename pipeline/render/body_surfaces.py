"""The bodies of the bearing as surfaces, as plain arrays (the ParaView series draws them).

Races are surfaces of revolution of their axial profile (docs/model.md §2): the groove arc of
radius r about the circle of curvature centres, and the lands at the shoulder diameter where
the scene gives it; the cage is a hollow cylinder (mean diameter ± half its radial
thickness, its width). Every surface is a grid of quadrilaterals over (azimuth, profile),
azimuth from +x towards +y, in the body's own frame: z along its axis, the groove plane at
z = 0. SI units (m).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

PROFILE_POINTS = 16  # along a race's axial profile
GROOVE_HALF_ANGLE = math.radians(40.0)  # extent of a groove drawn without a shoulder diameter


@dataclass(frozen=True)
class RevolvedSurface:
    """A surface of revolution: points (n_theta * n_profile, 3) and quads (n_cells, 4);
    `cell_azimuth` [rad] and `cell_z` [m] are each cell's centre, for fields over it."""

    points: np.ndarray
    quads: np.ndarray
    cell_azimuth: np.ndarray
    cell_z: np.ndarray


def revolve(radius: np.ndarray, z: np.ndarray, n_theta: int) -> RevolvedSurface:
    """The profile (radius[k], z[k]) revolved about +z in `n_theta` sectors (closed round)."""
    radius, z = np.asarray(radius, dtype=float), np.asarray(z, dtype=float)
    theta = np.arange(n_theta) * (2.0 * math.pi / n_theta)
    k = len(radius)
    points = np.stack([np.outer(np.cos(theta), radius), np.outer(np.sin(theta), radius),
                       np.broadcast_to(z, (n_theta, k))], axis=-1).reshape(-1, 3)
    i, j = np.meshgrid(np.arange(n_theta), np.arange(k - 1), indexing="ij")
    i1 = (i + 1) % n_theta
    quads = np.stack([i * k + j, i1 * k + j, i1 * k + j + 1, i * k + j + 1], axis=-1).reshape(-1, 4)
    azimuth = (np.arange(n_theta) + 0.5) * (2.0 * math.pi / n_theta)
    cell_azimuth = np.repeat(azimuth, k - 1)
    cell_z = np.tile(0.5 * (z[:-1] + z[1:]), n_theta)
    return RevolvedSurface(points, quads, cell_azimuth, cell_z)


def _race_profile(center_radius: float, groove_radius: float, shoulder_radius: float | None,
                  half_width: float | None, sign: float) -> tuple[np.ndarray, np.ndarray]:
    """(radius, z) along a race's bore (outer, sign = +1) or outside (inner, sign = -1):
    groove r = d/2 + sign r_g cos(alpha), then the lands out to the ring's half width."""
    if shoulder_radius is not None:
        edge = math.acos(min(1.0, max(-1.0, sign * (shoulder_radius - center_radius) / groove_radius)))
    else:
        edge = GROOVE_HALF_ANGLE
    alpha = np.linspace(-edge, edge, PROFILE_POINTS)
    radius = center_radius + sign * groove_radius * np.cos(alpha)
    z = groove_radius * np.sin(alpha)
    if shoulder_radius is not None and half_width is not None and half_width > z[-1]:
        radius = np.r_[shoulder_radius, radius, shoulder_radius]
        z = np.r_[-half_width, z, half_width]
    return radius, z


def outer_race_surface(bearing, n_theta: int, cage=None) -> RevolvedSurface:
    """The outer race's bore: groove and lands (the guiding land of an outer-guided cage).
    With a `cage`, the lands are split at the cage's edges (z = ±w_c/2), so that the cells
    of the cage's land overlap are exactly those between the groove edge and w_c/2."""
    shoulder = 0.5 * bearing.outer_shoulder_diameter if bearing.outer_shoulder_diameter else None
    half_width = 0.5 * bearing.width if bearing.width else None
    r, z = _race_profile(0.5 * bearing.outer_groove_center_diameter, bearing.outer_groove_radius,
                         shoulder, half_width, +1.0)
    if cage is not None and shoulder is not None and half_width is not None:
        edge = 0.5 * cage.width
        if z[-2] < edge < z[-1]:  # inside the land
            r = np.r_[r[0], shoulder, r[1:-1], shoulder, r[-1]]
            z = np.r_[z[0], -edge, z[1:-1], edge, z[-1]]
    return revolve(r, z, n_theta)


def inner_race_surface(bearing, n_theta: int) -> RevolvedSurface:
    """The inner race's outside: groove and lands."""
    shoulder = 0.5 * bearing.inner_shoulder_diameter if bearing.inner_shoulder_diameter else None
    half_width = 0.5 * bearing.width if bearing.width else None
    r, z = _race_profile(0.5 * bearing.inner_groove_center_diameter, bearing.inner_groove_radius,
                         shoulder, half_width, -1.0)
    return revolve(r, z, n_theta)


def cage_surface(cage, n_theta: int) -> RevolvedSurface:
    """The cage ring: outside, side faces and bore as one closed profile."""
    r_in, r_out = 0.5 * (cage.mean_diameter - cage.radial_thickness), 0.5 * (cage.mean_diameter + cage.radial_thickness)
    h = 0.5 * cage.width
    return revolve(np.array([r_in, r_out, r_out, r_in, r_in]), np.array([-h, -h, h, h, -h]), n_theta)


def axis_rotation(axis: np.ndarray) -> np.ndarray:
    """The rotation matrix taking +z onto the unit vector `axis` (smallest rotation)."""
    a = np.asarray(axis, dtype=float)
    a = a / np.linalg.norm(a)
    c = float(a[2])
    v = np.array([-a[1], a[0], 0.0])  # z × a
    if c > 1.0 - 1e-15:
        return np.eye(3)
    vx = np.array([[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]])
    return np.eye(3) + vx + vx @ vx / (1.0 + c)


def spin_rotation(angle: float) -> np.ndarray:
    """Rotation by `angle` [rad] about +z."""
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
