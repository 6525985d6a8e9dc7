"""Scene files: load TOML, apply `--set` overrides, validate, resolve (docs/scenes.md).

A `Scene` is the validated, resolved description of one physical case and how to
compute it. Nothing downstream sees raw TOML.
"""

from __future__ import annotations

import contextvars
import copy
import dataclasses
import re
import tomllib
from collections.abc import Iterable, Iterator, Mapping
from contextlib import contextmanager
from dataclasses import dataclass
from importlib import resources
from pathlib import Path
from typing import Any

from ...dynamics import thermal as th
from ...dynamics.geometry import BearingGeometry, CageGeometry, Material
from ...dynamics.journal.land_laws import LAWS as LAND_LAWS
from ...dynamics.traction.laws import LAWS as TRACTION_LAWS

from .sections import (
    CatalogueBearing,
    Hinge,
    Load,
    Materials,
    Output,
    Physics,
    SolverSettings,
    Speed,
    Thermal,
)
from .schema import SceneError, build, check_number, convert, describe_bounds, unit_suffix

FORM1_KEYS = ("inner_groove_center_diameter", "outer_groove_center_diameter",
              "inner_groove_radius", "outer_groove_radius")
FORM2_KEYS = ("pitch_diameter", "inner_conformity", "outer_conformity", "diametral_clearance")
MAX_SCENE_BYTES = 1_000_000  # [B] the built-in scenes are 2-5 kB
TOP_LEVEL = ("name", "description", "bearing", "cage", "materials", "lubricant", "load",
             "speed", "hinge", "fe", "solver", "physics", "output", "sweep", "thermal", "tolerances")


@dataclass(frozen=True)
class Parts:
    """Bearing, cage and materials at one temperature state."""

    bearing: BearingGeometry
    cage: CageGeometry | None
    materials: Materials


_BUILDING = contextvars.ContextVar("bearingsim_scene_building", default=False)


@contextmanager
def _building():
    """The resolver (and the few internal variants of a resolved scene) may construct a Scene."""
    token = _BUILDING.set(True)
    try:
        yield
    finally:
        _BUILDING.reset(token)


@dataclass(frozen=True, repr=False)
class Scene:
    """A validated scene (docs/scenes.md): build it with `bearingsim.load_scene`, change it with
    `replace`, which validates the change as the file would be.

    `bearing`, `cage` and `materials` are the parts as the scene gives them (as drawn, at
    `temperatures.reference`); `operating` holds them grown to their operating temperatures
    (docs/model.md §2.1), which is what the quasi-static and dynamic stages compute with. The
    FE identification meshes the parts as drawn. `raw` is the validated TOML table after
    overrides (`to_dict`), from which the scene is rebuilt exactly."""

    name: str
    description: str
    bearing: BearingGeometry
    cage: CageGeometry | None
    materials: Materials
    lubricant: Any | None  # dynamics.lubrication.lubricant.Lubricant (at its operating temperature)
    load: Load
    speed: Speed
    hinge: Hinge
    fe: Any | None  # fe_model.config.FEConfig when hinge.source == "fe"
    solver: SolverSettings
    physics: Physics
    output: Output
    raw: dict  # the validated TOML table after overrides (for saving and hashing)
    operating: Parts  # bearing, cage and materials at their operating temperatures
    temperatures: th.PartTemperatures = th.PartTemperatures()
    expansion: th.ExpansionCoefficients = th.ExpansionCoefficients()
    tolerances: Any | None = None  # pipeline.quasistatic.tolerances.ToleranceSpec when [tolerances] is given

    def __post_init__(self) -> None:
        if not _BUILDING.get():
            raise TypeError(
                "a Scene is built by bearingsim.load_scene and changed by scene.replace(...), e.g. "
                "scene.replace(**{'load.moment': 500}), which validates the change as the scene file "
                "would be; dataclasses.replace and Scene(...) would skip that validation")

    @property
    def nominal(self) -> Parts:
        """The parts as the scene gives them (as drawn): `bearing`, `cage`, `materials` together."""
        return Parts(self.bearing, self.cage, self.materials)

    def replace(self, changes: Mapping[str, Any] | Iterable[str] | None = None, /, **dotted: Any) -> "Scene":
        """A new scene with `changes` applied and validated exactly as the scene file would be:
        ``scene.replace(**{"load.moment": 500})``, ``scene.replace({"solver.duration": 0.1})``
        or ``scene.replace(["load.moment=500"])``. A bad value raises the `SceneError` the file
        would give (key, value, allowed range, unit)."""
        strings = override_strings(changes) + override_strings(dotted)
        scene = resolve(apply_overrides(self.raw, strings), self.origin)
        object.__setattr__(scene, "_origin", self.origin)
        return scene

    @property
    def origin(self) -> str:
        """Where the scene came from: a path, `built-in:<name>`, or how Python gave it."""
        return getattr(self, "_origin", "a Scene object of the Python API")

    def to_dict(self) -> dict:
        """The scene as a TOML-shaped dict (a copy of `raw`: the keys the scene gives, after
        overrides); `load_scene(scene.to_dict()) == scene`. A `[sweep]` table is not part of
        the scene and is not kept."""
        return copy.deepcopy(self.raw)

    def to_toml(self) -> str:
        """The scene as TOML text; `load_scene(scene.to_toml()) == scene`."""
        import tomli_w

        return tomli_w.dumps(self.raw)

    def __repr__(self) -> str:
        from .display import scene_repr

        return scene_repr(self)

    def _repr_html_(self) -> str:
        from .display import scene_html

        return scene_html(self)


