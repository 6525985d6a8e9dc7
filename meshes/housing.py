"""Parametric shaft / inner ring / supports / housing geometry (docs/model.md §3), gmsh OCC.

Axisymmetric about z, built from tubes (rectangles of the meridian section) and fragmented
so that every interface is conforming (the ring is tied to the shaft, the supports to shaft
and housing):

    z:   support_a ........ inner ring (|z| <= B/2) ........ support_b ..... flange
    r:   shaft [r_si, r_b]; ring [r_b, r_race]; support annuli [r_b, r_b + t_s];
         housing webs [r_b + t_s, R_seat] at the supports; housing shell
         [R_seat, R_seat + t_h] from support a to the flange; flange disc at the end.

The bearing's outer ring is not meshed: its seat is the housing bore over the ring width.
Two meshes of the same geometry: `build_section_mesh`, triangles of the (r, z) section for
the axisymmetric solver (the default, fe_model.axisymmetric), and `build_housing_mesh`,
tetrahedra of the 3-D body (fe_model's 3-D solver, kept as an independent cross-check).
Physical groups (the contract with fe_model): volumes `shaft`, `inner_ring`, `support_a`,
`support_b`, `housing`; surfaces `inner_ring_bore` = `inner_ring_seat` (ring–shaft interface),
`inner_ring_race` (ring outside diameter, where the balls push), `outer_ring_seat`
(housing bore over the ring width), `support_a`, `support_b` (shaft–support interfaces),
`housing_flange` (the clamped mounting face). In a section they are parts and boundary lines.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from .gmsh_io import classify_surface, close, extract_mesh, gmsh_session, grade_towards_curves, set_uniform_size
from .mesh_data import MeshData
from .section import SectionMesh, mesh_rectangles

# Section mesh (build_section_mesh): the size grows linearly from edge_refinement x mesh_size at
# every corner of the section back to mesh_size at CORNER_REACH x the thinnest wall from it.
# Fixed in metres for a geometry, so meshes of different mesh_size are self-similar.
CORNER_REACH = 3.0

# Graded refinement of the 3-D mesh (see build_housing_mesh): the edges that set the axial stiffness get
# SINGULAR_EDGE_FACTOR x the size of the other circular edges; sizes grow back to
# mesh_size within EDGE_REACH x mesh_size. At 0.030 m and 0.25 (the 3-D default until the
# axisymmetric model replaced it) H_u_zz is +1.7 % and H_psi +1.2 % above the converged
# hinge at 482k P2 dofs: isotropic tetrahedra cannot resolve edge singularities cheaply.
SINGULAR_EDGE_FACTOR = 0.32
EDGE_REACH = 1.0


@dataclass(frozen=True)
class RingSeat:
    """Bearing ring dimensions the FE geometry needs [m] (from the scene's `[bearing]`).

    inner_outer_diameter is the inner ring's outside diameter for the FE model: use the
    shoulder (land) diameter, 0.150 m for the reference bearing.
    """

    inner_bore_diameter: float = 0.130
    inner_outer_diameter: float = 0.150
    outer_outside_diameter: float = 0.196
    width: float = 0.034

    def __post_init__(self) -> None:
        for name in ("inner_bore_diameter", "inner_outer_diameter", "outer_outside_diameter", "width"):
            value = getattr(self, name)
            if not value > 0.0:
                raise ValueError(f"ring seat {name} = {value!r} m: must be > 0")
        if not self.inner_bore_diameter < self.inner_outer_diameter < self.outer_outside_diameter:
            raise ValueError(
                "ring seat diameters must satisfy inner_bore_diameter < inner_outer_diameter < "
                f"outer_outside_diameter, got {self.inner_bore_diameter} m, "
                f"{self.inner_outer_diameter} m, {self.outer_outside_diameter} m"
            )


@dataclass(frozen=True)
class HousingGeometry:
    """All dimensions of the simplified assembly [m]; see the module docstring."""

    ring: RingSeat
    shaft_inner_diameter: float
    support_a_position: float
    support_b_position: float
    support_width: float
    support_radial_thickness: float
    housing_wall_thickness: float
    housing_flange_position: float
    housing_flange_diameter: float
    housing_flange_thickness: float

    @property
    def support_outer_radius(self) -> float:
        return 0.5 * self.ring.inner_bore_diameter + self.support_radial_thickness

    @property
    def seat_radius(self) -> float:
        return 0.5 * self.ring.outer_outside_diameter


def build_housing_mesh(geometry: HousingGeometry, mesh_size: float, edge_refinement: float = 1.0,
                       msh_file=None) -> MeshData:
    """Mesh the assembly with linear tetrahedra of characteristic size `mesh_size` [m],
    graded to `edge_refinement * mesh_size` at the circular edges (1 = uniform) and to
    SINGULAR_EDGE_FACTOR times that at the edges whose singular stresses dominate the
    axial hinge stiffness (`_singular_curves`). `msh_file`: also write the mesh there as Gmsh
    .msh 4.1 with its physical groups (the 3-D mesh of this geometry as a user's mesh file,
    for `[fe] model = "mesh"`: docs/validation.md)."""
    with gmsh_session("housing") as gmsh:
        parts = _add_parts(gmsh, geometry)
        tags = [dimtag for dimtags in parts.values() for dimtag in dimtags]
        _, children = gmsh.model.occ.fragment(tags, [])
        gmsh.model.occ.synchronize()
        owner = _volume_owners(parts, tags, children)
        for name in ("shaft", "inner_ring", "support_a", "support_b", "housing"):
            volumes = sorted(v for v, part in owner.items() if part == name)
            gmsh.model.setPhysicalName(3, gmsh.model.addPhysicalGroup(3, volumes), name)
        for name, surfaces in _named_surfaces(gmsh, geometry).items():
            if not surfaces:
                raise RuntimeError(f"geometry has no surface for group {name!r}; check the [fe] dimensions")
            gmsh.model.setPhysicalName(2, gmsh.model.addPhysicalGroup(2, surfaces), name)
        set_uniform_size(gmsh, mesh_size)
        if edge_refinement < 1.0:
            every_edge = [tag for _, tag in gmsh.model.getEntities(1)]
            grade_towards_curves(gmsh, mesh_size, [
                (every_edge, edge_refinement),
                (_singular_curves(gmsh, geometry), SINGULAR_EDGE_FACTOR * edge_refinement),
            ], reach=EDGE_REACH)
        gmsh.model.mesh.generate(3)
        if msh_file is not None:
            gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
            gmsh.write(str(msh_file))
        return extract_mesh(gmsh)


def thinnest_wall(g: HousingGeometry) -> float:
    """Thinnest radial wall [m] of ring, housing shell, support annulus and shaft."""
    return min(0.5 * (g.ring.inner_outer_diameter - g.ring.inner_bore_diameter), g.housing_wall_thickness,
               g.support_radial_thickness, 0.5 * (g.ring.inner_bore_diameter - g.shaft_inner_diameter))


def build_section_mesh(geometry: HousingGeometry, mesh_size: float, edge_refinement: float = 1.0) -> SectionMesh:
    """Mesh the assembly's meridian section with triangles of size `mesh_size` [m], graded
    to `edge_refinement * mesh_size` at every corner of the section (the circular edges of
    the body: re-entrant corners, material junctions, seat and support ends), back to
    `mesh_size` at CORNER_REACH thinnest walls from the corner; 1 = uniform."""
    g = geometry
    # a boundary line of the section, ("r", r, z0, z1) or ("z", z, r0, r1), revolves into the surface
    lines = surface_rules(g, cylinder_kind="r", plane_kind="z")
    return mesh_rectangles(section_rectangles(g), lines, mesh_size, edge_refinement * mesh_size,
                           CORNER_REACH * thinnest_wall(g), match_tolerance(g))


def match_tolerance(g: HousingGeometry) -> float:
    """Length tolerance [m] for matching gmsh entities (surfaces, lines, edges) to the geometry."""
    return 1e-5 * g.housing_flange_diameter  # OCC pads bounding boxes by ~1e-7


def surface_rules(g: HousingGeometry, cylinder_kind: str, plane_kind: str) -> dict:
    """The named surfaces of the assembly (docs/model.md §3) as rules on a boundary entity's
    kind: (cylinder_kind, radius, z0, z1) for a cylinder, (plane_kind, z, r0, ...) for a plane
    normal to the axis. The 3-D mesh classifies gmsh surfaces, the section mesh its boundary
    lines, each with its own kind names; one table serves both."""
    tol = match_tolerance(g)
    r_b = 0.5 * g.ring.inner_bore_diameter
    half_b, half_w = 0.5 * g.ring.width, 0.5 * g.support_width

    def cylinder(radius: float, z0: float, z1: float):
        return lambda kind: (kind[0] == cylinder_kind and math.isclose(kind[1], radius, abs_tol=tol)
                             and kind[2] >= z0 - tol and kind[3] <= z1 + tol)

    return {
        "inner_ring_bore": cylinder(r_b, -half_b, half_b),
        "inner_ring_seat": cylinder(r_b, -half_b, half_b),  # docs/model.md's name: same surface as the bore
        "inner_ring_race": cylinder(0.5 * g.ring.inner_outer_diameter, -half_b, half_b),
        "outer_ring_seat": cylinder(g.seat_radius, -half_b, half_b),
        "support_a": cylinder(r_b, g.support_a_position - half_w, g.support_a_position + half_w),
        "support_b": cylinder(r_b, g.support_b_position - half_w, g.support_b_position + half_w),
        "housing_flange": lambda kind: (kind[0] == plane_kind
                                        and math.isclose(kind[1], g.housing_flange_position, abs_tol=tol)
                                        and kind[2] >= g.seat_radius - tol),
    }


def _tube(gmsh, r_in: float, r_out: float, z0: float, z1: float) -> list[tuple[int, int]]:
    occ = gmsh.model.occ
    outer = occ.addCylinder(0.0, 0.0, z0, 0.0, 0.0, z1 - z0, r_out)
    if r_in <= 0.0:
        return [(3, outer)]
    inner = occ.addCylinder(0.0, 0.0, z0, 0.0, 0.0, z1 - z0, r_in)
    result, _ = occ.cut([(3, outer)], [(3, inner)])
    return result


def section_rectangles(g: HousingGeometry) -> dict[str, list[tuple[float, float, float, float]]]:
    """The assembly's meridian section as (r0, r1, z0, z1) rectangles [m] per part: the one
    description of the geometry, swept round z by `build_housing_mesh` and meshed in the
    (r, z) plane by `build_section_mesh`."""
    r_b = 0.5 * g.ring.inner_bore_diameter
    half_b = 0.5 * g.ring.width
    half_w = 0.5 * g.support_width
    z_a, z_b = g.support_a_position, g.support_b_position
    r_s, R = g.support_outer_radius, g.seat_radius
    R_out = R + g.housing_wall_thickness
    z_end = g.housing_flange_position
    housing = [
        (R, R_out, z_a - half_w, -half_b),  # shell, support-a side
        (R, R_out, -half_b, half_b),  # shell at the seat (own bore face)
        (R, R_out, half_b, z_end),  # shell, flange side
        (r_s, R, z_a - half_w, z_a + half_w),  # web at support a
        (r_s, R, z_b - half_w, z_b + half_w),  # web at support b
        (R_out, 0.5 * g.housing_flange_diameter, z_end - g.housing_flange_thickness, z_end),
    ]
    return {
        "shaft": [(0.5 * g.shaft_inner_diameter, r_b, z_a - half_w, z_b + half_w)],
        "inner_ring": [(r_b, 0.5 * g.ring.inner_outer_diameter, -half_b, half_b)],
        "support_a": [(r_b, r_s, z_a - half_w, z_a + half_w)],
        "support_b": [(r_b, r_s, z_b - half_w, z_b + half_w)],
        "housing": housing,
    }


def _add_parts(gmsh, g: HousingGeometry) -> dict[str, list[tuple[int, int]]]:
    rects = section_rectangles(g)
    # the housing's tubes first: the OCC tags, and so the meshes, of builder version 2
    tubes = {name: [] for name in ("housing", *rects)}
    for name in tubes:
        for r0, r1, z0, z1 in rects[name]:
            tubes[name] += _tube(gmsh, r0, r1, z0, z1)
    return {name: tubes[name] for name in rects}


def _volume_owners(parts, tags, children) -> dict[int, str]:
    """Which part each fragmented volume came from (fragment keeps the input order)."""
    part_of_input = [name for name, dimtags in parts.items() for _ in dimtags]
    owner: dict[int, str] = {}
    for name, kids in zip(part_of_input, children):
        for dim, tag in kids:
            if dim == 3:
                owner[tag] = name
    return owner


def _named_surfaces(gmsh, g: HousingGeometry) -> dict[str, list[int]]:
    tol = match_tolerance(g)
    rules = surface_rules(g, cylinder_kind="cylinder", plane_kind="plane_z")
    kinds = {tag: classify_surface(gmsh, tag, tol) for _, tag in gmsh.model.getEntities(2)}
    return {name: sorted(t for t, k in kinds.items() if rule(k)) for name, rule in rules.items()}


def _singular_curves(gmsh, g: HousingGeometry) -> list[int]:
    """Circular edges where the axial load path has singular stresses: the four corners
    of each soft support annulus (bonded to shaft and web), the re-entrant corners where
    the webs meet the housing shell, and the edges of the outer-ring seat (end of the
    seat traction). Refining these moves H_u_zz most per degree of freedom."""
    tol = match_tolerance(g)
    r_b, r_s, R = 0.5 * g.ring.inner_bore_diameter, g.support_outer_radius, g.seat_radius
    half_b, half_w = 0.5 * g.ring.width, 0.5 * g.support_width
    support_ends = [z + s * half_w for z in (g.support_a_position, g.support_b_position) for s in (-1.0, 1.0)]
    corners = [(r, z) for r in (r_b, r_s, R) for z in support_ends] + [(R, -half_b), (R, half_b)]
    found = []
    for _, tag in gmsh.model.getEntities(1):
        x0, y0, z0, x1, y1, z1 = gmsh.model.getBoundingBox(1, tag)
        radius = max(abs(x0), abs(x1), abs(y0), abs(y1))
        if z1 - z0 < tol and any(close(radius, r, tol) and close(0.5 * (z0 + z1), z, tol) for r, z in corners):
            found.append(tag)
    if len(found) < len(corners):
        raise RuntimeError(f"found {len(found)} of {len(corners)} singular edges to refine; check that the "
                           "[fe] supports and housing dimensions pass FEConfig.validate, or set edge_refinement = 1")
    return found
