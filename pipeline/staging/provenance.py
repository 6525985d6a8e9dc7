"""What a run directory keeps besides results: resolved scene, versions, log; and the
code version that enters every stage's cache key."""

from __future__ import annotations

import functools
import hashlib
import logging
import platform
import subprocess
import sys
from importlib import metadata
from pathlib import Path

import tomli_w

from .artefacts import SCENE_HEADER, OutputRefused, atomic_write_json, atomic_write_text, is_own_scene_file
from .no_follow import out_name

PACKAGES = ("bearingsim", "numpy", "scipy", "numba", "scikit-fem", "gmsh", "meshio",
            "pyvista", "vtk", "matplotlib", "h5py", "typer", "rich", "filelock", "pypardiso")
# the folders installed as bearingsim.* (pyproject.toml); their sources are the model
SOURCE_FOLDERS = ("pipeline", "dynamics", "fe_model", "meshes")
SOURCE_SUFFIXES = (".py", ".toml")


def package_version() -> str:
    try:
        return metadata.version("bearingsim")
    except metadata.PackageNotFoundError:
        return "0+unknown"


def source_checkout() -> Path | None:
    """The repository root when bearingsim runs from a source checkout (an editable
    install or a bare checkout), else None (an installed wheel)."""
    root = Path(__file__).resolve().parents[2]  # pipeline/staging/ -> the repository root
    if (root / "pyproject.toml").is_file() and all((root / f).is_dir() for f in SOURCE_FOLDERS):
        return root
    return None


@functools.lru_cache(maxsize=1)
def source_fingerprint() -> str | None:
    """sha256 of the package sources (.py and data .toml) of a source checkout, else None.

    An editable install keeps its version number while the code changes under it; without
    this, a stage computed by old code would be served from the cache after an edit."""
    root = source_checkout()
    if root is None:
        return None
    digest = hashlib.sha256()
    for folder in SOURCE_FOLDERS:
        for path in sorted((root / folder).rglob("*")):
            if path.suffix in SOURCE_SUFFIXES and "__pycache__" not in path.parts and path.is_file():
                digest.update(path.relative_to(root).as_posix().encode())
                digest.update(b"\0")
                digest.update(path.read_bytes())
                digest.update(b"\0")
    return digest.hexdigest()


def code_version() -> str:
    """The version every stage key includes: the package version, plus the fingerprint of
    the sources when running from a checkout (editing any source then reruns stages)."""
    fingerprint = source_fingerprint()
    version = package_version()
    return f"{version}+src.{fingerprint[:16]}" if fingerprint else version


def versions() -> dict:
    out = {"python": sys.version.split()[0], "platform": platform.platform()}
    for name in PACKAGES:
        try:
            out[name] = metadata.version(name)
        except metadata.PackageNotFoundError:
            out[name] = None
    try:
        here = Path(__file__).resolve().parent
        commit = subprocess.run(["git", "-C", str(here), "rev-parse", "HEAD"],
                                capture_output=True, text=True, timeout=5)
        out["git_commit"] = commit.stdout.strip() or None
    except (OSError, subprocess.SubprocessError):
        out["git_commit"] = None
    out["source_fingerprint"] = source_fingerprint()
    return out


def write_run_provenance(run_dir: Path, raw_scene: dict, origin: str) -> None:
    """Save the resolved scene (after overrides) and the package versions.

    A scene.toml that bearingsim did not write (no header line: the user's own scene, e.g.
    `--out .` in the folder that holds it) is never overwritten."""
    run_dir.mkdir(parents=True, exist_ok=True)
    scene_file = run_dir / "scene.toml"
    if scene_file.exists() and not is_own_scene_file(scene_file):
        raise OutputRefused(
            f"{scene_file} is a scene file of yours, not one bearingsim wrote; the run would "
            f"replace it with the resolved scene. Give the run its own directory with {out_name()}, "
            f"e.g. {out_name(run_dir / 'run')}")
    origin_text = " ".join(str(origin).split())  # one line, whatever the path holds
    header = f"{SCENE_HEADER} (from {origin_text}, after --set overrides), as used by this run.\n"
    atomic_write_text(scene_file, header + tomli_w.dumps(raw_scene))
    atomic_write_json(run_dir / "versions.json", versions())


class _RunLogHandler(logging.FileHandler):
    """A FileHandler that refuses a link or a special file in the log's place (OutputRefused),
    and that falls silent when the log cannot be written (a full disk): logging's default prints
    a traceback per record, over the message that says what failed."""

    failed: OSError | None = None

    def _open(self):
        from .no_follow import open_no_follow

        return open_no_follow(Path(self.baseFilename))

    def handleError(self, record: logging.LogRecord) -> None:
        import sys

        exc = sys.exc_info()[1]
        if isinstance(exc, OSError):
            self.failed = self.failed or exc
            return
        super().handleError(record)

    def flush(self) -> None:
        try:
            super().flush()
        except OSError as exc:
            self.failed = self.failed or exc

    def close(self) -> None:
        try:
            super().close()
        except OSError as exc:
            self.failed = self.failed or exc


def attach_run_log(run_dir: Path) -> logging.Handler:
    """Append the bearingsim log to `<run_dir>/run.log` (never through a link)."""
    run_dir.mkdir(parents=True, exist_ok=True)
    handler = _RunLogHandler(run_dir / "run.log", encoding="utf-8")
    handler.setFormatter(logging.Formatter("%(asctime)s %(levelname)s %(message)s"))
    logger = logging.getLogger("bearingsim")
    logger.setLevel(logging.INFO)
    logger.addHandler(handler)
    return handler
