"""docs/scenes.md: the reference of every scene key, generated from the field metadata of the
dataclasses the scene loader builds (unit, range, choices, default, doc), so the document
cannot drift from what `bearingsim check` accepts (tests/test_scene_reference.py compares).

    python -m bearingsim.pipeline.scene.reference > docs/scenes.md
"""

from __future__ import annotations

import dataclasses
import math
import typing

from .schema import describe_bounds

INTRO = """# Scene reference

A scene is one TOML file (or a built-in name, `bearingsim scenes`); `--set KEY=VALUE` changes
one key on the command line with the same checks. SI units throughout, except where the key
says otherwise (`_rpm`, `_degC`). `bearingsim check SCENE` validates a scene and prints it
resolved. Besides each key's own range, every real number lies within 1e-30 .. 1e30 in size
(or is zero where the key allows zero) and every integer within 64 bits: the sizes of a
bearing's quantities in SI units, which the model's arithmetic holds (docs/reliability.md).
This page is generated from the code (`python -m bearingsim.pipeline.scene.reference`);
a test keeps it current. The model behind the keys is [docs/model.md](model.md).

Top level: `name` (required; names the run directory `runs/<name>/`), `description`
(free text), and the tables below. Required tables: `[bearing]`, `[materials]`, `[load]`,
`[speed]`. A scene computes only what it needs: no FE stage unless `hinge.source = "fe"`, no
cage contacts without `[cage]`, no film or traction without `[lubricant]` (the physics
defaults then fall back to the dry laws: `traction = "coulomb"`, `cage_race = "dry"`,
`ehd_film = false`).
"""


def _sections():
    from ...dynamics.geometry import BearingGeometry, CageGeometry, Material
    from ...dynamics.lubrication.lubricant import Lubricant

    from .sections import CatalogueBearing, Hinge, Load, Output, Physics, SolverSettings, Speed, Thermal
    from .cage_classes import CageClassThresholds
    from .sweep_section import SweepSection

    def fe():
        from ...fe_model.config import FEConfig

        return FEConfig

    return [
        ("[bearing] — form 1: groove curvature centres (the reference paper's data)", BearingGeometry,
         "Give form 1 or form 2, never both. Shoulder, bore, outside diameters and width are needed only "
         "by what uses them (ellipse truncation, the dynamic model's inner-ring mass, FE, renders)."),
        ("[bearing] — form 2: catalogue data", CatalogueBearing, ""),
        ("[cage]", CageGeometry, "Cylindrical pockets with radial axes; the cage is guided by the lands of "
                                 "the race named in `guidance`. Without `[cage]` no cage is modelled."),
        ("[materials.ball], [materials.race], [materials.cage]", Material,
         "`[materials.cage]` is required with a `[cage]` table. Each entry is a table (inline tables work: "
         "`ball = { youngs_modulus = 208e9, poisson_ratio = 0.3, density = 7850 }`), the name of a built-in "
         "material (`cage = \"pa66-gf25\"`, *Built-in materials* below), or a table that starts from one "
         "and refines it (`cage = { name = \"pa66-gf25\", youngs_modulus = 5.5e9 }`). The values serve "
         "every model alike: the Hertz contacts (ball–race, ball–pocket and cage–land effective moduli, "
         "docs/model.md §6.2, §7, §8), the masses and inertias, and the parts' thermal growth (§2.1). "
         "`bearingsim check` names the built-in material each part uses and warns when a part runs "
         "hotter than its material's continuous limit."),
        ("[lubricant]", Lubricant,
         "`name = \"nato-o156\"` loads a built-in set (*Built-in lubricants* below; docs/model.md §6.4); "
         "any key given beside it refines that set (e.g. `temperature_degC`, `eyring_stress`). Without a "
         "built-in name every key without a default is required. Every viscosity model is held at the "
         "glass viscosity 1e12 Pa·s above the pressure where it reaches it (`bearingsim check` prints "
         "that pressure)."),
        ("[thermal]", Thermal,
         "Operating geometry (docs/model.md §2.1): every length of a part grows by its material's "
         "`thermal_expansion` times its temperature rise over `reference_degC`; the screen, the quasi-static "
         "solve and the dynamics use the grown parts, the FE identification the drawing. "
         "`bearingsim check` prints the clearances cold and operating side by side. With every part at "
         "`thermal.parts_degC = 20` the scene's dimensions are used as drawn."),
        ("[load]", Load, ""),
        ("[speed]", Speed, ""),
        ("[hinge]", Hinge, "The viscoelastic hinge tying the inner race to its static frame (docs/model.md §5)."),
        ("[fe]", None, "Read only when `hinge.source = \"fe\"`; defaults suit the reference bearing. Two "
                       "models: `model = \"axisymmetric\"` (the parametric housing: the `shaft_`, `support_`, "
                       "`housing_` keys, `mesh_size`, `edge_refinement`, `load_reaction`) and `model = \"mesh\"`, "
                       "the engineer's own tetrahedral mesh (`mesh_file`, `mesh_unit`, `inner_seat`, `outer_seat`, "
                       "`fixed`, `[fe.materials]`; docs/housing-mesh.md); a key of the other model is refused."),
        ("[fe.materials.<region>]", "materials", "`model = \"mesh\"`: one table per volume region of the "
                                                 "mesh, named as the region, e.g. `housing = { youngs_modulus = "
                                                 "71e9, poisson_ratio = 0.33 }`; every tetrahedron needs one."),
        ("[solver]", SolverSettings, "Numerical settings of the dynamic run (docs/model.md §9)."),
        ("[physics]", Physics, "Which laws the contacts use and their parameters (docs/model.md §6–§8)."),
        ("[output]", Output, ""),
        ("[sweep]", SweepSection, "How `bearingsim sweep` varies the scene (docs/sweeps.md); it "
                                  "changes no stage key. `vary` maps dotted keys to `\"start:stop:count\"` or "
                                  "lists; `points` lists explicit points for `mode = \"list\"`."),
        ("[sweep.thresholds]", CageClassThresholds, "Limits of the cage classes (pipeline/scene/cage_classes.py)."),
    ], fe