# --- built-in scenes -------------------------------------------------------------------
def builtin_scene_names() -> list[str]:
    files = resources.files("bearingsim.pipeline") / "scenes"
    return sorted(p.name[:-5] for p in files.iterdir() if p.name.endswith(".toml"))


def builtin_scene_text(name: str) -> str:
    """The TOML text of a built-in scene (SceneError naming the built-in scenes otherwise)."""
    names = builtin_scene_names()
    if name not in names:
        shown = name if len(name) <= 80 else name[:77] + "..."
        raise SceneError("", f"{shown!r} is neither a scene file nor a built-in scene; "
                             f"built-in scenes: {', '.join(names)}")
    return (resources.files("bearingsim.pipeline") / "scenes" / f"{name}.toml").read_text(encoding="utf-8")


def read_scene_table(scene: str | Path) -> tuple[dict, str]:
    """Read a scene path or built-in name into a TOML table; returns (table, origin).
    Every way a file can be unreadable is a SceneError naming the file and what to do."""
    text_arg = str(scene)
    if not text_arg.strip():
        raise SceneError("", "the scene argument is empty; give a scene file (.toml) or the name of a built-in "
                             "scene (bearingsim scenes lists them)")
    if "\0" in text_arg:
        raise SceneError("", f"the scene argument {text_arg!r} contains a NUL byte; give a scene file "
                             "path or a built-in scene name")
    path = Path(scene)
    shown = text_arg if len(text_arg) <= 80 else text_arg[:77] + "..."
    try:
        # a built-in name wins over a folder of the same name (e.g. a run directory runs/<name>/)
        is_path = path.suffix == ".toml" or (path.exists() and not (path.is_dir() and text_arg in builtin_scene_names()))
    except (OSError, ValueError):
        is_path = True  # e.g. a name too long for the file system: reported below
    if is_path:
        try:
            data = _read_scene_file(path, shown)
        except SceneError:
            raise
        except IsADirectoryError:
            raise SceneError("", f"scene file {shown!r} is a directory; give a .toml file") from None
        except FileNotFoundError:
            raise SceneError("", f"scene file {shown!r} does not exist") from None
        except (OSError, ValueError) as exc:
            reason = exc.strerror if isinstance(exc, OSError) and exc.strerror else str(exc)
            raise SceneError("", f"scene file {shown!r} cannot be read ({reason})") from None
        origin = str(path)
        data = data.removeprefix(b"\xef\xbb\xbf")  # a byte-order mark some editors write: not TOML
        try:
            text = data.decode("utf-8")
        except UnicodeDecodeError as exc:
            line = data[:exc.start].count(b"\n") + 1
            raise SceneError("", f"{origin} is not UTF-8 text (byte 0x{data[exc.start]:02x} on line {line}); "
                                 "save the scene as UTF-8 (TOML files are UTF-8)") from None
    else:
        text = builtin_scene_text(text_arg)
        origin = f"built-in:{scene}"
    try:
        return tomllib.loads(text), origin
    except tomllib.TOMLDecodeError as exc:
        raise SceneError("", f"{origin} is not valid TOML: {exc}") from exc
    except ValueError:  # an integer of more digits than Python reads (4300)
        raise SceneError("", f"{origin} holds an integer of more than 4300 digits; a scene's numbers are "
                             "values in SI units") from None
    except RecursionError:
        raise SceneError("", f"{origin} nests arrays or tables too deeply to read; a scene needs at most "
                             "two levels (e.g. hinge.translational as a 3x3 matrix)") from None


