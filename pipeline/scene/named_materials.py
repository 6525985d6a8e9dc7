"""`[materials]` entries by name: the built-in materials of dynamics/materials/data
(docs/scenes.md, *Built-in materials*; docs/model.md §2.2).

An entry is a name (`cage = "pa66-gf25"`), a table (`cage = { youngs_modulus = 8e9, ... }`), or a
table that starts from a name and refines it (`cage = { name = "pa66-gf25", youngs_modulus = 5.5e9 }`).
Whatever the form, the values go through the same validator as a table, so a named material is
used exactly as the same numbers written out: in the Hertz contacts (pocket, land, ball-race
effective modulus), the masses and inertias, and the thermal growth of the parts.
"""

from __future__ import annotations

import dataclasses
from typing import Any

from ...dynamics.geometry import Material
from ...dynamics.materials.library import NamedMaterial, builtin_material_names, load_builtin_material

from .schema import SceneError, build

PARTS = ("ball", "race", "cage")


def resolve_material(value: Any, key: str, role: str) -> Material:
    """The `Material` of one `[materials]` entry (SceneError naming the key and the choices)."""
    if isinstance(value, str):
        table, name_key = {"name": value}, key
    elif isinstance(value, dict):
        table, name_key = dict(value), f"{key}.name"
    else:
        raise SceneError(key, f"expected a built-in material name ({', '.join(builtin_material_names(role))}) or a "
                              f"table of youngs_modulus, poisson_ratio, density and thermal_expansion; got {value!r}")
    name = table.pop("name", None)
    if name is not None:
        named = _named(name, name_key, role)
        base = {k: v for k, v in dataclasses.asdict(named.material).items() if v is not None}
        table = {**base, **table}  # explicit keys refine the built-in material
    return build(Material, table, key)


def _named(name: Any, key: str, role: str) -> NamedMaterial:
    choices = builtin_material_names(role)
    if name not in choices:
        other = name in builtin_material_names()
        roles = " and ".join(load_builtin_material(name).roles) if other else ""
        also = f" (it is one for the {roles})" if other else ""
        raise SceneError(key, f"{name!r} is not a built-in {role} material{also}; built-in {role} materials: "
                              f"{', '.join(choices)}; or give a table of youngs_modulus [Pa], poisson_ratio [-], "
                              f"density [kg/m^3] and thermal_expansion [1/K]")
    return load_builtin_material(name)


def named_materials(scene) -> dict[str, NamedMaterial]:
    """The built-in materials a resolved scene names, by part ("ball", "race", "cage")."""
    table = scene.raw.get("materials", {})
    out = {}
    for part in PARTS:
        entry = table.get(part) if isinstance(table, dict) else None
        name = entry if isinstance(entry, str) else entry.get("name") if isinstance(entry, dict) else None
        if name is not None:
            out[part] = load_builtin_material(name)
    return out


def material_rows(scene) -> list[tuple[str, str, str]]:
    """(key, value, unit) rows for `check`: which built-in material each part uses, its source
    and its temperature limit (the values themselves are in the [materials] rows)."""
    rows = []
    for part, named in named_materials(scene).items():
        limit = "" if named.max_temperature_degC is None else f"; up to {named.max_temperature_degC:g} °C continuous"
        rows.append((f"  {part}: built-in '{named.name}'", f"{named.description}{limit} ({named.source})", ""))
    return rows


def overheated_materials(scene) -> list[tuple[str, str]]:
    """(key, message) for each part hotter than its built-in material's maximum continuous
    temperature: warnings of `validity.scene_findings`."""
    temperatures = getattr(scene, "temperatures", None)
    if temperatures is None:
        return []
    part_temperature = {"ball": temperatures.ball, "cage": temperatures.cage,
                        "race": max(temperatures.inner_ring, temperatures.outer_ring)}
    out = []
    for part, named in named_materials(scene).items():
        t = float(part_temperature[part])
        if named.max_temperature_degC is not None and t > named.max_temperature_degC:
            out.append((f"materials.{part}", f"'{named.name}' ({named.description}) is rated for continuous "
                                                    f"use up to {named.max_temperature_degC:g} °C and the {part} runs "
                                                    f"at {t:g} °C ([thermal], lubricant.temperature_degC): its "
                                                    f"stiffness and dimensions there are outside the data [degC]"))
    return out
