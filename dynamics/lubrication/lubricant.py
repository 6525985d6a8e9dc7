"""Lubricant parameter set (docs/model.md §6.4) and the built-in data files.

A `Lubricant` is a frozen dataclass with the unit and allowed range of every field in its
metadata, so the scene loader can validate a `[lubricant]` table against it. Built-in sets
live in `dynamics/lubrication/data/<name>.toml`, each number with its source in a comment.

Model parameters are stored as given; `rheology_params()` packs them, at the operating
temperature, into the contiguous float64 array the kernels of `dynamics.lubrication.rheology` take.
Barus and Roelands parameters are taken at the operating temperature (isothermal models):
changing `temperature_degC` changes only the WLF viscosity. Use `at_temperature()` to move
a WLF set, and `as_barus()` / `as_roelands()` to get the equivalent simpler models.
"""

from __future__ import annotations

import dataclasses
import math
import tomllib
from dataclasses import dataclass, field
from importlib import resources

import numpy as np

from . import rheology

KELVIN_OFFSET = 273.15


@dataclass(frozen=True)
class Lubricant:
    """Rheology, Eyring stress and density of a lubricant (docs/model.md §6.4)."""

    name: str = field(metadata={"doc": "identifier, e.g. 'nato-o156'"})
    viscosity_model: str = field(
        metadata={"choices": ("wlf", "roelands", "barus"), "doc": "pressure-viscosity law"}
    )
    temperature_degC: float = field(
        metadata={"unit": "degC", "gt": -KELVIN_OFFSET, "doc": "operating (bulk oil) temperature"}
    )
    eyring_stress: float = field(metadata={"unit": "Pa", "gt": 0.0, "doc": "Eyring stress tau0"})
    elastic_shear_modulus: float = field(
        default=1.0e9, metadata={"unit": "Pa", "gt": 0.0,
                                 "doc": "G: the film's limiting elastic shear modulus, which bounds its low-slip "
                                        "stiffness (docs/model.md §6.4, Film elasticity); 1e30: in effect a purely viscous film"}
    )
    density: float = field(
        default=900.0, metadata={"unit": "kg/m^3", "gt": 0.0, "doc": "at density_temperature_degC"}
    )
    density_temperature_degC: float = field(
        default=15.0, metadata={"unit": "degC", "gt": -KELVIN_OFFSET, "doc": "temperature at which density is given"}
    )
    density_thermal_coefficient: float = field(
        default=0.0,
        metadata={"unit": "1/K", "ge": 0.0, "lt": 0.01, "doc": "rho(T) = rho_ref (1 - beta (T - T_ref))"},
    )
    # Barus / Roelands (isothermal: values at temperature_degC)
    ambient_viscosity: float | None = field(
        default=None, metadata={"unit": "Pa.s", "gt": 0.0, "lt": rheology.GLASS_VISCOSITY,
                                "doc": "eta0, barus/roelands only (roelands: above eta_inf = 6.31e-5 Pa.s)"}
    )
    pressure_viscosity_coefficient: float | None = field(
        default=None, metadata={"unit": "1/Pa", "ge": 0.0, "doc": "Barus alpha, barus only"}
    )
    roelands_z: float | None = field(
        default=None, metadata={"unit": "-", "gt": 0.0, "le": 2.0, "doc": "Roelands index, roelands only"}
    )
    # modified WLF (Yasutomi-Bair-Winer)
    wlf_tg0_degC: float | None = field(default=None, metadata={"unit": "degC", "gt": -KELVIN_OFFSET, "doc": "T_g0: glass transition temperature at ambient pressure (modified WLF, docs/model.md §6.4)"})
    wlf_c1: float | None = field(default=None, metadata={"unit": "-", "gt": 0.0, "doc": "C1 of the modified WLF law"})
    wlf_c2_K: float | None = field(default=None, metadata={"unit": "K", "gt": 0.0, "doc": "C2 of the modified WLF law"})
    wlf_a1_K: float | None = field(default=None, metadata={"unit": "K", "ge": 0.0, "doc": "A1: T_g(p) = T_g0 + A1 ln(1 + A2 p)"})
    wlf_a2_per_Pa: float | None = field(default=None, metadata={"unit": "1/Pa", "ge": 0.0, "doc": "A2 of T_g(p)"})
    wlf_b1: float | None = field(default=None, metadata={"unit": "-", "ge": 0.0, "doc": "B1: F(p) = 1 - B1 ln(1 + B2 p)"})
    wlf_b2_per_Pa: float | None = field(default=None, metadata={"unit": "1/Pa", "ge": 0.0, "doc": "B2 of F(p)"})
    description: str = field(default="", metadata={"doc": "free text"})
    source: str = field(default="", metadata={"doc": "where the set's numbers come from (free text; built-in sets cite theirs)"})

    def __post_init__(self) -> None:
        _validate(self)

    # --- derived quantities -------------------------------------------------------
    @property
    def temperature(self) -> float:
        """Operating temperature T [K]."""
        return self.temperature_degC + KELVIN_OFFSET

    @property
    def model_code(self) -> int:
        """Integer code of the viscosity model for the kernels (rheology.MODEL_*)."""
        return rheology.MODEL_CODES[self.viscosity_model]

    def rheology_params(self) -> np.ndarray:
        """Contiguous float64 parameters of rheology.viscosity at the operating temperature."""
        if self.viscosity_model == "barus":
            p = [self.ambient_viscosity, self.pressure_viscosity_coefficient]
        elif self.viscosity_model == "roelands":
            p = [self.ambient_viscosity, self.roelands_z]
        else:
            p = [
                self.temperature, self.wlf_tg0_degC + KELVIN_OFFSET, self.wlf_a1_K,
                self.wlf_a2_per_Pa, self.wlf_b1, self.wlf_b2_per_Pa, self.wlf_c1, self.wlf_c2_K,
            ]
        return np.ascontiguousarray(p, dtype=np.float64)

    def viscosity(self, pressure: float = 0.0) -> float:
        """Low-shear viscosity eta(p) [Pa.s] at the operating temperature; p [Pa]."""
        return float(rheology.viscosity(float(pressure), self.model_code, self.rheology_params()))

    @property
    def eta0(self) -> float:
        """Ambient-pressure viscosity eta0 [Pa.s] at the operating temperature."""
        return self.viscosity(0.0)

    @property
    def alpha_star(self) -> float:
        """Approximate pressure-viscosity coefficient d ln eta/dp at p = 0 [1/Pa] (§6.4)."""
        return float(rheology.pressure_viscosity_coefficient(self.model_code, self.rheology_params()))

    def glass_pressure(self, p_max: float = 1.0e11) -> float | None:
        """The lowest pressure [Pa] at which eta(p) reaches the glass viscosity eta_g, above
        which every model holds it there (`rheology`, docs/model.md §6.4); None when eta(p_max)
        is still below eta_g. Bisection on the non-decreasing eta(p), to 1 kPa."""
        if self.viscosity(p_max) < rheology.GLASS_VISCOSITY:
            return None
        lo, hi = 0.0, p_max
        while hi - lo > 1.0e3:
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if self.viscosity(mid) < rheology.GLASS_VISCOSITY else (lo, mid)
        return hi

    def density_at_temperature(self) -> float:
        """rho at the operating temperature [kg/m^3] (linear thermal law)."""
        dT = self.temperature_degC - self.density_temperature_degC
        return self.density * (1.0 - self.density_thermal_coefficient * dT)

    def at_temperature(self, temperature_degC: float) -> "Lubricant":
        """The same lubricant at another operating temperature [degC]."""
        return dataclasses.replace(self, temperature_degC=float(temperature_degC))

    def as_barus(self) -> "Lubricant":
        """Barus lubricant with this one's eta0 and alpha* at the operating temperature."""
        return dataclasses.replace(
            self, viscosity_model="barus", ambient_viscosity=self.eta0,
            pressure_viscosity_coefficient=self.alpha_star,
        )

    def as_roelands(self) -> "Lubricant":
        """Roelands lubricant with this one's eta0 and initial slope alpha*."""
        eta0 = self.eta0
        return dataclasses.replace(
            self, viscosity_model="roelands", ambient_viscosity=eta0,
            roelands_z=rheology.roelands_z_matching(eta0, self.alpha_star),
        )


