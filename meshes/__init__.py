"""gmsh geometry builders for stage 1 (docs/model.md §3). gmsh is imported lazily."""

from .cache import cached_housing_mesh, mesh_key
from .housing import HousingGeometry, RingSeat, build_housing_mesh
from .mesh_data import MeshData

__all__ = [
    "HousingGeometry",
    "MeshData",
    "RingSeat",
    "build_housing_mesh",
    "cached_housing_mesh",
    "mesh_key",
]