def _read_scene_file(path: Path, shown: str) -> bytes:
    """The bytes of a regular scene file of at most MAX_SCENE_BYTES; a device, a FIFO or an
    oversized file is refused before it is read (bounded time and memory)."""
    import os
    import stat

    def check(mode: int) -> None:
        if stat.S_ISDIR(mode):
            raise IsADirectoryError(path)
        if not stat.S_ISREG(mode):
            raise SceneError("", f"scene file {shown!r} is not a regular file (a device, a FIFO or a socket); "
                                 "give a .toml file")

    check(os.stat(path).st_mode)
    fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_CLOEXEC", 0))
    with os.fdopen(fd, "rb") as fh:
        check(os.fstat(fd).st_mode)  # the same file as the one checked (it may have been swapped)
        data = fh.read(MAX_SCENE_BYTES + 1)
    if len(data) > MAX_SCENE_BYTES:
        raise SceneError("", f"scene file {shown!r} is larger than {MAX_SCENE_BYTES // 1000} kB; a scene is a "
                             "few kB of TOML: give the scene file, not a data file")
    return data


# --- overrides -------------------------------------------------------------------------
def parse_override(text: str) -> tuple[list[str], Any]:
    """`load.moment=250` -> (["load", "moment"], 250.0). Values are TOML literals; a bare
    word that is not valid TOML is taken as a string (`name=foo`)."""
    if "=" not in text:
        raise SceneError("", f"--set expects KEY=VALUE (e.g. load.moment=250), got {text!r}")
    if "\n" in text or "\r" in text:  # TOML would read the lines after the first as more tables
        raise SceneError("", f"--set: {text!r} holds a line break; give one KEY=VALUE per --set")
    key, value_text = (s.strip() for s in text.split("=", 1))
    if not key or any(not part for part in key.split(".")):
        raise SceneError("", f"--set: bad key {key!r} in {text!r}")
    try:
        value = tomllib.loads(f"v = {value_text}")["v"]
    except tomllib.TOMLDecodeError:
        value = value_text
    except ValueError:  # an integer of more digits than Python reads (4300)
        raise SceneError(key, f"--set: the value is an integer of {len(value_text)} digits; give a number "
                              "of the key's unit") from None
    except RecursionError:
        raise SceneError(key, f"--set: the value nests arrays too deeply ({len(value_text)} characters)") from None
    return key.split("."), value


def override_strings(overrides: Mapping[str, Any] | Iterable[str] | None) -> list[str]:
    """`{"load.moment": 300}` -> `["load.moment=300"]`; strings pass through. A nested
    mapping is flattened to dotted keys (`{"materials.ball": {"density": 7800}}`)."""
    if overrides is None:
        return []
    if isinstance(overrides, str):
        return [overrides]
    if not isinstance(overrides, Mapping):
        return [str(o) for o in overrides]
    out = []
    for key, value in _flatten(overrides, ""):
        out.append(f"{key}={_toml_literal(key, value)}")
    return out


def _flatten(mapping: Mapping, prefix: str) -> Iterator[tuple[str, Any]]:
    for key, value in mapping.items():
        dotted = f"{prefix}{key}"
        if isinstance(value, Mapping):
            yield from _flatten(value, dotted + ".")
        else:
            yield dotted, value


def _toml_literal(key: str, value: Any) -> str:
    import numpy as np
    import tomli_w

    if isinstance(value, np.ndarray):
        value = value.tolist()
    elif isinstance(value, np.generic):
        value = value.item()
    elif isinstance(value, tuple):
        value = list(value)
    elif isinstance(value, Path):
        value = str(value)
    if isinstance(value, list):  # one line, as typed after --set
        return "[" + ", ".join(_toml_literal(key, v) for v in value) + "]"
    try:
        return tomli_w.dumps({"v": value})[len("v = "):].strip()
    except (TypeError, ValueError) as exc:
        raise SceneError(key, f"{value!r} cannot be written as a TOML value: {exc}") from None


