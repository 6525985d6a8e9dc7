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


def test_section_is_graded_to_its_corners():
    """Triangles touching a corner of the section are edge_refinement x mesh_size; the size
    grows back to mesh_size away from the corners (h = mesh_size * clip(d / reach, ratio, 1))."""
    from bearingsim.meshes.housing import CORNER_REACH, build_section_mesh, section_rectangles, thinnest_wall

    config, ring = FEConfig(), RingSeat()
    geometry = config.housing_geometry(ring)
    h, ratio = 0.01, 0.05
    section = build_section_mesh(geometry, h, ratio)
    p, t = section.points, section.triangles
    edges = np.max([np.linalg.norm(p[t[:, i]] - p[t[:, j]], axis=1) for i, j in ((0, 1), (1, 2), (0, 2))], axis=0)
    web_corner = np.array([0.5 * ring.outer_outside_diameter, config.support_b_position + 0.5 * config.support_width])
    distance = np.linalg.norm(p[t].mean(axis=1) - web_corner, axis=1)
    at_corner = edges[distance < ratio * h]
    assert at_corner.size and at_corner.max() < 2.0 * ratio * h
    reach = CORNER_REACH * thinnest_wall(geometry)
    corners = np.array([(r, z) for rects in section_rectangles(geometry).values()
                        for r0, r1, z0, z1 in rects for r in (r0, r1) for z in (z0, z1)])
    centroids = p[t].mean(axis=1)
    nearest = np.min(np.linalg.norm(centroids[:, None, :] - corners[None, :, :], axis=2), axis=1)
    far = edges[nearest > reach]
    assert far.size and np.median(far) > 0.7 * h
