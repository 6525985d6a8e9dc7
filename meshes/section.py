"""Meridian sections of axisymmetric bodies: triangles in the (r, z) half-plane.

An axisymmetric assembly (docs/model.md §3) is meshed as its section: gmsh meshes a set of
(r, z) rectangles, fragmented so that every interface is conforming, with the element size
graded towards the corners of the section (the circular edges of the body, where re-entrant
corners and material junctions make the stresses singular). `fe_model.axisymmetric` solves
on it with Fourier modes round the axis; `revolve_to_tets` turns it into a 3-D tetrahedral
`MeshData` (for cross-checks with the 3-D solver) and `revolved_points` / `revolved_wedges`
give the volume mesh of the `.vtu` artefacts.

Like `MeshData`, a section is plain arrays with named groups, saved as `.npz`.
"""

from __future__ import annotations

import math
import pathlib
from dataclasses import dataclass, field

import numpy as np

from .mesh_data import MeshData, facet_lookup, load_grouped_mesh, match_facets, save_grouped_mesh

Rectangle = tuple[float, float, float, float]  # r0, r1, z0, z1 [m]


@dataclass(frozen=True)
class SectionMesh:
    """Linear triangles of a meridian section with named parts and boundary lines.

    points: (N, 2) float64 [r, z] in m, r >= 0; triangles: (E, 3) int64, counter-clockwise
    in the (r, z) plane; volumes maps a part name to the indices of its triangles (a part of
    the section is a volume of revolution); surfaces maps a group name to its boundary
    segments as (F, 2) vertex indices (a segment revolves into a surface).
    """

    points: np.ndarray
    triangles: np.ndarray
    volumes: dict[str, np.ndarray] = field(default_factory=dict)
    surfaces: dict[str, np.ndarray] = field(default_factory=dict)

    @property
    def n_nodes(self) -> int:
        return int(self.points.shape[0])

    @property
    def n_elements(self) -> int:
        return int(self.triangles.shape[0])

    def to_skfem(self):
        """skfem `MeshTri` (x = r, y = z) with `subdomains` and `boundaries` (facets are
        the mesh's edges, matched by their sorted vertex pairs; interior lines work too)."""
        from skfem import MeshTri

        mesh = MeshTri(np.ascontiguousarray(self.points.T), np.ascontiguousarray(self.triangles.T))
        edge_index = facet_lookup(mesh.facets)
        boundaries = {name: match_facets(name, segments, edge_index, "segment", "an edge of the section mesh")
                      for name, segments in self.surfaces.items()}
        subdomains = {name: np.asarray(idx, dtype=np.int64) for name, idx in self.volumes.items()}
        return mesh.with_subdomains(subdomains).with_boundaries(boundaries)

    def save(self, path: pathlib.Path) -> None:
        """Write atomically to `path` (.npz)."""
        save_grouped_mesh(path, self.points, "triangles", self.triangles, self.volumes, self.surfaces)

    @classmethod
    def load(cls, path: pathlib.Path) -> "SectionMesh":
        return cls(*load_grouped_mesh(path, "triangles"))


