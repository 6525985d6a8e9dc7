"""Geometries with closed-form elasticity solutions, for verifying fe_model.

- `cantilever_mesh`: prismatic box beam along x (Timoshenko beam theory); groups
  `beam` (volume), `root` (x = 0), `tip` (x = L).
- `quarter_tube_mesh`: a quarter of a thick-walled tube, half its length (Lamé);
  groups `tube`, `bore`, `outside`, `sym_x` (plane x = 0), `sym_y` (y = 0),
  `sym_z` (z = 0), `top` (z = H).
"""

from __future__ import annotations

import math

from .gmsh_io import classify_surface, extract_mesh, gmsh_session, set_uniform_size
from .mesh_data import MeshData


def cantilever_mesh(length: float, width: float, height: float, mesh_size: float) -> MeshData:
    """Box [0, L] x [-b/2, b/2] x [-h/2, h/2] [m], tetrahedra of size `mesh_size` [m]."""
    with gmsh_session("cantilever") as gmsh:
        box = gmsh.model.occ.addBox(0.0, -0.5 * width, -0.5 * height, length, width, height)
        gmsh.model.occ.synchronize()
        gmsh.model.setPhysicalName(3, gmsh.model.addPhysicalGroup(3, [box]), "beam")
        tol = 1e-5 * length  # OCC pads bounding boxes
        for name, x in (("root", 0.0), ("tip", length)):
            faces = [
                tag for _, tag in gmsh.model.getEntities(2)
                if math.isclose(gmsh.model.getBoundingBox(2, tag)[0], x, abs_tol=tol)
                and math.isclose(gmsh.model.getBoundingBox(2, tag)[3], x, abs_tol=tol)
            ]
            gmsh.model.setPhysicalName(2, gmsh.model.addPhysicalGroup(2, faces), name)
        set_uniform_size(gmsh, mesh_size)
        gmsh.model.mesh.generate(3)
        return extract_mesh(gmsh)


def quarter_tube_mesh(inner_radius: float, outer_radius: float, half_length: float, mesh_size: float) -> MeshData:
    """Tube a <= r <= b, 0 <= theta <= pi/2, 0 <= z <= H [m]."""
    a, b, H = inner_radius, outer_radius, half_length
    with gmsh_session("quarter_tube") as gmsh:
        occ = gmsh.model.occ
        outer = occ.addCylinder(0, 0, 0, 0, 0, H, b)
        inner = occ.addCylinder(0, 0, 0, 0, 0, H, a)
        tube, _ = occ.cut([(3, outer)], [(3, inner)])
        quarter, _ = occ.intersect(tube, [(3, occ.addBox(0, 0, 0, 2 * b, 2 * b, H))])
        occ.synchronize()
        gmsh.model.setPhysicalName(3, gmsh.model.addPhysicalGroup(3, [t for _, t in quarter]), "tube")
        tol = 1e-5 * b  # OCC pads bounding boxes
        groups: dict[str, list[int]] = {k: [] for k in ("bore", "outside", "sym_x", "sym_y", "sym_z", "top")}
        for _, tag in gmsh.model.getEntities(2):
            kind = classify_surface(gmsh, tag, tol)
            x0, y0, z0, x1, y1, z1 = gmsh.model.getBoundingBox(2, tag)
            if kind[0] == "cylinder":
                groups["bore" if math.isclose(kind[1], a, abs_tol=tol) else "outside"].append(tag)
            elif kind[0] == "plane_z":
                groups["sym_z" if math.isclose(kind[1], 0.0, abs_tol=tol) else "top"].append(tag)
            elif math.isclose(x0, 0.0, abs_tol=tol) and math.isclose(x1, 0.0, abs_tol=tol):
                groups["sym_x"].append(tag)
            elif math.isclose(y0, 0.0, abs_tol=tol) and math.isclose(y1, 0.0, abs_tol=tol):
                groups["sym_y"].append(tag)
        for name, tags in groups.items():
            gmsh.model.setPhysicalName(2, gmsh.model.addPhysicalGroup(2, tags), name)
        set_uniform_size(gmsh, mesh_size)
        gmsh.model.mesh.generate(3)
        return extract_mesh(gmsh)
