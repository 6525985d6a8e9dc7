"""The engineer's own tetrahedral mesh, read with meshio (docs/housing-mesh.md).

Any format meshio reads whose regions have names: Gmsh `.msh` (physical groups, 4.1 or 2.2),
Abaqus `.inp` (`*ELSET`, `*NSET`, `*ELEMENT, ELSET=`), and others with cell or point sets.
Volume regions are sets of tetrahedra; a surface region is a set of triangles (the faces of
the tetrahedra) or a node set, which names the boundary faces whose three corners are all in
it (how Abaqus and ANSYS export a face-based set most simply). Linear (4-node) and quadratic
(10-node) tetrahedra; the mid-edge nodes of a quadratic mesh are kept (curved edges).

Like `MeshData`, an `ImportedMesh` is plain arrays in metres; `to_skfem` makes the skfem mesh
with `subdomains` and `boundaries` for fe_model. Errors name the file and what was found.
"""

from __future__ import annotations

import pathlib
from dataclasses import dataclass, field

import numpy as np

from .mesh_data import facet_lookup, match_facets

# local edges of a 10-node tetrahedron, in VTK's (= Abaqus C3D10's) order of its nodes 4..9;
# meshio gives every format's tetra10 in this order
TET10_EDGES = ((0, 1), (1, 2), (0, 2), (0, 3), (1, 3), (2, 3))
# a mid-edge node farther than this fraction of its edge's length from the edge's midpoint
# means a node order we do not understand (a curved edge of a sound mesh is far closer)
MIDSIDE_TOLERANCE = 0.25


class MeshReadError(ValueError):
    """The mesh file cannot be read, or holds no usable tetrahedra."""


@dataclass(frozen=True)
class ImportedMesh:
    """Tetrahedra with named regions, in metres.

    points: (N, 3); the corners of the tetrahedra are points 0 .. n_corners - 1, mid-edge nodes
    (quadratic meshes) follow. tets: (E, 4) corner indices; edge_nodes: (E, 6) mid-edge node of
    each local edge (TET10_EDGES order) or None. volumes: name -> tetrahedron indices;
    surfaces: name -> (F, 3) corner triangles; node_sets: name -> node indices (on the volume mesh).
    """

    points: np.ndarray
    tets: np.ndarray
    edge_nodes: np.ndarray | None = None
    volumes: dict[str, np.ndarray] = field(default_factory=dict)
    surfaces: dict[str, np.ndarray] = field(default_factory=dict)
    node_sets: dict[str, np.ndarray] = field(default_factory=dict)

    @property
    def n_corners(self) -> int:
        return int(self.tets.max()) + 1 if self.tets.size else 0

    @property
    def quadratic(self) -> bool:
        return self.edge_nodes is not None

    def region_names(self) -> list[str]:
        return sorted({*self.volumes, *self.surfaces, *self.node_sets})

    def to_skfem(self, order: int):
        """skfem mesh for elements of `order` with `subdomains` (volumes) and `boundaries`
        (surfaces and node sets): MeshTet2 with the file's mid-edge nodes for a quadratic
        mesh at order 2, else MeshTet1 of the corners (straight edges)."""
        from skfem import MeshTet1, MeshTet2

        corners = np.ascontiguousarray(self.points[: self.n_corners].T)
        mesh = MeshTet1(corners, np.ascontiguousarray(self.tets.T))
        if order == 2 and self.quadratic:
            mesh = MeshTet2(np.hstack([mesh.p, self._edge_positions(mesh)]), mesh.t)
        lookup = facet_lookup(mesh.facets)
        boundaries = {name: match_facets(name, tris, lookup, "triangle", "a face of the tetrahedra")
                      for name, tris in self.surfaces.items()}
        for name, nodes in self.node_sets.items():
            boundaries.setdefault(name, boundary_facets_of_nodes(mesh, nodes))
        subdomains = {name: np.asarray(idx, dtype=np.int64) for name, idx in self.volumes.items()}
        return mesh.with_subdomains(subdomains).with_boundaries(boundaries)

    def _edge_positions(self, mesh) -> np.ndarray:
        """(3, n_edges) position of each skfem edge's mid-edge node, from the file's nodes."""
        n = self.n_corners
        key = np.sort(mesh.edges, axis=0)
        order = np.argsort(key[0] * n + key[1])
        sorted_keys = (key[0] * n + key[1])[order]
        out = np.zeros((3, mesh.edges.shape[1]))
        for k, (a, b) in enumerate(TET10_EDGES):
            lo = np.minimum(self.tets[:, a], self.tets[:, b])
            hi = np.maximum(self.tets[:, a], self.tets[:, b])
            edge = order[np.searchsorted(sorted_keys, lo * n + hi)]
            out[:, edge] = self.points[self.edge_nodes[:, k]].T
        return out


