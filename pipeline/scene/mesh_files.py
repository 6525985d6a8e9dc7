"""Where `fe.mesh_file` points (docs/housing-mesh.md): the engineer's mesh, or an example.

A scene file's relative `mesh_file` is relative to the scene file's folder; a scene given as
a table (the Python API, a sweep point) resolves it against the working directory. A built-in
scene names one of the example meshes that bearingsim writes itself with its gmsh scripts
(meshes/example_housing.py) into `~/.cache/bearingsim/meshes/` (or `$XDG_CACHE_HOME`;
`BEARINGSIM_MESH_CACHE` overrides it), under a name that holds the hash of everything that
shapes it, so a cached example is never stale. The resolved path is absolute and is what the
run directory's scene.toml records.
"""

from __future__ import annotations

import hashlib
import json
import os
from pathlib import Path

from .schema import SceneError

# example meshes of the built-in scenes: the name a scene gives -> (element size [m], order)
EXAMPLES = {"housing-feet.msh": (0.012, 2)}
BUILTIN_PREFIX = "built-in:"


def example_mesh_dir() -> Path:
    """The folder of the example meshes bearingsim writes."""
    if os.environ.get("BEARINGSIM_MESH_CACHE"):
        return Path(os.environ["BEARINGSIM_MESH_CACHE"]).expanduser().resolve()
    base = Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache")
    return (base / "bearingsim" / "meshes").resolve()


def _example_path(name: str) -> Path:
    from ...meshes.example_housing import recipe

    size, order = EXAMPLES[name]
    digest = hashlib.sha256(json.dumps(recipe(size, order), sort_keys=True).encode()).hexdigest()[:16]
    return example_mesh_dir() / f"{Path(name).stem}-{digest}{Path(name).suffix}"


def resolve_mesh_file(value: str, origin: str) -> str:
    """The absolute path `fe.mesh_file = value` names in a scene from `origin` (a path,
    `built-in:<name>`, or anything else for a table)."""
    if not value:
        raise SceneError("fe.mesh_file", "required by fe.model = 'mesh': the mesh file (absolute, or relative "
                                         "to the scene file)")
    path = Path(value).expanduser()
    if path.is_absolute():
        return str(path)
    if origin.startswith(BUILTIN_PREFIX):
        if value not in EXAMPLES:
            raise SceneError("fe.mesh_file", f"{value!r}: a built-in scene names one of the example meshes "
                                             f"({', '.join(EXAMPLES)})")
        return str(_example_path(value))
    folder = Path(origin).parent if origin.endswith(".toml") or Path(origin).is_file() else Path.cwd()
    return str((folder / path).resolve())


def example_for(mesh_file: str) -> tuple[str, float, int] | None:
    """(example name, element size [m], order) if `mesh_file` is the cached example mesh of
    this version, else None."""
    path = Path(mesh_file)
    for name, (size, order) in EXAMPLES.items():
        if path == _example_path(name):
            return name, size, order
    return None


def ensure_example(mesh_file: str) -> bool:
    """Write the example mesh `mesh_file` names if it is missing; True if it was written."""
    example = example_for(mesh_file)
    path = Path(mesh_file)
    if example is None or path.is_file():
        return False
    from ...meshes.example_housing import write_foot_housing_mesh

    path.parent.mkdir(parents=True, exist_ok=True)
    write_foot_housing_mesh(path, example[1], example[2])
    return True


def mesh_identity(mesh_file: str) -> dict:
    """What the identification depends on of the mesh file, for its cache key: the content's
    SHA-256 (moving or renaming the file changes nothing), or an example's recipe."""
    example = example_for(mesh_file)
    if example is not None:
        return {"example": Path(mesh_file).name}  # the name holds the hash of its recipe
    path = Path(mesh_file)
    try:
        digest = hashlib.sha256()
        with open(path, "rb") as fh:
            for block in iter(lambda: fh.read(1 << 20), b""):
                digest.update(block)
    except FileNotFoundError:
        raise SceneError("fe.mesh_file", f"{path} does not exist (a relative fe.mesh_file is relative to the scene "
                                         "file's folder)") from None
    except OSError as exc:
        raise SceneError("fe.mesh_file", f"{path} cannot be read ({exc.strerror or exc})") from None
    return {"sha256": digest.hexdigest(), "bytes": path.stat().st_size}
