"""A tetrahedral mesh with named physical groups, as plain arrays.

With `SectionMesh` (meshes/section.py: the axisymmetric section the identify stage solves; this
3-D mesh serves its cross-check), this is what `meshes/` hands to `fe_model/` (docs/model.md §3:
the physical-group names are the contract). It is taken straight from the gmsh API rather than
through a .msh file: meshio 5.3.5 cannot read back its own .msh 4.1 and .msh 2.2 drops interior
groups (the ring–shaft interface is interior). Saved as .npz so a mesh is a cacheable
artefact keyed by the hash of what built it.
"""

from __future__ import annotations

import os
import pathlib
import tempfile
from dataclasses import dataclass, field

import numpy as np


@dataclass(frozen=True)
class MeshData:
    """Linear tetrahedra with named volumes and surfaces.

    points: (N, 3) float64 [m]; tets: (E, 4) int64 vertex indices; volumes maps a
    physical-volume name to the indices of its tetrahedra; surfaces maps a
    physical-surface name to its triangles as (F, 3) vertex indices.
    """

    points: np.ndarray
    tets: np.ndarray
    volumes: dict[str, np.ndarray] = field(default_factory=dict)
    surfaces: dict[str, np.ndarray] = field(default_factory=dict)

    @property
    def n_nodes(self) -> int:
        return int(self.points.shape[0])

    @property
    def n_elements(self) -> int:
        return int(self.tets.shape[0])

    def to_skfem(self):
        """skfem `MeshTet` with `subdomains` and `boundaries` from the physical groups.

        Boundary facets are matched to the mesh's facets by their sorted vertex
        triples, which works for interior surfaces too.
        """
        from skfem import MeshTet

        mesh = MeshTet(np.ascontiguousarray(self.points.T), np.ascontiguousarray(self.tets.T))
        facet_index = facet_lookup(mesh.facets)
        boundaries = {name: match_facets(name, tris, facet_index, "triangle", "a facet of the volume mesh")
                      for name, tris in self.surfaces.items()}
        subdomains = {name: np.asarray(idx, dtype=np.int64) for name, idx in self.volumes.items()}
        return mesh.with_subdomains(subdomains).with_boundaries(boundaries)

    def save(self, path: pathlib.Path) -> None:
        """Write atomically to `path` (.npz)."""
        save_grouped_mesh(path, self.points, "tets", self.tets, self.volumes, self.surfaces)

    @classmethod
    def load(cls, path: pathlib.Path) -> "MeshData":
        return cls(*load_grouped_mesh(path, "tets"))


def facet_lookup(facets: np.ndarray) -> dict[tuple[int, ...], int]:
    """Map sorted vertex tuple -> facet index for skfem's (k, F) facet array (k = 3 for
    tetrahedra, 2 for the edges of triangles)."""
    sorted_facets = np.sort(facets, axis=0).T
    return {tuple(f): i for i, f in enumerate(sorted_facets.tolist())}


def match_facets(name: str, cells: np.ndarray, lookup: dict, cell: str, facet: str) -> np.ndarray:
    """Facet indices of boundary group `name`'s `cells` (F, k) by their sorted vertices; a cell
    that is no facet of the mesh (a non-conforming mesh) is an error naming the group.
    `cell` and `facet` name them in the message ("triangle", "a facet of the volume mesh")."""
    keys = np.sort(np.asarray(cells, dtype=np.int64), axis=1).tolist()
    try:
        return np.array([lookup[tuple(k)] for k in keys], dtype=np.int64)
    except KeyError as err:
        raise ValueError(
            f"surface group {name!r} has a {cell} {err.args[0]} that is not {facet}; the mesh is not "
            "conforming (was the geometry fragmented?)"
        ) from None


def save_grouped_mesh(path, points, cells_name: str, cells, volumes: dict, surfaces: dict) -> None:
    """Write a mesh with named groups atomically to `path` (.npz): a temporary file in the
    same directory, then a rename (a reader never sees a partial file)."""
    path = pathlib.Path(path)
    arrays = {"points": points, cells_name: cells}
    arrays.update({f"volume:{k}": v for k, v in volumes.items()})
    arrays.update({f"surface:{k}": v for k, v in surfaces.items()})
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=path.name, suffix=".tmp.npz")
    os.close(fd)
    try:
        np.savez(tmp, **arrays)
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)


def load_grouped_mesh(path, cells_name: str):
    """(points, cells, volumes, surfaces) of a file written by `save_grouped_mesh`."""
    with np.load(path) as data:
        volumes = {k.split(":", 1)[1]: data[k] for k in data.files if k.startswith("volume:")}
        surfaces = {k.split(":", 1)[1]: data[k] for k in data.files if k.startswith("surface:")}
        return data["points"], data[cells_name], volumes, surfaces


def atomic_write_text(path, text: str) -> None:
    """Write `text` (UTF-8) atomically to `path`: a temporary file in the same directory, then
    a rename."""
    path = pathlib.Path(path)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as fh:
            fh.write(text)
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)
