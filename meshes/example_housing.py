"""The worked example of docs/housing-mesh.md: a housing on two feet, meshed with gmsh.

A non-axisymmetric structure of the kind `[fe] model = "mesh"` is for, built the way an
engineer's own model would be: the reference bearing's shaft (a steel tube) carried by two
support bearings (soft annuli) in a light-alloy housing, whose shell stands on a rib and a base
plate with two mounting feet; the feet's bottom faces are clamped. The inner ring is not
meshed: it sits on the shaft's seat. Volumes `shaft`, `support_a`, `support_b`, `housing`;
surfaces `inner_seat` (shaft, |z| <= ring width / 2), `outer_seat` (housing bore over the ring
width) and `fixed` (the feet's bottom faces). z is the bearing axis, y points up.

    python -m bearingsim.meshes.example_housing housing-feet.msh [--mesh-size 0.012] [--order 2]

writes the mesh as Gmsh .msh 4.1 (the built-in scene `housing-feet` has bearingsim write it
itself, into its cache). Dimensions in metres, from the reference assembly (meshes.housing).
"""

from __future__ import annotations

import argparse
import math
import pathlib
from dataclasses import asdict, dataclass

from .gmsh_io import classify_surface, gmsh_session, set_uniform_size
from .housing import HousingGeometry, RingSeat, _tube

BUILDER_VERSION = 1  # bump when the script makes a different mesh from the same inputs


@dataclass(frozen=True)
class FootHousing:
    """Dimensions [m]: the shaft, supports and shell of the reference assembly, and the stand."""

    shaft_inner_diameter: float = 0.090
    support_position: float = 0.110  # supports at z = +-support_position
    support_width: float = 0.020
    support_radial_thickness: float = 0.015
    wall_thickness: float = 0.012
    rib_width: float = 0.030  # the rib between shell and base plate (along x)
    plate_width: float = 0.340  # base plate, along x
    plate_thickness: float = 0.020
    plate_length: float = 0.160  # base plate and rib, along z
    foot_width: float = 0.060  # each foot, along x, at the plate's ends
    foot_height: float = 0.012
    stand_height: float = 0.040  # from the shell's outside (bottom) to the plate's top

    def geometry(self, ring: RingSeat) -> HousingGeometry:
        """The shaft, supports and shell as the parametric assembly's geometry (no flange)."""
        half = self.support_position + 0.5 * self.support_width
        return HousingGeometry(ring=ring, shaft_inner_diameter=self.shaft_inner_diameter,
                               support_a_position=-self.support_position, support_b_position=self.support_position,
                               support_width=self.support_width, support_radial_thickness=self.support_radial_thickness,
                               housing_wall_thickness=self.wall_thickness, housing_flange_position=half,
                               housing_flange_diameter=2.0 * half, housing_flange_thickness=0.0)


def recipe(mesh_size: float, order: int, housing: FootHousing = FootHousing(), ring: RingSeat = RingSeat()) -> dict:
    """Everything that shapes the mesh (for a cache key): dimensions, size, order, versions."""
    import importlib.metadata

    return {"housing": asdict(housing), "ring": asdict(ring), "mesh_size": mesh_size, "order": order,
            "builder": BUILDER_VERSION, "gmsh": importlib.metadata.version("gmsh")}


def write_foot_housing_mesh(path: pathlib.Path, mesh_size: float = 0.012, order: int = 2,
                            housing: FootHousing = FootHousing(), ring: RingSeat = RingSeat()) -> pathlib.Path:
    """Mesh the housing with tetrahedra of size `mesh_size` [m] and `order` (1: 4-node,
    2: 10-node, mid-edge nodes on the curved surfaces) and write it to `path` (.msh 4.1),
    atomically."""
    import os
    import tempfile

    if order not in (1, 2):
        raise ValueError(f"order = {order!r}: allowed 1 or 2")
    if not mesh_size > 0.0:
        raise ValueError(f"mesh_size = {mesh_size!r} m: must be > 0")
    g = housing.geometry(ring)
    path = pathlib.Path(path)
    with gmsh_session("foot_housing") as gmsh:
        parts = _add_parts(gmsh, housing, g)
        tags = [dimtag for dimtags in parts.values() for dimtag in dimtags]
        _, children = gmsh.model.occ.fragment(tags, [])
        gmsh.model.occ.synchronize()
        owner = {}
        names = [name for name, dimtags in parts.items() for _ in dimtags]
        for name, kids in zip(names, children):
            for dim, tag in kids:
                if dim == 3:
                    owner[tag] = name
        for name in parts:
            gmsh.model.addPhysicalGroup(3, sorted(v for v, p in owner.items() if p == name), name=name)
        for name, faces in _named_faces(gmsh, housing, g).items():
            if not faces:
                raise RuntimeError(f"the example housing has no face for {name!r}; check its dimensions")
            gmsh.model.addPhysicalGroup(2, faces, name=name)
        set_uniform_size(gmsh, mesh_size)
        gmsh.model.mesh.generate(3)
        if order == 2:
            gmsh.model.mesh.setOrder(2)
        gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
        gmsh.option.setNumber("Mesh.Binary", 0)
        fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.stem}.", suffix=".msh")
        os.close(fd)
        try:
            gmsh.write(tmp)
            os.replace(tmp, path)
        finally:
            if os.path.exists(tmp):
                os.remove(tmp)
    return path


