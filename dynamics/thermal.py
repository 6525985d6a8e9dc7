"""Operating geometry: every part at its own temperature (docs/model.md §2.1, M.120–M.122).

Drawing dimensions hold at the reference temperature T_ref (20 °C, ISO 1). In operation each
part grows freely by its linear expansion coefficient alpha and its own temperature rise:

    L_op = L_ref (1 + alpha (T_part - T_ref))                                        (M.120)

applied to every length of the part: the inner ring's groove-centre diameter, groove radius,
land and bore; the outer ring's likewise; the ball diameter; every cage length (mean diameter,
pocket diameter, thickness, width, run-out). Mass is conserved, so a density falls by the
cube of the factor. Fits, centrifugal growth of the rings and the temperature dependence of
the elastic moduli are not modelled (docs/model.md §2.1 says why they are small here).

The clearances that decide the crush screen follow as closed forms (M.121, M.122):

    Delta C   = 1/2 (alpha_race d_land - alpha_cage d_cage) Delta T    (outer-guided cage)
    Delta c_p = (alpha_cage d_p - alpha_ball D) Delta T
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field

from .geometry import BearingGeometry, CageGeometry, Material

# Default expansion coefficients [1/K] by role, used when a material gives none:
# - bearing steel: AISI 52100, 11.9e-6 1/K over 0–100 °C (ASM data for 52100, as tabulated in
#   the alloy's data sheets; hardened values reach 12.6e-6);
# - cage bronze: silicon bronze C65500 ("high-silicon bronze A", the family of the aerospace cage
#   alloy AMS 4616), 18.0e-6 1/K (Copper Development Association data sheet, 20–300 °C).
BEARING_STEEL_EXPANSION = 11.9e-6
CAGE_BRONZE_EXPANSION = 18.0e-6
ISO_REFERENCE_TEMPERATURE_DEGC = 20.0  # ISO 1: the temperature at which drawing dimensions hold


@dataclass(frozen=True)
class PartTemperatures:
    """Temperatures of the parts [°C] and the reference temperature of their dimensions."""

    reference: float = ISO_REFERENCE_TEMPERATURE_DEGC
    inner_ring: float = ISO_REFERENCE_TEMPERATURE_DEGC
    outer_ring: float = ISO_REFERENCE_TEMPERATURE_DEGC
    ball: float = ISO_REFERENCE_TEMPERATURE_DEGC
    cage: float = ISO_REFERENCE_TEMPERATURE_DEGC

    def rise(self, part: str) -> float:
        """T_part - T_ref [K]."""
        return getattr(self, part) - self.reference


@dataclass(frozen=True)
class ExpansionCoefficients:
    """Linear expansion coefficient of each part's material [1/K]."""

    race: float = field(default=BEARING_STEEL_EXPANSION)
    ball: float = field(default=BEARING_STEEL_EXPANSION)
    cage: float = field(default=CAGE_BRONZE_EXPANSION)


def growth_factor(alpha: float, rise: float) -> float:
    """1 + alpha Delta T of M.120 [-]."""
    return 1.0 + alpha * rise


def scaled(obj, factor: float, names: tuple[str, ...]):
    """`obj` (a frozen dataclass) with the length fields `names` multiplied by `factor`."""
    values = {}
    for name in names:
        v = getattr(obj, name)
        if v is None:
            continue
        values[name] = tuple(factor * x for x in v) if isinstance(v, tuple) else factor * v
    return dataclasses.replace(obj, **values)


INNER_RING_LENGTHS = ("inner_groove_center_diameter", "inner_groove_radius", "inner_shoulder_diameter",
                      "inner_bore_diameter", "width")
OUTER_RING_LENGTHS = ("outer_groove_center_diameter", "outer_groove_radius", "outer_shoulder_diameter",
                      "outer_outside_diameter")
CAGE_LENGTHS = ("mean_diameter", "pocket_diameter", "radial_thickness", "width", "pocket_circle_eccentricity",
                "pocket_index_errors", "land_length")


def operating_bearing(bearing: BearingGeometry, temperatures: PartTemperatures,
                      alpha: ExpansionCoefficients) -> BearingGeometry:
    """The bearing's rings and balls grown by M.120 (ring width follows the inner ring: it sets
    the inner ring's mass, the one ring that moves)."""
    b = scaled(bearing, growth_factor(alpha.race, temperatures.rise("inner_ring")), INNER_RING_LENGTHS)
    b = scaled(b, growth_factor(alpha.race, temperatures.rise("outer_ring")), OUTER_RING_LENGTHS)
    return scaled(b, growth_factor(alpha.ball, temperatures.rise("ball")), ("ball_diameter",))


def operating_cage(cage: CageGeometry, temperatures: PartTemperatures,
                   alpha: ExpansionCoefficients) -> CageGeometry:
    """Every cage length grown by M.120."""
    return scaled(cage, growth_factor(alpha.cage, temperatures.rise("cage")), CAGE_LENGTHS)


def operating_material(material: Material, alpha: float, rise: float) -> Material:
    """The same mass in the grown volume: rho / (1 + alpha Delta T)^3."""
    return dataclasses.replace(material, density=material.density / growth_factor(alpha, rise) ** 3)
