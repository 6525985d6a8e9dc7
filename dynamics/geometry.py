"""Bearing and cage geometry in SI units, with the derived quantities of docs/model.md §2.

One internal geometry serves every stage. It is built either from the paper's Table-1
form (groove curvature-centre circle diameters and groove radii) or from catalogue data
(pitch diameter, conformities, diametral clearance); both resolve to the same fields.

A ring's shoulder (land) diameter is one number for both sides of the groove or a pair
`(side toward +z, side toward -z)`, as an angular-contact ring has a high and a low shoulder.
Which side a contact presses on follows from the sign of its contact angle (`contact_side`):
an axial load on the inner race along +z (positive contact angles) loads the inner ring's
groove on its -z side and the outer ring's on its +z side (docs/scenes.md, *Ring shoulders*).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field


SIDES = (1, -1)  # +1: the side of a ring toward +z, -1: toward -z
SIDE_NAMES = ("side toward +z", "side toward -z")


def contact_side(ring: str, contact_angle: float) -> int:
    """The side (+1 toward +z, -1 toward -z) of `ring`'s groove a ball presses on at
    `contact_angle` [rad] (+: the contact carries +z thrust on the inner race): the inner ring
    on its -z side, the outer ring on its +z side (the module docstring)."""
    positive = contact_angle >= 0.0
    if ring == "inner":
        return -1 if positive else 1
    return 1 if positive else -1


@dataclass(frozen=True)
class Material:
    """Isotropic linear-elastic material."""

    youngs_modulus: float = field(metadata={"unit": "Pa", "gt": 0.0, "doc": "Young's modulus E"})
    poisson_ratio: float = field(metadata={"unit": "-", "gt": -1.0, "lt": 0.5, "doc": "Poisson's ratio"})
    density: float = field(metadata={"unit": "kg/m^3", "gt": 0.0, "doc": "mass density"})
    thermal_expansion: float | None = field(default=None, metadata={
        "unit": "1/K", "ge": 0.0, "lt": 1e-4,
        "doc": "linear expansion coefficient alpha (operating geometry, docs/model.md §2.1); default by role: "
               "11.9e-6 for ball and race (AISI 52100), 18.0e-6 for the cage (silicon bronze)"})

    @property
    def plane_strain_modulus(self) -> float:
        """E/(1-nu^2) [Pa]: one body's share of the Hertz effective modulus."""
        return self.youngs_modulus / (1.0 - self.poisson_ratio**2)


def effective_modulus(a: Material, b: Material) -> float:
    """Hertz effective modulus E' = 2 / ((1-nu_a^2)/E_a + (1-nu_b^2)/E_b) [Pa].

    For equal materials this is E/(1-nu^2) (docs/model.md §6.2).
    """
    return 2.0 / (1.0 / a.plane_strain_modulus + 1.0 / b.plane_strain_modulus)


