"""Built-in materials (docs/model.md §2.2): one data file a material in `data/<name>.toml`.

A file gives the isotropic elastic constants, the density and the linear expansion coefficient
of `geometry.Material`, the parts it may be used for (`roles`: "cage", "ball", "race"), the
maximum continuous operating temperature when a source gives one, and its sources in
comments and in `source`. A scene names a material (`materials.cage = "pa66-gf25"`), or gives
a table that may start from one (`{ name = "pa66-gf25", youngs_modulus = 5.5e9 }`).
"""

from __future__ import annotations

import tomllib
from dataclasses import dataclass
from importlib import resources

from ..geometry import Material

ROLES = ("cage", "ball", "race")
_MATERIAL_KEYS = ("youngs_modulus", "poisson_ratio", "density", "thermal_expansion")
_INFO_KEYS = ("name", "roles", "max_temperature_degC", "description", "source")


@dataclass(frozen=True)
class NamedMaterial:
    """A built-in material: its `Material`, where it may be used, and where its numbers come from."""

    name: str
    roles: tuple[str, ...]
    material: Material
    max_temperature_degC: float | None  # maximum continuous operating temperature (None: no source)
    description: str
    source: str


def _data():
    return resources.files("bearingsim.dynamics.materials") / "data"


def builtin_material_names(role: str | None = None) -> list[str]:
    """Names of the built-in materials (all, or those allowed for `role`)."""
    names = sorted(p.name[:-5] for p in _data().iterdir() if p.name.endswith(".toml"))
    return names if role is None else [n for n in names if role in load_builtin_material(n).roles]


def load_builtin_material(name: str) -> NamedMaterial:
    """Read data/<name>.toml (ValueError naming the built-in materials otherwise)."""
    path = _data() / f"{name}.toml"
    if not isinstance(name, str) or "/" in name or not path.is_file():
        raise ValueError(f"{name!r} is not a built-in material; built-in materials are "
                         f"{', '.join(builtin_material_names())}")
    table = tomllib.loads(path.read_text(encoding="utf-8"))
    unknown = sorted(set(table) - set(_MATERIAL_KEYS) - set(_INFO_KEYS))
    roles = tuple(table.get("roles", ()))
    if unknown or table.get("name") != name or not roles or not set(roles) <= set(ROLES):
        raise ValueError(f"dynamics/materials/data/{name}.toml: keys {unknown} unknown, name "
                         f"{table.get('name')!r} or roles {roles} wrong (roles among {ROLES})")
    material = Material(**{k: float(table[k]) for k in _MATERIAL_KEYS if k in table})
    t_max = table.get("max_temperature_degC")
    return NamedMaterial(name=name, roles=roles, material=material,
                         max_temperature_degC=None if t_max is None else float(t_max),
                         description=str(table.get("description", "")), source=str(table.get("source", "")))
