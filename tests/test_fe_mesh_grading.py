"""Graded housing mesh: the singular edges of the axial load path get the finest tets."""

import numpy as np

from bearingsim.fe_model import FEConfig, RingSeat
from bearingsim.meshes import build_housing_mesh
from bearingsim.meshes.housing import SINGULAR_EDGE_FACTOR


def _shortest_edge_near(mesh, radius: float, z: float, reach: float) -> float:
    """Shortest tetrahedron edge [m] among tets with a vertex within `reach` of the circle (radius, z)."""
    p = mesh.points
    near = np.hypot(np.hypot(p[:, 0], p[:, 1]) - radius, p[:, 2] - z) < reach
    tets = mesh.tets[near[mesh.tets].any(axis=1)]
    pairs = [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)]
    return min(np.linalg.norm(p[tets[:, i]] - p[tets[:, j]], axis=1).min() for i, j in pairs)


def test_singular_edges_are_refined_beyond_the_other_edges():
    """Web/shell corner at (seat radius, support b end) vs the inner-ring race corner:
    the sizes asked of gmsh are SINGULAR_EDGE_FACTOR * 0.25 * h and 0.25 * h."""
    config, ring = FEConfig(), RingSeat()
    h, ratio = 0.04, 0.25
    mesh = build_housing_mesh(config.housing_geometry(ring), h, ratio)
    seat_radius = 0.5 * ring.outer_outside_diameter
    web_corner = _shortest_edge_near(mesh, seat_radius, config.support_b_position + 0.5 * config.support_width, 0.002)
    race_corner = _shortest_edge_near(mesh, 0.5 * ring.inner_outer_diameter, 0.5 * ring.width, 0.002)
    assert web_corner < 1.5 * SINGULAR_EDGE_FACTOR * ratio * h
    assert race_corner > 0.5 * SINGULAR_EDGE_FACTOR * ratio * h
    assert web_corner < race_corner
