"""MkDocs hook (and a script): a folder named `bearingsim` for griffe (mkdocstrings).

The repository root is the package `bearingsim`, but griffe looks a package up by the name of
its folder, and a clone's folder may be called anything. Before a build this hook links the
root's `__init__.py` and its package folders into `.api_source/bearingsim/`, and mkdocs.yml
points mkdocstrings there. Type checkers and editors need no such folder: the product imports
itself relatively (docs/architecture.md). Nothing is copied, only linked.
"""

from __future__ import annotations

from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
TREE = ROOT / ".api_source"
SUBPACKAGES = ("pipeline", "dynamics", "fe_model", "meshes")


def on_startup(**kwargs):
    """Before any plugin reads its configuration: mkdocstrings keeps only search paths that exist.
    Idempotent, and safe when two processes lay the tree out at once (tests run in parallel)."""
    package = TREE / "bearingsim"
    marker = TREE / ".bearingsim-api-source"
    if TREE.is_symlink() or (TREE.exists() and not marker.exists()):
        raise RuntimeError(f"{TREE} exists and was not made by this hook; remove it or move it away")
    package.mkdir(parents=True, exist_ok=True)
    marker.write_text("made by docs/_hooks/package_tree.py\n")
    links = {"__init__.py": ROOT / "__init__.py",
             **{name: ROOT / name for name in SUBPACKAGES}}
    for name, target in links.items():
        link = package / name
        if link.is_symlink() and link.resolve() != target.resolve():
            link.unlink()  # a tree laid out from another checkout
        if not link.is_symlink():
            try:
                link.symlink_to(target, target_is_directory=target.is_dir())
            except FileExistsError:  # another process made it just now
                pass

if __name__ == "__main__":
    on_startup()
    print(f"{TREE / 'bearingsim'}: links to the package's folders")