def boundary_facets_of_nodes(mesh, nodes: np.ndarray) -> np.ndarray:
    """Boundary facets of `mesh` whose three corners are all in `nodes`; if there are none,
    the interior facets (a node set on an interface between two bodies)."""
    inside = np.zeros(mesh.nvertices, dtype=bool)
    corner_nodes = np.asarray(nodes, dtype=np.int64)
    inside[corner_nodes[corner_nodes < mesh.nvertices]] = True
    every = inside[mesh.facets].all(axis=0)
    on_boundary = np.zeros(mesh.facets.shape[1], dtype=bool)
    on_boundary[mesh.boundary_facets()] = True
    picked = np.flatnonzero(every & on_boundary)
    return picked if picked.size else np.flatnonzero(every)


def read_mesh(path: pathlib.Path, metres_per_unit: float = 1.0) -> ImportedMesh:
    """Read `path` with meshio; coordinates times `metres_per_unit` [m]."""
    import warnings

    import meshio

    path = pathlib.Path(path)
    if not path.is_file():
        raise MeshReadError(f"{path} does not exist or is not a file")
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            m = meshio.read(path)
    except Exception as exc:  # meshio raises many kinds (ReadError, KeyError, UnicodeDecodeError ...)
        raise MeshReadError(f"{path} cannot be read as a mesh ({type(exc).__name__}: {exc}); give a Gmsh .msh, "
                            "an Abaqus .inp or another format meshio reads, with named regions") from None
    cells = m.cells_dict
    kinds = [k for k in ("tetra", "tetra10") if k in cells]
    if not kinds:
        raise MeshReadError(f"{path} holds no tetrahedra (cells: {', '.join(sorted(cells)) or 'none'}); "
                            "bearingsim needs a mesh of 4- or 10-node tetrahedra")
    if len(kinds) == 2:
        raise MeshReadError(f"{path} mixes 4- and 10-node tetrahedra ({len(cells['tetra'])} and "
                            f"{len(cells['tetra10'])}); export the mesh at one order")
    kind = kinds[0]
    points = np.asarray(m.points, dtype=float)
    if points.ndim != 2 or points.shape[1] != 3:
        raise MeshReadError(f"{path}: points have {points.shape[1] if points.ndim == 2 else '?'} coordinates; "
                            "a 3-D mesh needs x, y, z")
    connectivity = np.asarray(cells[kind], dtype=np.int64)
    cell_sets = _named_cell_sets(m)
    volumes = {name: np.asarray(s[kind], dtype=np.int64) for name, s in cell_sets.items() if kind in s}
    surfaces_raw = {name: np.vstack([np.asarray(cells[t], dtype=np.int64)[np.asarray(s[t], dtype=np.int64), :3]
                                     for t in ("triangle", "triangle6") if t in s])
                    for name, s in cell_sets.items() if any(t in s for t in ("triangle", "triangle6"))}
    return _compact(path, points * metres_per_unit, connectivity, volumes, surfaces_raw,
                    {k: np.asarray(v, dtype=np.int64) for k, v in m.point_sets.items()})


def _named_cell_sets(m) -> dict[str, dict[str, np.ndarray]]:
    """{name: {cell type: indices into m.cells_dict[type]}}: meshio's cell sets, or for a
    .msh 2.2 file (which meshio reads without them) the physical tags with their names."""
    sets = {k: v for k, v in m.cell_sets_dict.items() if not k.startswith("gmsh:")} if m.cell_sets else {}
    if sets or "gmsh:physical" not in m.cell_data or not m.field_data:
        return sets
    physical = m.cell_data_dict["gmsh:physical"]
    dims = {"tetra": 3, "tetra10": 3, "triangle": 2, "triangle6": 2}
    for name, (tag, dim) in ((k, tuple(v[:2])) for k, v in m.field_data.items() if len(v) >= 2):
        for cell_type, tags in physical.items():
            if dims.get(cell_type) == dim:
                idx = np.flatnonzero(np.asarray(tags) == tag)
                if idx.size:
                    sets.setdefault(name, {})[cell_type] = idx
    return sets


