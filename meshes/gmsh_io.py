"""gmsh session handling and mesh extraction into `MeshData`.

gmsh is imported inside the functions (docs/contributing.md §6): importing it loads X11/GL
libraries that a bare machine may lack (see pipeline/machine/system_libraries.py).
"""

from __future__ import annotations

import contextlib
import math
from typing import Iterator

import numpy as np

from .mesh_data import MeshData

GMSH_TET4 = 4
GMSH_TRI3 = 2


@contextlib.contextmanager
def gmsh_session(model_name: str) -> Iterator[object]:
    """Initialise gmsh for deterministic meshing, yield the module, always finalise.

    The parallel 3-D mesher is not deterministic, so one thread and a fixed algorithm:
    a cached mesh must be the mesh the same inputs would produce again.
    """
    import gmsh

    gmsh.initialize(interruptible=False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.option.setNumber("General.Verbosity", 1)
        gmsh.option.setNumber("General.NumThreads", 1)
        gmsh.option.setNumber("Mesh.MaxNumThreads1D", 1)
        gmsh.option.setNumber("Mesh.MaxNumThreads2D", 1)
        gmsh.option.setNumber("Mesh.MaxNumThreads3D", 1)
        gmsh.option.setNumber("Mesh.Algorithm", 6)  # Frontal-Delaunay (2-D)
        gmsh.option.setNumber("Mesh.Algorithm3D", 1)  # Delaunay (3-D)
        gmsh.option.setNumber("Mesh.ElementOrder", 1)  # P2 fields live on straight tets
        gmsh.model.add(model_name)
        yield gmsh
    finally:
        gmsh.finalize()


def set_uniform_size(gmsh, size: float) -> None:
    """Characteristic element size `size` [m] everywhere (curvature does not refine)."""
    gmsh.option.setNumber("Mesh.MeshSizeMax", size)
    gmsh.option.setNumber("Mesh.MeshSizeMin", 0.05 * size)
    gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 0)
    gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 0)
    gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 1)


def grade_towards_curves(gmsh, size: float, refinements: list[tuple[list[int], float]], reach: float) -> None:
    """Background size field: `ratio * size` on each group of curves, growing linearly to
    `size` at `reach * size` from them; where zones overlap the smallest size wins.

    A reach of about one size makes the element size grow like the distance to the edge,
    the grading that edge singularities need, without filling the volume with small tets.
    """
    field = gmsh.model.mesh.field
    thresholds = []
    for curves, ratio in refinements:
        distance = field.add("Distance")
        field.setNumbers(distance, "CurvesList", curves)
        field.setNumber(distance, "Sampling", 400)
        threshold = field.add("Threshold")
        field.setNumber(threshold, "InField", distance)
        field.setNumber(threshold, "SizeMin", ratio * size)
        field.setNumber(threshold, "SizeMax", size)
        field.setNumber(threshold, "DistMin", 0.5 * ratio * size)
        field.setNumber(threshold, "DistMax", reach * size)
        thresholds.append(threshold)
    smallest = field.add("Min")
    field.setNumbers(smallest, "FieldsList", thresholds)
    field.setAsBackgroundMesh(smallest)
    gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)


def extract_mesh(gmsh) -> MeshData:
    """Read nodes, tetrahedra and all physical groups from the current gmsh model."""
    tags, coords, _ = gmsh.model.mesh.getNodes()
    tag_to_index = np.full(int(tags.max()) + 1, -1, dtype=np.int64)
    tag_to_index[tags.astype(np.int64)] = np.arange(tags.size)
    points = coords.reshape(-1, 3)

    tet_blocks, entity_range, start = [], {}, 0
    for _, entity in gmsh.model.getEntities(3):
        nodes = _elements_of(gmsh, 3, entity, GMSH_TET4, 4)
        tet_blocks.append(tag_to_index[nodes])
        entity_range[entity] = (start, start + nodes.shape[0])
        start += nodes.shape[0]
    tets = np.concatenate(tet_blocks)

    volumes, surfaces = {}, {}
    for dim, group in gmsh.model.getPhysicalGroups():
        name = gmsh.model.getPhysicalName(dim, group)
        entities = gmsh.model.getEntitiesForPhysicalGroup(dim, group)
        if dim == 3:
            volumes[name] = np.concatenate(
                [np.arange(*entity_range[e], dtype=np.int64) for e in entities]
            )
        elif dim == 2:
            surfaces[name] = np.concatenate(
                [tag_to_index[_elements_of(gmsh, 2, e, GMSH_TRI3, 3)] for e in entities]
            )
    return _drop_unused_nodes(points, tets, volumes, surfaces)


def _elements_of(gmsh, dim: int, entity: int, element_type: int, n: int) -> np.ndarray:
    types, _, node_tags = gmsh.model.mesh.getElements(dim, entity)
    for t, nodes in zip(types, node_tags):
        if t == element_type:
            return nodes.astype(np.int64).reshape(-1, n)
    return np.empty((0, n), dtype=np.int64)


def _drop_unused_nodes(points, tets, volumes, surfaces) -> MeshData:
    """Renumber so that every point belongs to a tetrahedron (gmsh may keep others)."""
    used = np.unique(tets)
    new_index = np.full(points.shape[0], -1, dtype=np.int64)
    new_index[used] = np.arange(used.size)
    surfaces = {k: new_index[v] for k, v in surfaces.items()}
    for name, tris in surfaces.items():
        if (tris < 0).any():
            raise ValueError(f"surface group {name!r} is not on the volume mesh")
    return MeshData(points[used].copy(), new_index[tets], volumes, surfaces)


def classify_surface(gmsh, tag: int, tol: float) -> tuple:
    """Describe an OCC surface by sampling it: ("cylinder", R, z0, z1), ("plane_z", z, r0, r1)
    or ("other",). Bounding boxes alone cannot tell a cylinder from an annulus."""
    (u0, v0), (u1, v1) = gmsh.model.getParametrizationBounds(2, tag)
    uu, vv = np.meshgrid(np.linspace(u0, u1, 5), np.linspace(v0, v1, 5))
    params = np.column_stack([uu.ravel(), vv.ravel()]).ravel()
    xyz = np.asarray(gmsh.model.getValue(2, tag, params)).reshape(-1, 3)
    r = np.hypot(xyz[:, 0], xyz[:, 1])
    z = xyz[:, 2]
    # the parametrisation may extend past trimmed edges: use the bounding box for extents
    x0, y0, zb0, x1, y1, zb1 = gmsh.model.getBoundingBox(2, tag)
    if np.ptp(r) < tol and np.ptp(z) > tol:
        return ("cylinder", float(np.mean(r)), zb0, zb1)
    if np.ptp(z) < tol:
        r_out = max(abs(x0), abs(x1), abs(y0), abs(y1))
        r_in = _plane_inner_radius(gmsh, tag, r_out)
        return ("plane_z", float(np.mean(z)), r_in, r_out)
    return ("other",)


def _plane_inner_radius(gmsh, tag: int, r_out: float) -> float:
    """Inner radius of an annular face: the smallest radius among its boundary curves."""
    r_in = r_out
    for _, curve in gmsh.model.getBoundary([(2, tag)], oriented=False):
        x0, y0, _, x1, y1, _ = gmsh.model.getBoundingBox(1, abs(curve))
        r_in = min(r_in, max(abs(x0), abs(x1), abs(y0), abs(y1)))
    return r_in


def close(a: float, b: float, tol: float) -> bool:
    return math.isclose(a, b, abs_tol=tol)
