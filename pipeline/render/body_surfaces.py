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


def _edge_angle(center_radius: float, groove_radius: float, shoulder_radius: float | None, sign: float) -> float:
    """Angle from the groove plane at which the groove meets a land of `shoulder_radius`."""
    if shoulder_radius is None:
        return GROOVE_HALF_ANGLE
    return math.acos(min(1.0, max(-1.0, sign * (shoulder_radius - center_radius) / groove_radius)))


def _race_profile(center_radius: float, groove_radius: float, shoulders: tuple[float, float] | None,
                  half_width: float | None, sign: float) -> tuple[np.ndarray, np.ndarray]:
    """(radius, z) along a race's bore (outer, sign = +1) or outside (inner, sign = -1):
    groove r = d/2 + sign r_g cos(alpha), then the lands out to the ring's half width.
    `shoulders`: the land radii on the side toward +z and toward -z (None: no lands)."""
    up, down = shoulders if shoulders is not None else (None, None)
    alpha = np.linspace(-_edge_angle(center_radius, groove_radius, down, sign),
                        _edge_angle(center_radius, groove_radius, up, sign), PROFILE_POINTS)
    radius = center_radius + sign * groove_radius * np.cos(alpha)
    z = groove_radius * np.sin(alpha)
    if shoulders is not None and half_width is not None and half_width > max(z[-1], -z[0]):
        radius = np.r_[down, radius, up]
        z = np.r_[-half_width, z, half_width]
    return radius, z


def _land_radii(bearing, ring: str) -> tuple[float, float] | None:
    pair = bearing.shoulders(ring)
    return None if pair is None else (0.5 * pair[0], 0.5 * pair[1])


def outer_race_surface(bearing, n_theta: int, cage=None) -> RevolvedSurface:
    """The outer race's bore: groove and lands (the guiding land of an outer-guided cage).
    With a `cage`, the lands are split at the cage's edges (z = ±w_c/2), so that the cells
    of the cage's land overlap are exactly those between the groove edge and w_c/2."""
    shoulders = _land_radii(bearing, "outer")
    half_width = 0.5 * bearing.width if bearing.width else None
    r, z = _race_profile(0.5 * bearing.outer_groove_center_diameter, bearing.outer_groove_radius,
                         shoulders, half_width, +1.0)
    return _split_at_cage(r, z, cage, shoulders, half_width, n_theta)


def _split_at_cage(r, z, cage, shoulders, half_width, n_theta) -> RevolvedSurface:
    """The profile revolved, its lands split at the cage's edges z = ±w_c/2 where they lie on them."""
    if cage is not None and shoulders is not None and half_width is not None:
        edge = 0.5 * cage.width
        if z[-2] < edge < z[-1] and z[0] < -edge < z[1]:  # inside both lands
            r = np.r_[r[0], shoulders[1], r[1:-1], shoulders[0], r[-1]]
            z = np.r_[z[0], -edge, z[1:-1], edge, z[-1]]
    return revolve(r, z, n_theta)


def inner_race_surface(bearing, n_theta: int, cage=None) -> RevolvedSurface:
    """The inner race's outside: groove and lands (the guiding land of an inner-guided cage;
    with a `cage`, split at its edges as `outer_race_surface` does)."""
    shoulders = _land_radii(bearing, "inner")
    half_width = 0.5 * bearing.width if bearing.width else None
    r, z = _race_profile(0.5 * bearing.inner_groove_center_diameter, bearing.inner_groove_radius,
                         shoulders, half_width, -1.0)
    return _split_at_cage(r, z, cage, shoulders, half_width, n_theta)


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