def apply_overrides(table: dict, overrides: list[str]) -> dict:
    table = copy.deepcopy(table)
    for text in overrides:
        path, value = parse_override(text)
        node = table
        for part in path[:-1]:
            nxt = node.setdefault(part, {})
            if isinstance(nxt, str) and node is table.get("materials"):  # a built-in name: refine it
                nxt = node[part] = {"name": nxt}
            if not isinstance(nxt, dict):
                raise SceneError(".".join(path), f"--set: {part!r} is a value, not a table")
            node = nxt
        node[path[-1]] = value
    return table


# --- resolution ------------------------------------------------------------------------
def resolve_bearing(table: Any) -> BearingGeometry:
    if not isinstance(table, dict):
        raise SceneError("bearing", f"expected a table, got {table!r}")
    has1 = [k for k in FORM1_KEYS if k in table]
    has2 = [k for k in FORM2_KEYS if k in table]
    if has1 and has2:
        raise SceneError("bearing", f"give geometry form 1 ({', '.join(FORM1_KEYS)}) OR form 2 "
                                    f"({', '.join(FORM2_KEYS)}), never both: found {has1 + has2}")
    if has2:
        cat = build(CatalogueBearing, table, "bearing")
        values = dataclasses.asdict(cat)
        try:
            return BearingGeometry.from_catalogue(**values)
        except ValueError as exc:
            raise SceneError("bearing", str(exc)) from exc
    return build(BearingGeometry, table, "bearing")


def resolve_materials(table: Any, need_cage: bool) -> Materials:
    if not isinstance(table, dict):
        raise SceneError("materials", f"expected a table, got {table!r}")
    allowed = {"ball", "race", "cage"}
    unknown = sorted(set(table) - allowed)
    if unknown:
        raise SceneError(f"materials.{unknown[0]}", "unknown key; allowed keys here: ball, cage, race")
    if need_cage and "cage" not in table:
        raise SceneError("materials.cage", "required when the scene has a [cage] table")
    for key in ("ball", "race"):
        if key not in table:
            raise SceneError(f"materials.{key}", "required table is missing")
    from .named_materials import resolve_material  # a name or a table (docs/scenes.md)

    return Materials(
        ball=resolve_material(table["ball"], "materials.ball", "ball"),
        race=resolve_material(table["race"], "materials.race", "race"),
        cage=resolve_material(table["cage"], "materials.cage", "cage") if "cage" in table else None,
    )


def resolve_lubricant(table: Any):
    """`[lubricant]`: a built-in set by `name` (its keys may be refined, e.g.
    `temperature_degC`), or a complete explicit parameter set."""
    if table is None:
        return None
    if not isinstance(table, dict):
        raise SceneError("lubricant", f"expected a table, got {table!r}")
    from ...dynamics.lubrication import lubricant as lub  # light: numpy + a data file

    table = dict(table)
    name = table.get("name")
    names = lub.builtin_lubricant_names()
    if name in names:
        base = dataclasses.asdict(lub.load_builtin_lubricant(name))
        base.update(table)  # explicit keys refine the built-in set
        table = base
    elif "viscosity_model" not in table:
        raise SceneError("lubricant.name", f"{name!r} is not a built-in lubricant; choose one of "
                                           f"{', '.join(names)} or give the parameters explicitly")
    return build(lub.Lubricant, table, "lubricant")