_REQUIRED = {
    "barus": ("ambient_viscosity", "pressure_viscosity_coefficient"),
    "roelands": ("ambient_viscosity", "roelands_z"),
    "wlf": ("wlf_tg0_degC", "wlf_c1", "wlf_c2_K", "wlf_a1_K", "wlf_a2_per_Pa", "wlf_b1", "wlf_b2_per_Pa"),
}
_BOUNDS = {"gt": (lambda v, b: v > b, ">"), "ge": (lambda v, b: v >= b, ">="),
           "lt": (lambda v, b: v < b, "<"), "le": (lambda v, b: v <= b, "<=")}


def _validate(lub: Lubricant) -> None:
    """Raise ValueError naming the key, the value, what is allowed and the unit."""
    where = f"lubricant '{lub.name}'"
    if lub.viscosity_model not in _REQUIRED:
        raise ValueError(
            f"{where}: viscosity_model = {lub.viscosity_model!r} is not one of "
            f"{tuple(_REQUIRED)}; choose 'wlf' (default), 'roelands' or 'barus'."
        )
    for f in dataclasses.fields(lub):
        value = getattr(lub, f.name)
        if value is None:
            if f.name in _REQUIRED[lub.viscosity_model]:
                raise ValueError(
                    f"{where}: viscosity_model = '{lub.viscosity_model}' needs {f.name} "
                    f"[{f.metadata.get('unit', '-')}]; it is missing."
                )
            continue
        for key, (ok, sym) in _BOUNDS.items():
            if key in f.metadata and not ok(value, f.metadata[key]):
                raise ValueError(
                    f"{where}: {f.name} = {value!r} is out of range; allowed {sym} "
                    f"{f.metadata[key]} [{f.metadata.get('unit', '-')}]."
                )
    eta_inf = math.exp(rheology.ROELANDS_LN_ETA_INF)
    if lub.viscosity_model == "roelands" and lub.ambient_viscosity <= eta_inf:
        raise ValueError(
            f"{where}: ambient_viscosity = {lub.ambient_viscosity!r} is at or below Roelands' eta_inf = "
            f"{eta_inf:.3g} Pa.s, where his law makes the viscosity fall with pressure; allowed > "
            f"{eta_inf:.3g} [Pa.s], or viscosity_model = 'barus'.")
    if lub.viscosity_model == "wlf" and lub.temperature_degC <= lub.wlf_tg0_degC:
        raise ValueError(
            f"{where}: temperature_degC = {lub.temperature_degC} is at or below the glass "
            f"temperature wlf_tg0_degC = {lub.wlf_tg0_degC} [degC]; the oil would be a glass. "
            "Raise the operating temperature or check the WLF set."
        )


