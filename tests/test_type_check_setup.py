"""The editor and type-checker set-up of docs/architecture.md works: with the linked tree of
docs/_hooks/package_tree.py on MYPYPATH, mypy resolves `bearingsim.*` imports across the
packages (without it: "Can't find package"). Two modules that import across packages are
checked; they type-check clean, so any failure is the set-up's or a new type error there."""

from __future__ import annotations

import importlib.util
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def test_mypy_resolves_the_package_through_the_linked_tree():
    pytest.importorskip("mypy", reason="mypy is not installed (the test extra installs it)")
    spec = importlib.util.spec_from_file_location("package_tree", ROOT / "docs" / "_hooks" / "package_tree.py")
    tree = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(tree)
    tree.on_startup()
    result = subprocess.run(
        [sys.executable, "-m", "mypy", "--ignore-missing-imports", "--follow-imports=silent", "--no-incremental",
         "-m", "bearingsim.pipeline.scene", "-m", "bearingsim.dynamics.traction.laws"],
        cwd=ROOT, capture_output=True, text=True, env=dict(os.environ, MYPYPATH=str(tree.TREE)))
    assert "Can't find" not in result.stdout + result.stderr
    assert result.returncode == 0, result.stdout[-3000:] + result.stderr[-2000:]