def resolve_fe(table: Any, hinge: Hinge, origin: str = "<table>") -> Any | None:
    """`[fe]` as fe_model's FEConfig: the generic checks, `[fe.materials.<region>]` tables, no key
    of the other model (fe_model.config.MESH_KEYS / AXISYMMETRIC_KEYS), and `mesh_file` made
    absolute (relative to the scene file; for a built-in scene, the example meshes bearingsim
    writes itself, pipeline/scene/mesh_files.py)."""
    if hinge.source != "fe":
        return None
    from ...fe_model.config import AXISYMMETRIC_KEYS, MESH_KEYS, FEConfig, RegionMaterial

    table = {} if table is None else table
    if not isinstance(table, dict):
        raise SceneError("fe", f"expected a table, got {table!r}")
    table = dict(table)
    materials = table.pop("materials", {})
    config = build(FEConfig, table, "fe")
    other = AXISYMMETRIC_KEYS if config.model == "mesh" else MESH_KEYS
    given = [k for k in other if k in table or (k == "materials" and materials)]
    if given:
        reader = "axisymmetric" if config.model == "mesh" else "mesh"
        raise SceneError(f"fe.{given[0]}", f"only read by fe.model = {reader!r} (fe.model is {config.model!r}); "
                                           f"remove it, or set fe.model = {reader!r}")
    if config.model != "mesh":
        return config
    if not isinstance(materials, dict):
        raise SceneError("fe.materials", f"expected a table of volume regions, each a table with youngs_modulus "
                                         f"[Pa] and poisson_ratio, got {materials!r}")
    regions = []
    for name, body in materials.items():
        key = f"fe.materials.{name}"
        if not isinstance(body, dict):
            raise SceneError(key, f"expected a table with youngs_modulus [Pa] and poisson_ratio, got {body!r}")
        if "region" in body:
            raise SceneError(f"{key}.region", "unknown key; the region is the table's name; allowed keys here: "
                                              "poisson_ratio, youngs_modulus")
        for needed in ("youngs_modulus", "poisson_ratio"):
            if needed not in body:
                raise SceneError(f"{key}.{needed}", "required key is missing" + (" [Pa]" if needed[0] == "y" else ""))
        regions.append(build(RegionMaterial, {**body, "region": str(name)}, key))
    from .mesh_files import resolve_mesh_file

    mesh_file = resolve_mesh_file(config.mesh_file, origin)
    return dataclasses.replace(config, materials=tuple(regions), mesh_file=mesh_file)


def resolve(table: dict, origin: str = "<table>") -> Scene:
    """Validate a raw scene table into a `Scene`; raises SceneError."""
    unknown = sorted(set(table) - set(TOP_LEVEL))
    if unknown:
        raise SceneError(unknown[0], f"unknown key or table in {origin}; allowed: {', '.join(TOP_LEVEL)}")
    for key in ("name", "bearing", "materials", "load", "speed"):
        if key not in table:
            raise SceneError(key, f"required {'key' if key == 'name' else 'table'} is missing in {origin}")
    if "sweep" in table:  # how to vary the scene, not physics: validated, then kept out of raw
        from .sweep_section import build_sweep_section

        build_sweep_section(table["sweep"])
        table = {k: v for k, v in table.items() if k != "sweep"}
    name = check_name("name", convert("name", table["name"], str, {}))
    bearing = resolve_bearing(table["bearing"])
    cage = build(CageGeometry, table["cage"], "cage") if "cage" in table else None
    if cage is not None:
        try:
            cage.check_fits(bearing)
        except ValueError as exc:
            raise SceneError("cage", str(exc)) from exc
    hinge_table = table.get("hinge", {})
    if isinstance(hinge_table, dict) and _is_matrix(hinge_table.get("translational")):
        # a 3x3 H_u as nested lists (as hinge.toml writes it): flatten row-major
        rows = hinge_table["translational"]
        if len(rows) != 3 or any(len(r) != 3 for r in rows):
            raise SceneError("hinge.translational", "a matrix must be 3x3 [N/m]")
        hinge_table = {**hinge_table, "translational": [x for r in rows for x in r]}
    hinge = build(Hinge, hinge_table, "hinge")
    lubricant = resolve_lubricant(table.get("lubricant"))
    physics_table = table.get("physics", {})
    if lubricant is None and isinstance(physics_table, dict):
        # docs/scenes.md: without [lubricant], contacts are dry; defaults fall back to the dry laws
        physics_table = {"traction": "coulomb", "cage_race": "dry", "ehd_film": False, **physics_table}
    physics = build(Physics, physics_table, "physics")
    film_law = TRACTION_LAWS[physics.traction].film
    if film_law and lubricant is None:
        raise SceneError("physics.traction", f"{physics.traction!r} needs a [lubricant] table; give one, or set "
                                             "physics.traction = 'coulomb' (dry) or 'none'")
    if film_law and not physics.ehd_film:
        raise SceneError("physics.ehd_film", f"false, but {physics.traction!r} traction needs the EHD film "
                                             "thickness; set it true or physics.traction = 'coulomb'")
    if LAND_LAWS[physics.cage_race].film and cage is not None and lubricant is None:
        raise SceneError("physics.cage_race", f"{physics.cage_race!r} needs a [lubricant] table "
                                              "(film viscosity); give one or set it to 'dry'")
    materials = resolve_materials(table["materials"], need_cage=cage is not None)
    temperatures = resolve_temperatures(table.get("thermal", {}), lubricant)
    expansion = th.ExpansionCoefficients(
        race=_alpha(materials.race, th.BEARING_STEEL_EXPANSION), ball=_alpha(materials.ball, th.BEARING_STEEL_EXPANSION),
        cage=_alpha(materials.cage, th.CAGE_BRONZE_EXPANSION))
    nominal = Parts(bearing, cage, materials)
    fe = resolve_fe(table.get("fe"), hinge, origin)
    with _building():
        scene = Scene(
            name=name,
            description=convert("description", table.get("description", ""), str, {}),
            bearing=bearing,
            cage=cage,
            materials=materials,
            lubricant=lubricant,
            load=build(Load, table["load"], "load"),
            speed=build(Speed, table["speed"], "speed"),
            hinge=hinge,
            fe=fe,
            solver=build(SolverSettings, table.get("solver", {}), "solver"),
            physics=physics,
            output=build(Output, table.get("output", {}), "output"),
            raw=_with_mesh_file(table, fe),
            operating=nominal,  # until grown below: the checks that follow read the parts as drawn
            temperatures=temperatures,
            expansion=expansion,
        )
    # geometry the model cannot represent, resources a run cannot have (pipeline.scene.validity),
    # checked on the parts as drawn; then the parts grown to their operating temperatures
    from .validity import raise_errors, scene_findings

    raise_errors(scene_findings(scene))
    scene = variant(scene, operating=operating_parts(nominal, temperatures, expansion))
    if "tolerances" in table:
        from .tolerance_section import build_tolerance_spec

        scene = variant(scene, tolerances=build_tolerance_spec(table["tolerances"], scene))
    return scene


