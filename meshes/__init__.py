"""gmsh geometry builders for stage 1 (docs/model.md §3). gmsh is imported lazily."""

from bearingsim.meshes.cache import cached_housing_mesh, mesh_key
from bearingsim.meshes.housing import HousingGeometry, RingSeat, build_housing_mesh
from bearingsim.meshes.mesh_data import MeshData

__all__ = [
    "HousingGeometry",
    "MeshData",
    "RingSeat",
    "build_housing_mesh",
    "cached_housing_mesh",
    "mesh_key",
]
