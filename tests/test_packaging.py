"""One import namespace: pyproject.toml installs exactly the packages under bearingsim.*, one
per folder holding an __init__.py, and the top-level folders map to bearingsim.<folder>."""

from __future__ import annotations

import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
TOP = ("pipeline", "dynamics", "fe_model", "meshes")


def _config():
    return tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["tool"]["setuptools"]


def test_every_package_folder_is_installed_under_bearingsim():
    listed = set(_config()["packages"])
    found = {"bearingsim"} | {
        "bearingsim." + ".".join(p.parent.relative_to(ROOT).parts)
        for top in TOP for p in (ROOT / top).rglob("__init__.py")
        if "root_package" not in p.parts and "__pycache__" not in p.parts}
    assert listed == found, f"pyproject.toml packages differ from the folders: {sorted(listed ^ found)}"


def test_nothing_but_bearingsim_at_top_level():
    cfg = _config()
    assert all(p == "bearingsim" or p.startswith("bearingsim.") for p in cfg["packages"])
    assert cfg["package-dir"] == {"bearingsim": "pipeline/root_package",
                                  **{f"bearingsim.{t}": t for t in TOP}}


def test_the_console_script_is_in_the_namespace():
    scripts = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]["scripts"]
    # main, not the typer app: main turns SIGTERM into a logged interruption first
    assert scripts == {"bearingsim": "bearingsim.pipeline.cli:main"}


def test_no_module_imports_a_top_level_folder_by_its_bare_name():
    import re

    bare = re.compile(r"^\s*(from|import)\s+(pipeline|dynamics|fe_model|meshes)\b", re.M)
    offenders = [str(p.relative_to(ROOT)) for folder in (*TOP, "tests", "benchmarks")
                 for p in (ROOT / folder).rglob("*.py") if bare.search(p.read_text(encoding="utf-8"))]
    assert not offenders, f"import bearingsim.<folder> instead: {offenders}"


def test_dynamics_and_fe_model_never_import_each_other_or_pipeline():
    import re

    for folder, banned in (("dynamics", ("fe_model", "pipeline", "meshes")), ("fe_model", ("dynamics", "pipeline"))):
        pat = re.compile(r"^\s*(from|import)\s+bearingsim\.(" + "|".join(banned) + r")\b", re.M)
        offenders = [str(p.relative_to(ROOT)) for p in (ROOT / folder).rglob("*.py") if pat.search(p.read_text(encoding="utf-8"))]
        assert not offenders, f"{folder} must not import {banned}: {offenders}"


def test_python_dash_m_runs_the_command_line():
    """`python -m bearingsim` is the console script, for a venv whose bin/ is not on PATH."""
    import subprocess
    import sys

    listed = subprocess.run([sys.executable, "-m", "bearingsim", "scenes"], capture_output=True, text=True)
    assert listed.returncode == 0, listed.stderr
    assert "helicopter-b" in listed.stdout
    refused = subprocess.run([sys.executable, "-m", "bearingsim", "check", "no-such-scene"],
                             capture_output=True, text=True)
    assert refused.returncode == 2 and "no-such-scene" in refused.stderr
    usage = subprocess.run([sys.executable, "-m", "bearingsim", "--help"], capture_output=True, text=True)
    assert "Usage: bearingsim " in usage.stdout