def _add_parts(gmsh, h: FootHousing, g: HousingGeometry) -> dict[str, list[tuple[int, int]]]:
    occ = gmsh.model.occ
    r_b, half_b = 0.5 * g.ring.inner_bore_diameter, 0.5 * g.ring.width
    r_si, r_s, R = 0.5 * h.shaft_inner_diameter, g.support_outer_radius, g.seat_radius
    R_out = R + h.wall_thickness
    z_end = h.support_position + 0.5 * h.support_width
    zs = [(-h.support_position - 0.5 * h.support_width, -h.support_position + 0.5 * h.support_width),
          (h.support_position - 0.5 * h.support_width, h.support_position + 0.5 * h.support_width)]
    # the shaft in three tubes: the middle one's outside is the inner seat
    shaft = [t for z0, z1 in ((-z_end, -half_b), (-half_b, half_b), (half_b, z_end)) for t in _tube(gmsh, r_si, r_b, z0, z1)]
    housing = [t for z0, z1 in ((-z_end, -half_b), (-half_b, half_b), (half_b, z_end)) for t in _tube(gmsh, R, R_out, z0, z1)]
    housing += [t for z0, z1 in zs for t in _tube(gmsh, r_s, R, z0, z1)]  # the webs at the supports
    y_top = -R_out - h.stand_height  # top of the base plate
    y_rib = -R_out + 0.25 * h.wall_thickness  # the rib reaches into the shell wall
    zl = 0.5 * h.plate_length
    stand = [occ.addBox(-0.5 * h.rib_width, y_top, -zl, h.rib_width, y_rib - y_top, h.plate_length),
             occ.addBox(-0.5 * h.plate_width, y_top - h.plate_thickness, -zl, h.plate_width, h.plate_thickness,
                        h.plate_length)]
    for side in (-1.0, 1.0):
        x0 = side * 0.5 * h.plate_width - (h.foot_width if side > 0 else 0.0)
        stand.append(occ.addBox(x0, y_top - h.plate_thickness - h.foot_height, -zl, h.foot_width, h.foot_height,
                                h.plate_length))
    fused, _ = occ.fuse([(3, stand[0])], [(3, t) for t in stand[1:]])
    return {"shaft": shaft,
            "support_a": _tube(gmsh, r_b, r_s, *zs[0]),
            "support_b": _tube(gmsh, r_b, r_s, *zs[1]),
            "housing": housing + fused}


def _named_faces(gmsh, h: FootHousing, g: HousingGeometry) -> dict[str, list[int]]:
    tol = 1e-5 * h.plate_width
    r_b, R, half_b = 0.5 * g.ring.inner_bore_diameter, g.seat_radius, 0.5 * g.ring.width
    y_bottom = -(R + h.wall_thickness) - h.stand_height - h.plate_thickness - h.foot_height
    found: dict[str, list[int]] = {"inner_seat": [], "outer_seat": [], "fixed": []}
    for _, tag in gmsh.model.getEntities(2):
        kind = classify_surface(gmsh, tag, tol)
        if kind[0] == "cylinder" and kind[2] >= -half_b - tol and kind[3] <= half_b + tol:
            if math.isclose(kind[1], r_b, abs_tol=tol):
                found["inner_seat"].append(tag)
            elif math.isclose(kind[1], R, abs_tol=tol):
                found["outer_seat"].append(tag)
        x0, y0, _, x1, y1, _ = gmsh.model.getBoundingBox(2, tag)
        if math.isclose(y0, y_bottom, abs_tol=tol) and math.isclose(y1, y_bottom, abs_tol=tol):
            found["fixed"].append(tag)
    return found


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description="Write the example housing on two feet as a Gmsh .msh file.")
    parser.add_argument("out", type=pathlib.Path, help="the .msh file to write")
    parser.add_argument("--mesh-size", type=float, default=0.012, help="element size [m] (default 0.012)")
    parser.add_argument("--order", type=int, default=2, choices=(1, 2), help="1: 4-node, 2: 10-node tetrahedra")
    args = parser.parse_args(argv)
    print(write_foot_housing_mesh(args.out, args.mesh_size, args.order))


if __name__ == "__main__":
    main()