def variant(scene: Scene, **fields: Any) -> Scene:
    """`scene` with `fields` replaced, unvalidated: for bearingsim's own derived scenes (a
    tolerance stack's grown parts, a compile-only hinge), never for user input (`Scene.replace`)."""
    with _building():
        return dataclasses.replace(scene, **fields)


def _with_mesh_file(table: dict, fe) -> dict:
    """The scene table with fe.mesh_file as resolved (absolute): the run directory's scene.toml,
    sweep points and `bearingsim render` then find the mesh wherever they run."""
    if fe is None or getattr(fe, "model", None) != "mesh" or table.get("fe", {}).get("mesh_file") == fe.mesh_file:
        return table
    return {**table, "fe": {**table["fe"], "mesh_file": fe.mesh_file}}


def _alpha(material: Material | None, default: float) -> float:
    return default if material is None or material.thermal_expansion is None else material.thermal_expansion


def resolve_temperatures(table: Any, lubricant) -> th.PartTemperatures:
    """`[thermal]` with its defaults filled in (docs/scenes.md)."""
    thermal = build(Thermal, table, "thermal")
    oil = lubricant.temperature_degC if lubricant is not None else thermal.reference_degC
    parts = thermal.parts_degC if thermal.parts_degC is not None else oil
    if thermal.parts_degC is None:  # the parts take the oil's temperature: parts_degC's range holds
        meta = dict(Thermal.__dataclass_fields__["parts_degC"].metadata)
        try:
            check_number("thermal.parts_degC", oil, meta)
        except SceneError:
            raise SceneError("lubricant.temperature_degC",
                             f"{oil:g} is out of range for the parts, which take the oil's temperature "
                             f"(thermal.parts_degC not given); allowed {describe_bounds(meta)}{unit_suffix(meta)}, "
                             f"or give thermal.parts_degC") from None

    def part(value):
        return parts if value is None else value

    return th.PartTemperatures(reference=thermal.reference_degC, inner_ring=part(thermal.inner_ring_degC),
                               outer_ring=part(thermal.outer_ring_degC), ball=part(thermal.ball_degC),
                               cage=part(thermal.cage_degC))