def _compact(path, points, connectivity, volumes, surfaces, node_sets) -> ImportedMesh:
    """Renumber: corners of the tetrahedra first, then mid-edge nodes; drop nodes no
    tetrahedron uses (geometry points, nodes of surface-only elements)."""
    corners = np.unique(connectivity[:, :4])
    quadratic = connectivity.shape[1] == 10
    midside = np.setdiff1d(np.unique(connectivity[:, 4:]), corners) if quadratic else np.empty(0, np.int64)
    new = np.full(points.shape[0], -1, dtype=np.int64)
    new[corners] = np.arange(corners.size)
    new[midside] = corners.size + np.arange(midside.size)
    keep = np.concatenate([corners, midside])
    tets = new[connectivity[:, :4]]
    edge_nodes = new[connectivity[:, 4:]] if quadratic else None
    out_surfaces = {}
    for name, tris in surfaces.items():
        mapped = new[tris]
        if (mapped < 0).any() or (mapped >= corners.size).any():
            raise MeshReadError(f"{path}: surface region {name!r} has triangles whose corners are not corners of "
                                "the tetrahedra; export the surface on the volume mesh (shared nodes)")
        out_surfaces[name] = mapped
    out_nodes = {}
    for name, nodes in node_sets.items():
        mapped = new[nodes[(nodes >= 0) & (nodes < new.size)]]
        out_nodes[name] = mapped[mapped >= 0]
    mesh = ImportedMesh(points[keep].copy(), tets, edge_nodes, volumes, out_surfaces, out_nodes)
    _check_cells(path, mesh)
    return mesh


def _check_cells(path, mesh: ImportedMesh) -> None:
    p = mesh.points[mesh.tets]
    volume6 = np.einsum("ij,ij->i", np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]), p[:, 3] - p[:, 0])
    scale = np.linalg.norm(p[:, 1] - p[:, 0], axis=1) ** 3
    flat = np.flatnonzero(np.abs(volume6) <= 1e-12 * scale)
    if flat.size:
        raise MeshReadError(f"{path}: {flat.size} tetrahedra have no volume (first: cell {int(flat[0])}); "
                            "repair the mesh")
    if mesh.quadratic:
        for k, (a, b) in enumerate(TET10_EDGES):
            mid = 0.5 * (p[:, a] + p[:, b])
            length = np.linalg.norm(p[:, b] - p[:, a], axis=1)
            off = np.linalg.norm(mesh.points[mesh.edge_nodes[:, k]] - mid, axis=1) / length
            if off.max() > MIDSIDE_TOLERANCE:
                raise MeshReadError(
                    f"{path}: the 10-node tetrahedra's mid-edge nodes are not at their edges (node {k + 5} of a "
                    f"cell is {off.max():.2f} edge lengths from its edge's midpoint); the node order is not "
                    "meshio's (VTK's): export from the mesher's own writer")


def write_abaqus_inp(path: pathlib.Path, mesh: ImportedMesh, metres_per_unit: float = 1.0) -> None:
    """Write `mesh` as an Abaqus input file that meshio reads back: `*NODE`, one `*ELEMENT`
    block (C3D4 or C3D10), an `*ELSET` per volume, an `*NSET` per surface and node set (the
    form Abaqus/CAE and ANSYS exports give most simply). Coordinates divided by
    `metres_per_unit`. Used by the tests and for converting a mesh from elsewhere."""
    lines = ["*HEADING", "bearingsim mesh", "*NODE"]
    lines += [f"{i + 1}, {x:.17g}, {y:.17g}, {z:.17g}" for i, (x, y, z) in enumerate(mesh.points / metres_per_unit)]
    cells = mesh.tets if not mesh.quadratic else np.hstack([mesh.tets, mesh.edge_nodes])
    lines.append(f"*ELEMENT, TYPE={'C3D10' if mesh.quadratic else 'C3D4'}")
    lines += [", ".join(str(v) for v in [e + 1, *(c + 1)]) for e, c in enumerate(cells)]
    for name, idx in mesh.volumes.items():
        lines.append(f"*ELSET, ELSET={name}")
        lines += _rows(np.asarray(idx) + 1)
    node_sets = {name: np.unique(tris) for name, tris in mesh.surfaces.items()}
    node_sets.update(mesh.node_sets)
    for name, nodes in node_sets.items():
        lines.append(f"*NSET, NSET={name}")
        lines += _rows(np.asarray(nodes) + 1)
    from .mesh_data import atomic_write_text

    atomic_write_text(path, "\n".join(lines) + "\n")


def _rows(values: np.ndarray, per_line: int = 16) -> list[str]:
    return [", ".join(str(int(v)) for v in values[i:i + per_line]) for i in range(0, len(values), per_line)]