def mesh_rectangles(
    parts: dict[str, list[Rectangle]],
    lines: dict[str, callable],
    mesh_size: float,
    corner_size: float,
    reach: float,
    tol: float,
) -> SectionMesh:
    """Mesh a union of (r, z) rectangles with gmsh (fragmented: conforming interfaces).

    Element size `mesh_size` [m], graded linearly to `corner_size` at every corner of the
    fragmented geometry: h(d) = mesh_size * clip(d / reach, corner_size / mesh_size, 1) with
    d the distance to the nearest corner, so for a fixed `reach` and ratio the meshes of
    different `mesh_size` are a self-similar family (h(x) = mesh_size * f(x)).
    `lines` maps a surface-group name to a rule on a boundary line ("r", r, z0, z1) (a
    cylinder) or ("z", z, r0, r1) (a plane annulus); every group must match a line.
    """
    from .gmsh_io import gmsh_session

    with gmsh_session("section") as gmsh:
        occ = gmsh.model.occ
        tags, part_of = [], []
        for name, rects in parts.items():
            for r0, r1, z0, z1 in rects:
                tags.append((2, occ.addRectangle(r0, z0, 0.0, r1 - r0, z1 - z0)))
                part_of.append(name)
        _, children = occ.fragment(tags, []) if len(tags) > 1 else ([], [tags])  # one shape: nothing to cut
        occ.synchronize()
        owner: dict[int, str] = {}
        for name, kids in zip(part_of, children):  # fragment keeps the input order
            for dim, tag in kids:
                if dim == 2:
                    owner[tag] = name
        gmsh.option.setNumber("Mesh.MeshSizeMax", mesh_size)
        gmsh.option.setNumber("Mesh.MeshSizeMin", 0.5 * min(corner_size, mesh_size))
        gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 0)
        gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 0)
        if corner_size < mesh_size:
            f = gmsh.model.mesh.field
            distance = f.add("Distance")
            f.setNumbers(distance, "PointsList", [tag for _, tag in gmsh.model.getEntities(0)])
            threshold = f.add("Threshold")
            f.setNumber(threshold, "InField", distance)
            f.setNumber(threshold, "SizeMin", corner_size)
            f.setNumber(threshold, "SizeMax", mesh_size)
            f.setNumber(threshold, "DistMin", reach * corner_size / mesh_size)
            f.setNumber(threshold, "DistMax", reach)
            f.setAsBackgroundMesh(threshold)
            gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)
        else:
            gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 1)
        gmsh.model.mesh.generate(2)

        node_tags, coords, _ = gmsh.model.mesh.getNodes()
        index = np.full(int(node_tags.max()) + 1, -1, dtype=np.int64)
        index[node_tags.astype(np.int64)] = np.arange(node_tags.size)
        points = coords.reshape(-1, 3)[:, :2].copy()
        blocks, block_part = [], []
        for _, tag in gmsh.model.getEntities(2):
            types, _, nodes = gmsh.model.mesh.getElements(2, tag)
            for t, n in zip(types, nodes):
                if t == 2:  # 3-node triangle
                    blocks.append(index[n.astype(np.int64)].reshape(-1, 3))
                    block_part.append(owner[tag])
        triangles = np.concatenate(blocks)
        part = np.concatenate([np.full(len(b), i) for i, b in enumerate(blocks)])
        volumes = {}
        for name in parts:
            pick = [i for i, p in enumerate(block_part) if p == name]
            volumes[name] = np.flatnonzero(np.isin(part, pick))
        found = {name: [] for name in lines}
        for _, tag in gmsh.model.getEntities(1):
            x0, y0, _, x1, y1, _ = gmsh.model.getBoundingBox(1, tag)
            if math.isclose(x0, x1, abs_tol=tol):
                kind = ("r", 0.5 * (x0 + x1), y0, y1)
            elif math.isclose(y0, y1, abs_tol=tol):
                kind = ("z", 0.5 * (y0 + y1), x0, x1)
            else:
                continue
            types, _, nodes = gmsh.model.mesh.getElements(1, tag)
            segments = index[nodes[0].astype(np.int64)].reshape(-1, 2)
            for name, rule in lines.items():
                if rule(kind):
                    found[name].append(segments)
    for name, segs in found.items():
        if not segs:
            raise RuntimeError(f"section has no boundary line for group {name!r}; check the [fe] dimensions")
    surfaces = {name: np.concatenate(segs) for name, segs in found.items()}
    return _tidy(points, triangles, volumes, surfaces)