def builtin_lubricant_names() -> list[str]:
    """Names of the lubricant data files shipped in dynamics/lubrication/data (without .toml)."""
    data = resources.files("bearingsim.dynamics.lubrication") / "data"
    return sorted(p.name[:-5] for p in data.iterdir() if p.name.endswith(".toml"))


def load_builtin_lubricant(name: str) -> Lubricant:
    """Read dynamics/lubrication/data/<name>.toml into a Lubricant (validated)."""
    names = builtin_lubricant_names()
    if name not in names:
        raise ValueError(
            f"lubricant name = {name!r} is not a built-in set; built-in sets are {names}. "
            "Give the parameters explicitly in [lubricant] instead."
        )
    text = (resources.files("bearingsim.dynamics.lubrication") / "data" / f"{name}.toml").read_text(encoding="utf-8")
    return lubricant_from_dict(tomllib.loads(text), source=f"dynamics/lubrication/data/{name}.toml")


def lubricant_from_dict(table: dict, source: str = "[lubricant]") -> Lubricant:
    """Build a Lubricant from a TOML table, rejecting unknown keys with a clear message."""
    known = {f.name for f in dataclasses.fields(Lubricant)}
    unknown = sorted(set(table) - known)
    if unknown:
        raise ValueError(f"{source}: unknown key(s) {unknown}; allowed keys are {sorted(known)}.")
    values = {k: (float(v) if isinstance(v, int) and not isinstance(v, bool) else v) for k, v in table.items()}
    try:
        return Lubricant(**values)
    except TypeError as exc:  # missing required keys
        raise ValueError(f"{source}: {exc}") from None