def _type_name(tp) -> str:
    origin = typing.get_origin(tp)
    args = [a for a in typing.get_args(tp) if a is not type(None)]
    if origin in (typing.Union, getattr(__import__("types"), "UnionType", None)) and args:
        optional = " (optional)" if type(None) in typing.get_args(tp) else ""
        return " or ".join(_type_name(a) for a in args) + optional
    if origin is tuple:
        return "list of " + _type_name(args[0]) if args else "list"
    return getattr(tp, "__name__", str(tp)).replace("float", "number").replace("int", "integer").replace("str", "text").replace("bool", "true/false")


def _default(f) -> str:
    if f.default is not dataclasses.MISSING:
        v = f.default
    elif f.default_factory is not dataclasses.MISSING:
        return "(table)"
    else:
        return "**required**"
    if v is None:
        return "—"
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, float):
        return "inf" if math.isinf(v) else f"{v:g}"
    if isinstance(v, str):
        return f'"{v}"'
    return str(v)


def _allowed(meta: dict) -> str:
    if "choices" in meta:
        return ", ".join(f'"{c}"' for c in meta["choices"])
    bounds = describe_bounds(meta)
    if "length" in meta:
        bounds = (bounds + "; " if bounds else "") + f"{meta['length']} values"
    return bounds or "—"


def _cell(text: str) -> str:
    return str(text).replace("|", "\\|").replace("\n", " ")


def section_table(cls) -> str:
    hints = typing.get_type_hints(cls)
    rows = ["| key | type | unit | allowed | default | meaning |", "| --- | --- | --- | --- | --- | --- |"]
    for f in dataclasses.fields(cls):
        if not f.init or f.name in ("thresholds", "vary", "points") or (f.name == "region" and cls.__name__ == "RegionMaterial"):
            continue
        meta = dict(f.metadata)
        if dataclasses.is_dataclass(hints.get(f.name)):
            continue
        unit = meta.get("unit", "")
        rows.append("| " + " | ".join(_cell(c) for c in (
            f"`{f.name}`", _type_name(hints.get(f.name, f.type)), unit if unit else "—",
            _allowed(meta), _default(f), meta.get("doc", ""))) + " |")
    return "\n".join(rows)


