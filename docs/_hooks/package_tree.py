"""MkDocs hook (and a script): lay out the installed package's tree for static tools.

pyproject.toml installs the repository's top-level folders as `bearingsim.*`, so the source tree
has no `bearingsim/` folder and griffe (mkdocstrings) finds no `bearingsim.pipeline`. Before a
build this hook links the folders into `.api_source/bearingsim/` as an install would place them,
and mkdocs.yml points mkdocstrings there. Type checkers and editors that read the source
tree can use the same folder (docs/architecture.md): `python docs/_hooks/package_tree.py` lays it
out without building the site. Nothing is copied; the folder is rebuilt every time.
"""

from __future__ import annotations

import shutil
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
TREE = ROOT / ".api_source"
SUBPACKAGES = ("pipeline", "dynamics", "fe_model", "meshes")


def on_startup(**kwargs):
    """Before any plugin reads its configuration: mkdocstrings keeps only search paths that exist."""
    package = TREE / "bearingsim"
    if TREE.is_symlink() or (TREE.exists() and not (TREE / ".bearingsim-api-source").exists()):
        raise RuntimeError(f"{TREE} exists and was not made by this hook; remove it or move it away")
    shutil.rmtree(TREE, ignore_errors=True)
    package.mkdir(parents=True)
    (TREE / ".bearingsim-api-source").write_text("made by docs/_hooks/package_tree.py\n")
    (package / "__init__.py").symlink_to(ROOT / "pipeline" / "root_package" / "__init__.py")
    for name in SUBPACKAGES:
        (package / name).symlink_to(ROOT / name, target_is_directory=True)


if __name__ == "__main__":
    on_startup()
    print(f"{TREE / 'bearingsim'}: links to the package's folders")