@dataclass(frozen=True)
class BearingGeometry:
    """Ball-bearing geometry (docs/model.md §2), SI units.

    `inner_groove_center_diameter` (d_i) and `outer_groove_center_diameter` (d_o) are the
    diameters of the circles on which the groove curvature centres lie; `*_groove_radius`
    are r_i, r_o. Shoulder, bore, outside diameters and width are optional: only the stages
    that use them (ellipse truncation, FE geometry, renders) require them.
    """

    ball_diameter: float = field(metadata={"unit": "m", "gt": 0.0, "doc": "ball diameter D"})
    ball_count: int = field(metadata={"unit": "-", "ge": 3, "doc": "number of balls Z"})
    inner_groove_center_diameter: float = field(metadata={"unit": "m", "gt": 0.0, "doc": "d_i: diameter of the circle of inner-groove curvature centres"})
    outer_groove_center_diameter: float = field(metadata={"unit": "m", "gt": 0.0, "doc": "d_o: diameter of the circle of outer-groove curvature centres"})
    inner_groove_radius: float = field(metadata={"unit": "m", "gt": 0.0, "doc": "r_i: inner groove (raceway) cross-section radius"})
    outer_groove_radius: float = field(metadata={"unit": "m", "gt": 0.0, "doc": "r_o: outer groove cross-section radius"})
    inner_shoulder_diameter: float | tuple[float, float] | None = field(default=None, metadata={
        "unit": "m", "gt": 0.0, "length": 2,
        "doc": "inner-ring land diameter: one value for both sides, or [side toward +z, side toward -z] "
               "(ellipse truncation; land of an inner-guided cage)"})
    outer_shoulder_diameter: float | tuple[float, float] | None = field(default=None, metadata={
        "unit": "m", "gt": 0.0, "length": 2,
        "doc": "outer-ring land diameter: one value for both sides, or [side toward +z, side toward -z] "
               "(ellipse truncation; land of an outer-guided cage)"})
    inner_bore_diameter: float | None = field(default=None, metadata={"unit": "m", "gt": 0.0, "doc": "inner-ring bore (inner-ring mass of the dynamic model, FE seat)"})
    outer_outside_diameter: float | None = field(default=None, metadata={"unit": "m", "gt": 0.0, "doc": "outer-ring outside diameter (FE seat, renders)"})
    width: float | None = field(default=None, metadata={"unit": "m", "gt": 0.0, "doc": "ring width B"})

    def __post_init__(self) -> None:
        """Reject geometry that cannot be built; messages name the scene keys."""
        D = self.ball_diameter
        # a ball of 0.2 m or more is larger than any rolling bearing's: most likely millimetres
        slip = (f"; ball_diameter = {D:g} m would be a ball of {D:g} metres: lengths are in metres, "
                "not millimetres (12.7 mm is 0.0127)" if D >= 0.2 else "")
        for name in ("inner_groove_radius", "outer_groove_radius"):
            r = getattr(self, name)
            if r <= 0.5 * D:
                raise ValueError(
                    f"{name} = {r:g} m must exceed the ball radius D/2 = {0.5 * D:g} m "
                    f"(a groove tighter than the ball cannot hold it){slip}"
                )
        if self.inner_groove_bottom_diameter <= 0.0:
            raise ValueError(
                f"inner groove bottom diameter d_i - 2 r_i = {self.inner_groove_bottom_diameter:g} m "
                "must be positive: check inner_groove_center_diameter and inner_groove_radius (form 1), "
                f"or ball_diameter against pitch_diameter (form 2){slip}"
            )
        play = self.diametral_clearance
        if play < -0.1 * D:
            raise ValueError(
                f"diametral clearance {play:g} m is a preload of more than 10 % of the ball "
                "diameter: check the groove diameters (form 1) or diametral_clearance (form 2)"
            )
        # Z balls fit on the pitch circle only if the chord between neighbours exceeds D.
        chord = self.pitch_diameter * math.sin(math.pi / self.ball_count)
        if chord <= D:
            raise ValueError(
                f"ball_count = {self.ball_count} balls of diameter {D:g} m do not fit around "
                f"the pitch circle of diameter {self.pitch_diameter:g} m "
                f"(neighbour spacing {chord:g} m <= D); at most "
                f"{int(math.pi / math.asin(min(1.0, D / self.pitch_diameter)))} fit"
            )
        for ring in ("inner", "outer"):
            value = getattr(self, f"{ring}_shoulder_diameter")
            if isinstance(value, tuple) and len(value) != 2:
                raise ValueError(f"{ring}_shoulder_diameter: give one diameter, or two [side toward +z, "
                                 f"side toward -z] [m]; got {len(value)} values")
        if self.inner_shoulder_diameter is not None and self.inner_bore_diameter is not None:
            for side, d in zip(SIDE_NAMES, self.shoulders("inner")):
                if self.inner_bore_diameter >= d:
                    raise ValueError(
                        f"inner_bore_diameter = {self.inner_bore_diameter:g} m must be smaller than "
                        f"inner_shoulder_diameter = {d:g} m ({side})"
                    )
        if self.outer_shoulder_diameter is not None and self.outer_outside_diameter is not None:
            for side, d in zip(SIDE_NAMES, self.shoulders("outer")):
                if self.outer_outside_diameter <= d:
                    raise ValueError(
                        f"outer_outside_diameter = {self.outer_outside_diameter:g} m must exceed "
                        f"outer_shoulder_diameter = {d:g} m ({side})"
                    )

    @classmethod
    def from_catalogue(
        cls,
        ball_diameter: float,
        ball_count: int,
        pitch_diameter: float,
        inner_conformity: float,
        outer_conformity: float,
        diametral_clearance: float,
        **optional: float | None,
    ) -> "BearingGeometry":
        """Build from catalogue data: d_m, f_i = r_i/D, f_o = r_o/D, P_d (unmounted).

        Groove bottoms sit at d_m -/+ (D + P_d/2); the curvature centres lie one groove
        radius inside the groove from its bottom.
        """
        D = ball_diameter
        r_i = inner_conformity * D
        r_o = outer_conformity * D
        inner_bottom = pitch_diameter - D - 0.5 * diametral_clearance
        outer_bottom = pitch_diameter + D + 0.5 * diametral_clearance
        return cls(
            ball_diameter=D,
            ball_count=ball_count,
            inner_groove_center_diameter=inner_bottom + 2.0 * r_i,
            outer_groove_center_diameter=outer_bottom - 2.0 * r_o,
            inner_groove_radius=r_i,
            outer_groove_radius=r_o,
            **optional,
        )

    # --- the shoulders (lands), per side of the groove -------------------------------------
    def shoulders(self, ring: str) -> tuple[float, float] | None:
        """(land diameter on the side toward +z, on the side toward -z) [m] of `ring`
        ("inner" | "outer"), None without a shoulder diameter."""
        value = getattr(self, f"{ring}_shoulder_diameter")
        if value is None:
            return None
        return (float(value[0]), float(value[1])) if isinstance(value, tuple) else (float(value), float(value))

    def shoulder(self, ring: str, side: int) -> float | None:
        """Land diameter [m] of `ring` on `side` (+1: toward +z, -1: toward -z)."""
        pair = self.shoulders(ring)
        return None if pair is None else pair[0 if side > 0 else 1]

    def mean_shoulder_diameter(self, ring: str) -> float | None:
        """The mean of the two sides' land diameters [m] (one value where a ring is drawn as a
        plain annulus: the FE seat, renders without sides)."""
        pair = self.shoulders(ring)
        return None if pair is None else 0.5 * (pair[0] + pair[1])

    # --- derived quantities (docs/model.md §2) -------------------------------------------
    @property
    def inner_groove_bottom_diameter(self) -> float:
        """d_i - 2 r_i [m]."""
        return self.inner_groove_center_diameter - 2.0 * self.inner_groove_radius

    @property
    def outer_groove_bottom_diameter(self) -> float:
        """d_o + 2 r_o [m]."""
        return self.outer_groove_center_diameter + 2.0 * self.outer_groove_radius

    @property
    def pitch_diameter(self) -> float:
        """d_m: mean of the groove-bottom diameters [m]."""
        return 0.5 * (self.inner_groove_bottom_diameter + self.outer_groove_bottom_diameter)

    @property
    def curvature_center_distance(self) -> float:
        """A = r_i + r_o - D: distance between groove curvature centres at first contact [m]."""
        return self.inner_groove_radius + self.outer_groove_radius - self.ball_diameter

    @property
    def curvature_center_radial_offset(self) -> float:
        """(d_i - d_o)/2 [m]: radial offset of the curvature-centre circles, centred rings."""
        return 0.5 * (self.inner_groove_center_diameter - self.outer_groove_center_diameter)

    @property
    def diametral_clearance(self) -> float:
        """P_d = outer bottom - inner bottom - 2D [m] (negative: preload)."""
        return (
            self.outer_groove_bottom_diameter
            - self.inner_groove_bottom_diameter
            - 2.0 * self.ball_diameter
        )

    @property
    def free_contact_angle(self) -> float:
        """alpha_0 = acos(1 - P_d/(2A)) [rad]; 0 for zero or negative clearance."""
        cos_a = 1.0 - self.diametral_clearance / (2.0 * self.curvature_center_distance)
        return math.acos(min(1.0, max(-1.0, cos_a)))

    @property
    def inner_conformity(self) -> float:
        """f_i = r_i / D."""
        return self.inner_groove_radius / self.ball_diameter

    @property
    def outer_conformity(self) -> float:
        """f_o = r_o / D."""
        return self.outer_groove_radius / self.ball_diameter

    def ball_mass(self, ball: Material) -> float:
        """m_b = rho pi D^3 / 6 [kg]."""
        return ball.density * math.pi * self.ball_diameter**3 / 6.0

    def ball_inertia(self, ball: Material) -> float:
        """J_b = m_b D^2 / 10 [kg m^2] (solid sphere)."""
        return self.ball_mass(ball) * self.ball_diameter**2 / 10.0


