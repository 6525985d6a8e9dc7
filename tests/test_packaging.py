"""One import namespace: the repository root is the package bearingsim, pyproject.toml installs
exactly the packages under it, one per product folder holding an __init__.py, and the API's
face lists its names once for the run time and once for static tools."""

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
        for top in TOP for p in (ROOT / top).rglob("__init__.py") if "__pycache__" not in p.parts}
    assert listed == found, f"pyproject.toml packages differ from the folders: {sorted(listed ^ found)}"


def test_nothing_but_bearingsim_at_top_level():
    cfg = _config()
    assert all(p == "bearingsim" or p.startswith("bearingsim.") for p in cfg["packages"])
    assert cfg["package-dir"] == {"bearingsim": "."}


def test_the_face_names_the_same_api_for_static_tools_and_at_run_time():
    import ast

    import bearingsim

    tree = ast.parse((ROOT / "__init__.py").read_text(encoding="utf-8"))
    checked = next(node for node in tree.body if isinstance(node, ast.If) and ast.unparse(node.test) == "TYPE_CHECKING")
    static = {alias.name: "bearingsim" + "." * (imp.level > 0) + (imp.module or "")
              for imp in checked.body for alias in imp.names}
    assert static == bearingsim._API


def test_the_console_script_is_in_the_namespace():
    scripts = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]["scripts"]
    # main, not the typer app: main turns SIGTERM into a logged interruption first
    assert scripts == {"bearingsim": "bearingsim.pipeline.cli.commands:main"}


def test_no_module_imports_a_top_level_folder_by_its_bare_name():
    import re

    bare = re.compile(r"^\s*(from|import)\s+(pipeline|dynamics|fe_model|meshes)\b", re.M)
    offenders = [str(p.relative_to(ROOT)) for folder in (*TOP, "tests", "benchmarks")
                 for p in (ROOT / folder).rglob("*.py") if bare.search(p.read_text(encoding="utf-8"))]
    assert not offenders, f"import bearingsim.<folder> instead: {offenders}"


def test_the_product_imports_itself_relatively():
    """An absolute bearingsim.* import resolves only where bearingsim is installed; a relative one
    resolves from the files too, which is what static tools read (docs/architecture.md)."""
    import ast

    def absolute_imports(path: Path) -> list[str]:
        found = []
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Import):
                found += [a.name for a in node.names if a.name.split(".")[0] == "bearingsim"]
            elif isinstance(node, ast.ImportFrom) and not node.level and (node.module or "").split(".")[0] == "bearingsim":
                found.append(node.module)
        return found

    files = [*(p for folder in TOP for p in (ROOT / folder).rglob("*.py")), ROOT / "__init__.py", ROOT / "__main__.py"]
    offenders = {str(p.relative_to(ROOT)): names for p in files if (names := absolute_imports(p))}
    assert not offenders, f"import relatively (from ..dynamics import ...): {offenders}"


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
