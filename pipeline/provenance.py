"""What a run directory keeps besides results: resolved scene, versions, log."""

from __future__ import annotations

import logging
import platform
import subprocess
import sys
from importlib import metadata
from pathlib import Path

import tomli_w

from .artefacts import atomic_write_json, atomic_write_text

PACKAGES = ("bearingsim", "numpy", "scipy", "numba", "scikit-fem", "gmsh", "meshio",
            "pyvista", "vtk", "matplotlib", "h5py", "typer", "rich", "pypardiso")


def package_version() -> str:
    try:
        return metadata.version("bearingsim")
    except metadata.PackageNotFoundError:
        return "0+unknown"


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
    return out


def write_run_provenance(run_dir: Path, raw_scene: dict, origin: str) -> None:
    """Save the resolved scene (after overrides) and the package versions."""
    run_dir.mkdir(parents=True, exist_ok=True)
    header = f"# Resolved scene (from {origin}, after --set overrides), as used by this run.\n"
    atomic_write_text(run_dir / "scene.toml", header + tomli_w.dumps(raw_scene))
    atomic_write_json(run_dir / "versions.json", versions())


def attach_run_log(run_dir: Path) -> logging.Handler:
    """Append the bearingsim log to `<run_dir>/run.log`."""
    run_dir.mkdir(parents=True, exist_ok=True)
    handler = logging.FileHandler(run_dir / "run.log", encoding="utf-8")
    handler.setFormatter(logging.Formatter("%(asctime)s %(levelname)s %(message)s"))
    logger = logging.getLogger("bearingsim")
    logger.setLevel(logging.INFO)
    logger.addHandler(handler)
    return handler