def operating_parts(nominal: Parts, temperatures: th.PartTemperatures,
                    expansion: th.ExpansionCoefficients) -> Parts:
    """The parts grown to their temperatures (M.120); the race material's density follows the
    inner ring, the ring that moves."""
    m = nominal.materials
    try:
        bearing = th.operating_bearing(nominal.bearing, temperatures, expansion)
        cage = th.operating_cage(nominal.cage, temperatures, expansion) if nominal.cage is not None else None
        if cage is not None:
            cage.check_fits(bearing)
    except ValueError as exc:
        raise SceneError("thermal", f"at the operating temperatures: {exc}") from exc
    materials = Materials(
        ball=th.operating_material(m.ball, expansion.ball, temperatures.rise("ball")),
        race=th.operating_material(m.race, expansion.race, temperatures.rise("inner_ring")),
        cage=None if m.cage is None else th.operating_material(m.cage, expansion.cage, temperatures.rise("cage")))
    return Parts(bearing, cage, materials)


NAME_MAX = 100
_NAME = re.compile(r"[A-Za-z0-9][A-Za-z0-9._+-]*")


def check_name(key: str, name: str, max_length: int = NAME_MAX) -> str:
    """A scene (or sweep) name becomes a folder name under runs/: plain characters only."""
    if not _NAME.fullmatch(name) or len(name) > max_length:
        shown = name if len(name) <= 60 else name[:57] + "..."
        raise SceneError(key, f"{shown!r} cannot name a run directory: use 1 to {max_length} letters, digits, "
                              f"'-', '_', '.' or '+', starting with a letter or digit (no spaces, slashes or "
                              f"shell characters), e.g. my-6209")
    return name


def _is_matrix(value: Any) -> bool:
    return isinstance(value, list) and bool(value) and all(isinstance(r, list) for r in value)


def is_toml_text(scene: Any) -> bool:
    """A string that is a scene's TOML text rather than a path or a built-in name: it holds a
    line break, or a `key = value` and does not name a .toml file."""
    return isinstance(scene, str) and ("\n" in scene or ("=" in scene and not scene.rstrip().endswith(".toml")))


def scene_table(scene: Any) -> tuple[dict, str]:
    """(TOML table, origin) of a Scene, a dict (TOML-shaped: tables as dicts, dotted keys not
    split), a scene's TOML text, a scene file path or a built-in scene name."""
    if isinstance(scene, Scene):
        return scene.to_dict(), scene.origin
    if isinstance(scene, Mapping):
        return plain_table(scene, ""), "a dict of the Python API"
    if is_toml_text(scene):
        try:
            return tomllib.loads(scene), "TOML text of the Python API"
        except tomllib.TOMLDecodeError as exc:
            raise SceneError("", f"the scene text is not valid TOML: {exc}") from None
    if not isinstance(scene, (str, Path)):
        raise SceneError("", f"a scene is a file path, a built-in scene name, TOML text, a dict or a Scene; "
                             f"got {type(scene).__name__}")
    return read_scene_table(scene)


def plain_table(mapping: Mapping, prefix: str) -> dict:
    """A dict of Python values as the TOML table it stands for: tuples and numpy arrays as
    lists, numpy scalars as numbers, paths as strings (SceneError for what TOML cannot hold)."""
    import numpy as np

    def plain(key: str, value: Any) -> Any:
        if isinstance(value, Mapping):
            return plain_table(value, f"{key}.")
        if isinstance(value, np.ndarray):
            value = value.tolist()
        if isinstance(value, (list, tuple)):
            return [plain(key, v) for v in value]
        if isinstance(value, np.generic):
            return value.item()
        if isinstance(value, Path):
            return str(value)
        if value is None or not isinstance(value, (str, int, float, bool)):
            raise SceneError(key, f"{value!r} is not a TOML value (a number, string, boolean, list or table)")
        return value

    out = {}
    for key, value in mapping.items():
        if not isinstance(key, str):
            raise SceneError(prefix.rstrip("."), f"table keys are strings, got {key!r}")
        out[key] = plain(f"{prefix}{key}", value)
    return out


def load_scene(scene: Any, overrides: Mapping[str, Any] | Iterable[str] | None = None) -> Scene:
    """A validated Scene from a scene file path, a built-in scene name, a scene's TOML text, a
    dict or another Scene, with `overrides` (``{"load.moment": 300}`` or ``["load.moment=300"]``)
    applied and validated exactly as the file's values are."""
    table, origin = scene_table(scene)
    resolved = resolve(apply_overrides(table, override_strings(overrides)), origin)
    # provenance for scene.toml's header; a frozen dataclass, so set past its __setattr__
    object.__setattr__(resolved, "_origin", origin)
    return resolved
