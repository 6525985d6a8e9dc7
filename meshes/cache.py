"""Generated meshes are artefacts: cached by a hash of everything that shapes them."""

from __future__ import annotations

import dataclasses
import hashlib
import importlib.metadata
import json
import pathlib

from bearingsim.meshes.housing import HousingGeometry, build_housing_mesh
from bearingsim.meshes.mesh_data import MeshData

# bump when the geometry builder changes what it produces for the same inputs
BUILDER_VERSION = 2


def mesh_key(geometry: HousingGeometry, mesh_size: float, edge_refinement: float = 1.0) -> str:
    """Hex digest of geometry, size, builder and gmsh versions (gmsh is deterministic
    with one thread and fixed algorithms, see meshes.gmsh_io.gmsh_session)."""
    payload = {
        "geometry": dataclasses.asdict(geometry),
        "mesh_size": mesh_size,
        "edge_refinement": edge_refinement,
        "builder": BUILDER_VERSION,
        "gmsh": importlib.metadata.version("gmsh"),
    }
    return hashlib.sha256(json.dumps(payload, sort_keys=True).encode()).hexdigest()[:16]


def cached_housing_mesh(
    geometry: HousingGeometry, mesh_size: float, cache_dir: pathlib.Path, edge_refinement: float = 1.0
) -> tuple[MeshData, pathlib.Path, bool]:
    """(mesh, file, reused): load `cache_dir/mesh-<key>.npz` or build and save it."""
    cache_dir = pathlib.Path(cache_dir)
    cache_dir.mkdir(parents=True, exist_ok=True)
    path = cache_dir / f"mesh-{mesh_key(geometry, mesh_size, edge_refinement)}.npz"
    if path.exists():
        try:
            return MeshData.load(path), path, True
        except (OSError, ValueError, KeyError):
            path.unlink(missing_ok=True)  # a truncated artefact: rebuild it
    mesh = build_housing_mesh(geometry, mesh_size, edge_refinement)
    mesh.save(path)
    return mesh, path, False
