"""The `[fe]` scene table: geometry, materials, supports, loads and numerics of stage 1.

Field names are exactly the `[fe]` keys; the scene loader checks type and range from
each field's metadata (unit, gt/ge/lt/le, choices, doc). Cross-field checks that need the
bearing ring live in `FEConfig.validate`. Two models: the parametric axisymmetric assembly
(`model = "axisymmetric"`, the default) and the engineer's own tetrahedral mesh
(`model = "mesh"`, docs/model.md §3.1), each with its own keys (`AXISYMMETRIC_KEYS`,
`MESH_KEYS`); the scene loader refuses a key of the other model.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, fields

from ..meshes.housing import HousingGeometry, RingSeat


def _f(default, unit: str, doc: str, **limits):
    return field(default=default, metadata={"unit": unit, "doc": doc, **limits})


MESH_UNITS = {"m": 1.0, "cm": 1e-2, "mm": 1e-3, "in": 0.0254}  # length of one mesh unit [m]


@dataclass(frozen=True)
class RegionMaterial:
    """`[fe.materials.<region>]`: the isotropic elastic material of one volume region of the mesh."""

    region: str = _f("", "-", "name of the volume region (cell set, physical volume) of the mesh")
    youngs_modulus: float = _f(208e9, "Pa", "Young's modulus of the region", gt=0.0)
    poisson_ratio: float = _f(0.3, "-", "Poisson ratio of the region", gt=-1.0, lt=0.5)


@dataclass(frozen=True)
class FEConfig:
    """Stage-1 settings (docs/model.md §3). Defaults suit the reference bearing (§2)."""

    model: str = _f(
        "axisymmetric", "-",
        "axisymmetric: the parametric housing below, solved on its meridian section; mesh: the "
        "engineer's own 3-D tetrahedral mesh (mesh_file, docs/housing-mesh.md)",
        choices=("axisymmetric", "mesh"),
    )
    # --- the engineer's mesh (model = "mesh", docs/model.md §3.1) ------------------------------
    mesh_file: str = _f(
        "", "-", "model = mesh: the mesh file (.msh, Abaqus .inp or any meshio format with named "
        "regions), absolute or relative to the scene file; linear or quadratic tetrahedra")
    mesh_unit: str = _f("m", "-", "model = mesh: the length unit of the mesh's coordinates",
                        choices=tuple(MESH_UNITS))
    inner_seat: str = _f(
        "inner_seat", "-", "model = mesh: the surface region where the inner ring sits (e.g. on the "
        "shaft); the perturbation loads reach it through a distributing coupling from its centroid, "
        "the reference point")
    outer_seat: str = _f(
        "outer_seat", "-", "model = mesh: the surface region where the outer ring sits in the housing; "
        "the loads are reacted there and the response is relative to it (a mesh without it: "
        "relative to the clamped ground)")
    fixed: str = _f("fixed", "-", "model = mesh: the clamped surface region (zero displacement)")
    materials: tuple[RegionMaterial, ...] = _f(
        (), "-", "model = mesh: [fe.materials.<region>] tables, one per volume region, with "
        "youngs_modulus [Pa] and poisson_ratio")
    refinement_check: bool = _f(
        False, "-", "also identify on a once-refined discretisation and report the change of H in "
        "hinge.toml [refinement] (mesh_size halved; a mesh: every tetrahedron split into eight); "
        "`bearingsim identify --refine` sets it")
    # --- numerics -----------------------------------------------------------------------
    mesh_size: float = _f(
        0.010, "m", "triangle size in the meridian (r, z) section of the axisymmetric model, away "
        "from its corners", gt=0.0)
    edge_refinement: float = _f(
        0.02, "-", "triangle size at the corners of the section (the circular edges: re-entrant "
        "corners, material junctions, seat ends) as a fraction of mesh_size, growing linearly back "
        "to mesh_size at 3 thinnest walls from them; 1 = uniform mesh",
        gt=0.0, le=1.0,
    )
    element_order: int = _f(
        2, "-", "displacement order: 2 (accurate) or 1 (fast preview, up to ~2 % stiff)",
        choices=(1, 2),
    )
    linear_solver: str = _f(
        "auto", "-", "sparse solver: pardiso (MKL, SPD), splu (scipy), amg (pyamg smoothed aggregation "
        "+ conjugate gradients); auto = a direct solver (pardiso if installed, else splu) up to "
        "direct_max_dofs free dofs, amg beyond",
        choices=("auto", "pardiso", "splu", "amg"),
    )
    direct_max_dofs: int = _f(
        100_000, "-", "linear_solver = auto: the largest system (free dofs) given to a direct solver",
        ge=0)
    iterative_tolerance: float = _f(
        1e-10, "-", "linear_solver = amg: relative residual at which conjugate gradients stop",
        gt=0.0, lt=1e-3)
    # --- shaft and supports ---------------------------------------------------------------
    shaft_inner_diameter: float = _f(0.090, "m", "bore of the hollow steel shaft", ge=0.0)
    shaft_youngs_modulus: float = _f(208e9, "Pa", "shaft and inner ring (steel)", gt=0.0)
    shaft_poisson_ratio: float = _f(0.3, "-", "shaft and inner ring (steel)", gt=-1.0, lt=0.5)
    shaft_density: float = _f(7850.0, "kg/m^3", "shaft and inner ring (steel)", gt=0.0)
    support_a_position: float = _f(-0.110, "m", "axial position of roller-bearing support a (centre)")
    support_b_position: float = _f(0.110, "m", "axial position of roller-bearing support b (centre)")
    support_width: float = _f(0.020, "m", "axial width of each support annulus", gt=0.0)
    support_radial_thickness: float = _f(0.015, "m", "radial section of each support annulus", gt=0.0)
    support_radial_stiffness: float = _f(
        1.0e9, "N/m", "radial stiffness of each support (sets the annulus modulus)", gt=0.0
    )
    # --- housing --------------------------------------------------------------------------
    housing_wall_thickness: float = _f(0.012, "m", "light-alloy housing shell wall", gt=0.0)
    housing_flange_position: float = _f(0.160, "m", "axial position of the clamped flange face")
    housing_flange_diameter: float = _f(0.300, "m", "flange outside diameter", gt=0.0)
    housing_flange_thickness: float = _f(0.012, "m", "flange thickness", gt=0.0)
    housing_youngs_modulus: float = _f(71e9, "Pa", "housing alloy (aluminium; ~44e9 for magnesium)", gt=0.0)
    housing_poisson_ratio: float = _f(0.33, "-", "housing alloy", gt=-1.0, lt=0.5)
    housing_density: float = _f(2810.0, "kg/m^3", "housing alloy (not used by statics)", gt=0.0)
    # --- perturbation loads (docs/model.md §3) ------------------------------------------------------
    perturbation_forces: tuple[float, ...] = _f(
        (-1000.0, 500.0, 1000.0), "N", "force magnitudes along x, y, z", ge=-1000.0, le=1000.0
    )
    perturbation_moments: tuple[float, ...] = _f(
        (-1000.0, 500.0, 1000.0), "N*m", "moment magnitudes about x, y", ge=-1000.0, le=1000.0
    )
    load_reaction: str = _f(
        "outer_seat", "-",
        "outer_seat: load pair on inner ring and outer-ring seat, response relative to the seat; "
        "flange: load on the inner ring only, response relative to the clamped flange",
        choices=("outer_seat", "flange"),
    )

    def housing_geometry(self, ring: RingSeat) -> HousingGeometry:
        names = {f.name for f in fields(HousingGeometry)} - {"ring"}
        return HousingGeometry(ring=ring, **{n: getattr(self, n) for n in names})

    def support_modulus(self, ring: RingSeat) -> float:
        """Young's modulus [Pa] of the support annulus (Poisson ratio 0) giving the radial
        stiffness `support_radial_stiffness` under a rigid radial offset of its bore.

        Thin-layer estimate: normal stiffness E/t and shear stiffness G = E/2 over
        t per unit area, integrated round the annulus: k_r = pi R w (E + G)/t = 1.5 pi R w E / t.
        Approximate for t/R ~ 0.2; the FE model then carries whatever the annulus gives.
        """
        t, w = self.support_radial_thickness, self.support_width
        r_mean = 0.5 * ring.inner_bore_diameter + 0.5 * t
        return self.support_radial_stiffness * t / (1.5 * math.pi * r_mean * w)

    def validate(self, ring: RingSeat) -> None:
        """Raise ValueError naming the key, value, allowed range and unit if the geometry
        is inconsistent with the bearing ring (the mesh itself is checked when it is read,
        fe_model.mesh_checks)."""
        self._validate_perturbations()
        if self.model == "mesh":
            if not self.mesh_file:
                raise ValueError("[fe] mesh_file is missing: model = 'mesh' needs the mesh file "
                                 "(absolute, or relative to the scene file)")
            if not self.materials:
                raise ValueError("[fe] materials is missing: model = 'mesh' needs one table "
                                 "[fe.materials.<region>] per volume region, with youngs_modulus [Pa] "
                                 "and poisson_ratio")
            return
        half_b, half_w = 0.5 * ring.width, 0.5 * self.support_width
        r_b, R = 0.5 * ring.inner_bore_diameter, 0.5 * ring.outer_outside_diameter
        _require("shaft_inner_diameter", self.shaft_inner_diameter, "<", ring.inner_bore_diameter,
                 "m", "the ring bore (bearing.inner_bore_diameter)")
        _require("support_radial_thickness", self.support_radial_thickness, "<", 0.9 * (R - r_b),
                 "m", "90 % of the gap between ring bore and outer-ring seat")
        _require("support_a_position", self.support_a_position, "<", -half_b - half_w,
                 "m", "-(width/2 + support_width/2): the support must clear the inner ring")
        _require("support_b_position", self.support_b_position, ">", half_b + half_w,
                 "m", "width/2 + support_width/2: the support must clear the inner ring")
        _require("housing_flange_position", self.housing_flange_position, ">",
                 self.support_b_position + half_w + self.housing_flange_thickness,
                 "m", "support_b_position + support_width/2 + housing_flange_thickness")
        _require("housing_flange_diameter", self.housing_flange_diameter, ">",
                 ring.outer_outside_diameter + 2.0 * self.housing_wall_thickness + 0.002,
                 "m", "outer_outside_diameter + 2 housing_wall_thickness + 2 mm")
        thinnest = min(0.5 * (ring.inner_outer_diameter - ring.inner_bore_diameter),
                       self.housing_wall_thickness, self.support_radial_thickness,
                       r_b - 0.5 * self.shaft_inner_diameter)
        _require("mesh_size", self.mesh_size, "<=", 4.0 * thinnest,
                 "m", "4 x the thinnest wall (ring, shaft, support or housing)")

    def _validate_perturbations(self) -> None:
        for key, unit in (("perturbation_forces", "N"), ("perturbation_moments", "N*m")):
            values = tuple(getattr(self, key))
            if not values or any(v == 0.0 or not math.isfinite(v) for v in values):
                raise ValueError(
                    f"[fe] {key} = {list(values)} {unit}: give at least one non-zero finite "
                    "magnitude in [-1000, 1000]"
                )


# the keys only one model reads (the others are common: model, element_order, the solver and
# the perturbation loads); a scene that gives a key of the other model is refused
MESH_KEYS = ("mesh_file", "mesh_unit", "inner_seat", "outer_seat", "fixed", "materials")
AXISYMMETRIC_KEYS = tuple(
    f.name for f in fields(FEConfig)
    if f.name.startswith(("shaft_", "support_", "housing_")) or f.name in ("mesh_size", "edge_refinement",
                                                                           "load_reaction"))


def _require(key: str, value: float, op: str, bound: float, unit: str, meaning: str) -> None:
    # an inclusive bound admits the value as the message states it (6 digits): 4 x 0.01 m
    # computes as 0.039999... m, and 0.04 m must not be refused as "must be <= 0.04 m"
    stated = float(f"{bound:.6g}")
    ok = {"<": value < bound, ">": value > bound, "<=": value <= max(bound, stated)}[op]
    if not ok:
        raise ValueError(
            f"[fe] {key} = {value!r} {unit} is not allowed: it must be {op} {bound:.6g} {unit} "
            f"({meaning})"
        )