GUIDANCES = ("outer", "inner", "ball")
POCKET_SHAPES = ("cylindrical", "spherical")
# two lands of one ring whose diameters differ by less than this both guide the cage (equal drawn
# values stay equal when the ring grows, so this only absorbs rounding)
_SAME_LAND = 1e-9  # m


@dataclass(frozen=True)
class CageGeometry:
    """Land-guided or ball-guided cage with radial pockets (docs/model.md §2, §7, §8).

    `guidance` names what centres the cage: the outer ring's lands (the cage's outside
    diameter runs in them), the inner ring's lands (its bore runs on them) or the balls
    (no land: spherical pockets hold it). Of a ring whose two lands differ (a high and a low
    shoulder), the land with the smaller radial clearance guides; equal lands guide together.
    """

    mean_diameter: float = field(metadata={"unit": "m", "gt": 0.0, "doc": "cage mean diameter (pocket centres)"})
    pocket_diameter: float = field(metadata={"unit": "m", "gt": 0.0, "doc": "pocket diameter (pocket clearance = pocket_diameter - D)"})
    radial_thickness: float = field(metadata={"unit": "m", "gt": 0.0, "doc": "cage radial thickness (outside diameter = mean + thickness)"})
    width: float = field(metadata={"unit": "m", "gt": 0.0, "doc": "cage axial width w_c (sets its overlap with the guide lands)"})
    guidance: str = field(default="outer", metadata={
        "choices": GUIDANCES,
        "doc": "what guides the cage: 'outer' (outer-ring lands), 'inner' (inner-ring lands, which turn with "
               "the inner ring), 'ball' (the balls, through spherical pockets; no land contact)"})
    pocket_shape: str | None = field(default=None, metadata={
        "choices": POCKET_SHAPES,
        "doc": "'cylindrical' (radial axis: holds the ball along the orbit and axially) or 'spherical' (holds it "
               "in every direction, so the balls can carry the cage); default: spherical for a ball-guided cage, "
               "cylindrical otherwise"})
    land_roughness: float = field(default=1.0e-6, metadata={
        "unit": "m", "gt": 0.0, "lt": 1e-4,
        "doc": "composite RMS roughness sigma = sqrt(Rq_rim^2 + Rq_land^2) of cage rim and guide land: "
               "the film-thickness ratio h_min/sigma of the verdict (ground land ~0.25 um, bronze rim ~1 um)"})

    pocket_circle_eccentricity: float = field(default=0.0, metadata={
        "unit": "m", "ge": 0.0, "lt": 1e-3,
        "doc": "cage run-out: offset of the pocket circle's centre from the centre of the cage's guiding surface, "
               "towards pocket 0 (0: none; the reference gives no value)"})
    pocket_index_errors: tuple[float, ...] | None = field(default=None, metadata={
        "unit": "m",
        "doc": "pocket pitch errors: each pocket's position along the pitch circle minus its nominal one, "
               "one value a pocket (ball_count values; none: evenly spaced)"})
    land_length: float | None = field(default=None, metadata={
        "unit": "m", "gt": 0.0,
        "doc": "journal length L of the guide lands (both lands together); default: the cage's axial overlap "
               "with the lands (docs/model.md §8)"})

    def __post_init__(self) -> None:
        if self.pocket_index_errors is not None and any(abs(x) >= 1e-3 for x in self.pocket_index_errors):
            raise ValueError(f"pocket_index_errors = {list(self.pocket_index_errors)} m: each must be smaller "
                             "than 1e-3 m in magnitude (pitch errors of machined cages are micrometres)")
        if self.radial_thickness >= self.mean_diameter:
            raise ValueError(
                f"radial_thickness = {self.radial_thickness:g} m must be smaller than "
                f"mean_diameter = {self.mean_diameter:g} m"
            )
        if self.guidance == "ball" and self.pocket_shape == "cylindrical":
            raise ValueError(
                "guidance = 'ball' with pocket_shape = 'cylindrical': a pocket whose axis is radial cannot hold "
                "the cage radially, so nothing would centre it; give pocket_shape = 'spherical' (or leave it out), "
                "or guide the cage on a land (guidance = 'outer' or 'inner')")
        if self.guidance == "ball" and self.land_length is not None:
            raise ValueError("land_length is the journal length of the guide lands; a ball-guided cage has none: "
                             "remove it or guide the cage on a land")

    @property
    def pocket_form(self) -> str:
        """The pocket shape in use: `pocket_shape`, or its default by guidance."""
        if self.pocket_shape is not None:
            return self.pocket_shape
        return "spherical" if self.guidance == "ball" else "cylindrical"

    @property
    def guide_ring(self) -> str | None:
        """The ring whose lands guide the cage ("outer" | "inner"), None for a ball-guided cage."""
        return None if self.guidance == "ball" else self.guidance

    def check_fits(self, bearing: BearingGeometry) -> None:
        """Cross-checks against the bearing; messages name the scene keys."""
        D = bearing.ball_diameter
        if self.pocket_index_errors is not None and len(self.pocket_index_errors) != bearing.ball_count:
            raise ValueError(
                f"cage.pocket_index_errors has {len(self.pocket_index_errors)} values; give one per pocket "
                f"(bearing.ball_count = {bearing.ball_count}) [m]")
        if self.pocket_diameter <= D:
            raise ValueError(
                f"cage.pocket_diameter = {self.pocket_diameter:g} m must exceed the ball "
                f"diameter bearing.ball_diameter = {D:g} m"
            )
        spacing = self.mean_diameter * math.sin(math.pi / bearing.ball_count)
        if self.pocket_diameter >= spacing:
            raise ValueError(
                f"cage.pocket_diameter = {self.pocket_diameter:g} m leaves no bar between "
                f"pockets: the pocket spacing on the cage mean circle is {spacing:g} m"
            )
        # the guiding ring's lands here; the other ring's (and a ball-guided cage's) in the
        # scene's validity checks, which give the allowed range (pipeline.scene.validity)
        outer = bearing.shoulders("outer") if self.guidance == "outer" else None
        inner = bearing.shoulders("inner") if self.guidance == "inner" else None
        if outer is not None and self.outside_diameter >= min(outer):
            raise ValueError(
                f"cage outside diameter mean_diameter + radial_thickness = "
                f"{self.outside_diameter:g} m must be smaller than the outer ring's land "
                f"bearing.outer_shoulder_diameter = {min(outer):g} m"
            )
        if inner is not None and self.bore_diameter <= max(inner):
            raise ValueError(
                f"cage bore mean_diameter - radial_thickness = {self.bore_diameter:g} m "
                f"must exceed the inner ring's land bearing.inner_shoulder_diameter = "
                f"{max(inner):g} m"
            )

    @property
    def outside_diameter(self) -> float:
        return self.mean_diameter + self.radial_thickness

    @property
    def bore_diameter(self) -> float:
        return self.mean_diameter - self.radial_thickness

    def clearance_to(self, ring: str, land_diameter: float) -> float:
        """Radial gap between the cage and a land of `ring` of diameter `land_diameter`, centred [m]."""
        if ring == "outer":
            return 0.5 * (land_diameter - self.outside_diameter)
        return 0.5 * (self.bore_diameter - land_diameter)

    def guide_sides(self, bearing: BearingGeometry) -> tuple[int, ...]:
        """The sides (+1 toward +z, -1 toward -z) of the guiding ring whose lands guide: the one
        with the smaller clearance, or both when their diameters are equal (empty for a
        ball-guided cage)."""
        ring = self.guide_ring
        if ring is None:
            return ()
        pair = bearing.shoulders(ring)
        if pair is None:
            raise ValueError(f"bearing.{ring}_shoulder_diameter is required for a {ring}-ring-guided cage [m]")
        gaps = [self.clearance_to(ring, d) for d in pair]
        if abs(pair[0] - pair[1]) <= _SAME_LAND:
            return SIDES
        return (SIDES[0],) if gaps[0] < gaps[1] else (SIDES[1],)

    def guide_land_diameter(self, bearing: BearingGeometry) -> float:
        """Diameter of the land the cage runs on [m] (requires the shoulder diameter)."""
        ring = self.guide_ring
        if ring is None:
            raise ValueError("a ball-guided cage runs on no land (cage.guidance = 'ball')")
        return bearing.shoulder(ring, self.guide_sides(bearing)[0])

    def pocket_index_range(self) -> float:
        """Spread of the pocket pitch errors, max - min [m] (0 without them)."""
        e = self.pocket_index_errors
        return 0.0 if not e else max(e) - min(e)

    def non_guiding_rings(self) -> tuple[str, ...]:
        """The rings whose lands face the cage without guiding it."""
        return {"outer": ("inner",), "inner": ("outer",), "ball": ("inner", "outer")}[self.guidance]

    def non_guiding_land_diameter(self, bearing: BearingGeometry) -> float | None:
        """Diameter of the other ring's land nearest the cage across the non-guiding gap [m]
        (for a ball-guided cage, the nearer of the two rings' lands)."""
        nearest = self._nearest_non_guiding(bearing)
        return None if nearest is None else nearest[1]

    def _nearest_non_guiding(self, bearing: BearingGeometry) -> tuple[float, float] | None:
        best = None
        for ring in self.non_guiding_rings():
            pair = bearing.shoulders(ring)
            if pair is None:
                continue
            d = min(pair) if ring == "outer" else max(pair)
            gap = self.clearance_to(ring, d)
            if best is None or gap < best[0]:
                best = (gap, d)
        return best

    def non_guiding_clearance(self, bearing: BearingGeometry) -> float | None:
        """Radial gap between the cage and the nearest land that does not guide it, parts centred
        [m]: cage bore against the inner-ring land for an outer-guided cage, cage outside against
        the outer-ring land for an inner-guided one, the nearer of the two for a ball-guided one
        (None without those lands' diameters)."""
        nearest = self._nearest_non_guiding(bearing)
        return None if nearest is None else nearest[0]

    def guide_clearance(self, bearing: BearingGeometry) -> float:
        """Radial guide clearance C [m]: between the cage and its guiding land; for a ball-guided
        cage, the radial play c_p/2 of its spherical pockets on the balls (docs/model.md §10.1)."""
        if self.guide_ring is None:
            return 0.5 * (self.pocket_diameter - bearing.ball_diameter)
        return self.clearance_to(self.guide_ring, self.guide_land_diameter(bearing))

    def guide_land_count(self, bearing: BearingGeometry) -> int:
        """How many lands guide the cage: 2 (equal lands either side), 1, or 0 (ball-guided)."""
        return len(self.guide_sides(bearing))

    def guide_land_length(self, bearing: BearingGeometry) -> float:
        """Journal length L [m]: the cage's axial overlap with the guiding lands.

        The groove (radius r about the curvature centre, at radius d/2 from the axis) meets a
        land cylinder at axial distance z_l from the groove plane; the cage (width w_c,
        centred) overlaps that land by w_c/2 - z_l. `land_length`, when given, replaces the sum.
        """
        if self.land_length is not None:
            return self.land_length
        return sum(max(0.0, 0.5 * self.width - 0.5 * self.groove_opening_at_land(bearing, side))
                   for side in self.guide_sides(bearing))

    def groove_opening_at_land(self, bearing: BearingGeometry, side: int | None = None) -> float:
        """2 z_l [m]: twice the axial distance from the groove plane at which the guiding ring's
        groove meets its land on `side` (default: the first guiding land). The cage overlaps a
        land only where its half width exceeds z_l."""
        ring = self.guide_ring
        if ring is None:
            raise ValueError("a ball-guided cage runs on no land (cage.guidance = 'ball')")
        side = self.guide_sides(bearing)[0] if side is None else side
        land_r = 0.5 * bearing.shoulder(ring, side)
        if ring == "outer":
            rc, r = 0.5 * bearing.outer_groove_center_diameter, bearing.outer_groove_radius
        else:
            rc, r = 0.5 * bearing.inner_groove_center_diameter, bearing.inner_groove_radius
        dr = land_r - rc
        return 2.0 * math.sqrt(max(r * r - dr * dr, 0.0))

    def mass(self, cage: Material, bearing: BearingGeometry) -> float:
        """Ring mass less the Z cylindrical pockets (through the radial thickness) [kg]."""
        ring = math.pi * self.mean_diameter * self.radial_thickness * self.width
        pockets = bearing.ball_count * math.pi * 0.25 * self.pocket_diameter**2 * self.radial_thickness
        return cage.density * (ring - pockets)

    def inertia(self, cage: Material, bearing: BearingGeometry) -> tuple[float, float]:
        """(J_axial, J_diametral) [kg m^2] of a thin ring of the cage's mass.

        Thick-ring formula: J_z = m (r_o^2 + r_i^2)/2, J_x = m (3(r_o^2 + r_i^2) + w^2)/12.
        """
        m = self.mass(cage, bearing)
        ro, ri = 0.5 * self.outside_diameter, 0.5 * self.bore_diameter
        jz = 0.5 * m * (ro * ro + ri * ri)
        jx = m * (3.0 * (ro * ro + ri * ri) + self.width**2) / 12.0
        return jz, jx
