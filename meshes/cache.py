"""Generated meshes are artefacts: cached by a hash of everything that shapes them."""

from __future__ import annotations

import dataclasses
import hashlib
import importlib.metadata
import json
import pathlib

from .housing import HousingGeometry, build_housing_mesh, build_section_mesh
from .mesh_data import MeshData
from .section import SectionMesh

# bump when a builder changes what it produces for the same inputs
BUILDER_VERSION = 2  # 3-D tetrahedra, build_housing_mesh
SECTION_BUILDER_VERSION = 1  # meridian-section triangles, build_section_mesh


def mesh_key(geometry: HousingGeometry, mesh_size: float, edge_refinement: float = 1.0, kind: str = "tets") -> str:
    """Hex digest of geometry, size, builder and gmsh versions (gmsh is deterministic
    with one thread and fixed algorithms, see meshes.gmsh_io.gmsh_session).
    kind: "tets" (3-D) or "section" (meridian section)."""
    payload = {
        "geometry": dataclasses.asdict(geometry),
        "mesh_size": mesh_size,
        "edge_refinement": edge_refinement,
        "builder": BUILDER_VERSION,
        "gmsh": importlib.metadata.version("gmsh"),
    }
    if kind == "section":
        payload.update(kind="section", builder=SECTION_BUILDER_VERSION)
    elif kind != "tets":
        raise ValueError(f"mesh kind {kind!r}: allowed 'tets' or 'section'")
    return hashlib.sha256(json.dumps(payload, sort_keys=True).encode()).hexdigest()[:16]


def cached_housing_mesh(
    geometry: HousingGeometry, mesh_size: float, cache_dir: pathlib.Path, edge_refinement: float = 1.0
) -> tuple[MeshData, pathlib.Path, bool]:
    """(mesh, file, reused): load `cache_dir/mesh-<key>.npz` or build and save it."""
    return _cached(MeshData, build_housing_mesh, "mesh", geometry, mesh_size, cache_dir, edge_refinement, "tets")


def cached_section_mesh(
    geometry: HousingGeometry, mesh_size: float, cache_dir: pathlib.Path, edge_refinement: float = 1.0
) -> tuple[SectionMesh, pathlib.Path, bool]:
    """(section, file, reused): load `cache_dir/section-<key>.npz` or build and save it."""
    return _cached(SectionMesh, build_section_mesh, "section", geometry, mesh_size, cache_dir, edge_refinement,
                   "section")


def _cached(cls, build, prefix, geometry, mesh_size, cache_dir, edge_refinement, kind):
    cache_dir = pathlib.Path(cache_dir)
    cache_dir.mkdir(parents=True, exist_ok=True)
    path = cache_dir / f"{prefix}-{mesh_key(geometry, mesh_size, edge_refinement, kind)}.npz"
    if path.exists():
        try:
            return cls.load(path), path, True
        except (OSError, ValueError, KeyError):
            path.unlink(missing_ok=True)  # a truncated artefact: rebuild it
    mesh = build(geometry, mesh_size, edge_refinement)
    mesh.save(path)
    return mesh, path, False
