"""Static tools read the clone as an install would (docs/architecture.md): the repository root
is the package and every product import is relative, so mypy resolves each of them from the
source tree alone: no install, no MYPYPATH, no linked tree."""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PRODUCT = ("pipeline", "dynamics", "fe_model", "meshes", "__init__.py", "__main__.py")
# mypy's words for an import of ours it could not resolve (the copy's folder is named a_clone)
OURS = re.compile(r'module named "(\.|a_clone\b|bearingsim\b)|Module "(a_clone|bearingsim)[\w.]*" has no attribute'
                  r'|relative import|No parent module')


def copy_of_the_sources(tmp_path: Path) -> Path:
    """The product sources under another folder name and away from the installed package:
    what resolves there resolves from the files, whatever the clone is called."""
    clone = tmp_path / "a_clone"
    clone.mkdir()
    for name in PRODUCT:
        source = ROOT / name
        if source.is_dir():
            shutil.copytree(source, clone / name, ignore=shutil.ignore_patterns("__pycache__"))
        else:
            shutil.copy2(source, clone / name)
    return clone


def unresolved_imports(clone: Path) -> list[str]:
    # no site-packages: third-party imports are reported missing too, and filtered out by OURS
    env = {k: v for k, v in os.environ.items() if k != "MYPYPATH"}
    result = subprocess.run(
        [sys.executable, "-m", "mypy", "--follow-imports=silent", "--no-incremental", "--no-site-packages",
         "--cache-dir", os.devnull, "pipeline", "dynamics", "fe_model", "meshes"],
        cwd=clone, capture_output=True, text=True, env=env)
    assert "error:" in result.stdout or result.returncode == 0, result.stdout[-2000:] + result.stderr[-2000:]
    return [line for line in result.stdout.splitlines() if OURS.search(line)]


def test_mypy_resolves_every_product_import_from_the_source_tree(tmp_path):
    pytest.importorskip("mypy", reason="mypy is not installed (the test extra installs it)")
    found = unresolved_imports(copy_of_the_sources(tmp_path))
    assert found == [], "\n".join(found[:20])


def test_an_import_that_resolves_nowhere_is_reported(tmp_path):
    """The check above can fail: a relative import of a module that is not there is reported."""
    pytest.importorskip("mypy", reason="mypy is not installed (the test extra installs it)")
    clone = copy_of_the_sources(tmp_path)
    with open(clone / "dynamics" / "thermal.py", "a", encoding="utf-8") as fh:
        fh.write("\nfrom ..pipeline import no_such_module  # noqa: E402\nfrom ..no_such_package import x  # noqa: E402\n")
    found = unresolved_imports(clone)
    assert sum("thermal.py" in line for line in found) == 2, found