def _tidy(points, triangles, volumes, surfaces) -> SectionMesh:
    """Drop nodes no triangle uses and orient every triangle counter-clockwise in (r, z)."""
    used = np.unique(triangles)
    new_index = np.full(points.shape[0], -1, dtype=np.int64)
    new_index[used] = np.arange(used.size)
    triangles = new_index[triangles]
    surfaces = {k: new_index[v] for k, v in surfaces.items()}
    for name, segs in surfaces.items():
        if (segs < 0).any():
            raise ValueError(f"surface group {name!r} is not on the section mesh")
    points = points[used].copy()
    d1 = points[triangles[:, 1]] - points[triangles[:, 0]]
    d2 = points[triangles[:, 2]] - points[triangles[:, 0]]
    flip = d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0] < 0.0  # clockwise in (r, z)
    triangles[flip] = triangles[flip][:, [0, 2, 1]]
    return SectionMesh(points, triangles, volumes, surfaces)


def revolved_points(points: np.ndarray, sectors: int) -> np.ndarray:
    """(sectors * N, 3) Cartesian points of the section's nodes at the angles 2 pi k / sectors
    (node i of layer k is row k N + i)."""
    theta = 2.0 * np.pi * np.arange(sectors) / sectors
    out = np.empty((sectors, points.shape[0], 3))
    out[:, :, 0] = points[None, :, 0] * np.cos(theta)[:, None]
    out[:, :, 1] = points[None, :, 0] * np.sin(theta)[:, None]
    out[:, :, 2] = points[None, :, 1]
    return out.reshape(-1, 3)


def revolved_wedges(triangles: np.ndarray, n_points: int, sectors: int) -> np.ndarray:
    """(sectors * E, 6) VTK wedges between consecutive layers of `revolved_points`, sector
    by sector: a counter-clockwise (r, z) triangle faces -e_theta, away from the next layer,
    which is VTK's orientation of the base (0, 1, 2) of a wedge."""
    k = np.arange(sectors)[:, None, None]
    lower = triangles[None, :, :] + k * n_points
    upper = triangles[None, :, :] + ((k + 1) % sectors) * n_points
    return np.concatenate([lower, upper], axis=2).reshape(-1, 6)


def revolve_to_tets(section: SectionMesh, sectors: int) -> MeshData:
    """The body of revolution as linear tetrahedra: each triangle swept through each sector is
    a prism cut into three tetrahedra. Every quadrilateral face is cut along the diagonal from
    its lower-numbered node in the lower layer, the same rule on both sides, so neighbouring
    prisms are conforming (Dompierre et al., Proc. 8th Int. Meshing Roundtable, 1999).
    Faces are flat, so cylinders become polygons: a cross-check, not an accurate model, at
    small `sectors`."""
    n = section.n_nodes
    points = revolved_points(section.points, sectors)
    a, b, c = np.sort(section.triangles, axis=1).T
    k = np.arange(sectors)[:, None]
    lo, hi = k * n, ((k + 1) % sectors) * n
    prisms = [(a + lo, b + lo, c + lo, c + hi), (a + lo, b + lo, b + hi, c + hi), (a + lo, a + hi, b + hi, c + hi)]
    tets = np.stack([np.stack(t, axis=-1) for t in prisms], axis=2).reshape(-1, 4)  # (k, tri, 3) order
    m = section.n_elements
    volumes = {}
    for name, tris in section.volumes.items():
        e = (np.arange(sectors)[:, None, None] * m + np.asarray(tris)[None, :, None]) * 3 + np.arange(3)
        volumes[name] = np.sort(e.ravel())
    surfaces = {}
    for name, segments in section.surfaces.items():
        i, j = np.sort(segments, axis=1).T
        quads = [(i + lo, j + lo, j + hi), (i + lo, i + hi, j + hi)]  # diagonal i(lower) - j(upper)
        surfaces[name] = np.stack([np.stack(t, axis=-1) for t in quads], axis=2).reshape(-1, 3)
    p = points[tets]
    volume6 = np.einsum("ij,ij->i", np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]), p[:, 3] - p[:, 0])
    tets[volume6 < 0.0] = tets[volume6 < 0.0][:, [1, 0, 2, 3]]
    return MeshData(points, tets, volumes, surfaces)