def tolerance_section() -> str:
    """`[tolerances]`: not a dataclass but a table of quantities (pipeline/quasistatic/tolerances.py)."""
    from .tolerance_section import MAX_SAMPLES, QUANTITIES

    rows = ["## [tolerances]\n",
            "Tolerance stacks for the crush probability (docs/model.md §10.2; `bearingsim tolerances`; also "
            "computed by the quasi-static stage when the table is given, and repeated in the verdict). "
            f"`samples` (100 to {MAX_SAMPLES}, default 10000) and `seed` (default 0) set the sampling; every "
            "other key names a quantity and gives its deviation from the scene's value as "
            "`{ lower = …, upper = … }` (uniform) or `{ sd = … }` (normal, mean 0). None is given by default.\n",
            "| quantity | unit | meaning |", "| --- | --- | --- |"]
    rows += [f"| `{name}` | {unit} | {_cell(doc)} |" for name, (unit, doc) in QUANTITIES.items()]
    return "\n".join(rows) + "\n"


def builtin_lubricants_section() -> str:
    """The built-in lubricants, from their data files (dynamics/lubrication/data)."""
    from ...dynamics.lubrication.lubricant import builtin_lubricant_names, load_builtin_lubricant

    rows = ["## Built-in lubricants\n",
            "`[lubricant] name = \"...\"` (`bearingsim lubricants` prints this table). Each data file "
            "gives the source of every number; each is a modified-WLF set fitted to published "
            "viscosities and pressure–viscosity coefficients (docs/model.md §6.4).\n",
            "| name | what | η 40 °C [mPa·s] | η 100 °C [mPa·s] | α* 40 / 100 °C [1e-8 1/Pa] | sources |",
            "| --- | --- | --- | --- | --- | --- |"]
    for name in builtin_lubricant_names():
        lub = load_builtin_lubricant(name)
        cold, hot = lub.at_temperature(40.0), lub.at_temperature(100.0)
        rows.append(f"| `{name}` | {_cell(lub.description)} | {cold.eta0 * 1e3:.3g} | {hot.eta0 * 1e3:.3g} | "
                    f"{cold.alpha_star * 1e8:.3g} / {hot.alpha_star * 1e8:.3g} | {_cell(lub.source)} |")
    return "\n".join(rows) + "\n"


def builtin_materials_section() -> str:
    """The built-in materials, from their data files (dynamics/materials/data)."""
    from ...dynamics.materials.library import builtin_material_names, load_builtin_material

    rows = ["## Built-in materials\n",
            "`[materials] cage = \"...\"` (or `ball`, `race`; `bearingsim materials` prints this table). "
            "\"max\" is the continuous operating temperature of the source, where one gives it.\n",
            "| name | for | E [GPa] | ν | ρ [kg/m³] | α [1e-6/K] | max [°C] | what | sources |",
            "| --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
    for name in builtin_material_names():
        m = load_builtin_material(name)
        mat, t = m.material, m.max_temperature_degC
        rows.append(f"| `{name}` | {', '.join(m.roles)} | {mat.youngs_modulus * 1e-9:.4g} | {mat.poisson_ratio:.3g} | "
                    f"{mat.density:.4g} | {mat.thermal_expansion * 1e6:.3g} | {'—' if t is None else f'{t:g}'} | "
                    f"{_cell(m.description)} | {_cell(m.source)} |")
    return "\n".join(rows) + "\n"


def render() -> str:
    sections, fe = _sections()
    parts = [INTRO]
    for title, cls, note in sections:
        parts.append(f"## {title}\n")
        if note:
            parts.append(note + "\n")
        if cls == "materials":
            from ...fe_model.config import RegionMaterial

            cls = RegionMaterial
        parts.append(section_table(cls if cls is not None else fe()) + "\n")
    parts.append(tolerance_section())
    parts.append(builtin_lubricants_section())
    parts.append(builtin_materials_section())
    return "\n".join(parts)


if __name__ == "__main__":
    print(render(), end="")
