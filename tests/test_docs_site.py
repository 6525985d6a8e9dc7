"""The documentation site (mkdocs.yml, docs/) builds with warnings as errors: a broken link, a
page missing from the nav, an API name the reference cannot find or a README section the site
includes that is gone all fail the build. Installed by the `test` extra, so CI builds it."""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def _build_strictly(project: Path, site: Path) -> subprocess.CompletedProcess:
    """`mkdocs build --strict` of the site whose mkdocs.yml is in `project`, into `site`."""
    return subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict", "--site-dir", str(site)],
                          cwd=project, capture_output=True, text=True, env=dict(os.environ, NO_MKDOCS_2_WARNING="1"))


def test_site_builds_strictly(tmp_path):
    pytest.importorskip("mkdocs", reason="the docs extra is not installed")
    pytest.importorskip("mkdocstrings", reason="the docs extra is not installed")
    result = _build_strictly(ROOT, tmp_path / "site")
    assert result.returncode == 0, result.stdout[-3000:] + result.stderr[-3000:]
    for page in ("index.html", "reference/index.html", "scenes/index.html", "performance/index.html"):
        assert (tmp_path / "site" / page).is_file(), page
    reference = (tmp_path / "site" / "reference" / "index.html").read_text(encoding="utf-8")
    assert "load_scene" in reference and "export_stiffness" in reference
    assert "bearingsim.pipeline" not in reference  # headings under the public names
    # the example notebook, shown with the outputs it was executed with
    notebook = (tmp_path / "site" / "examples" / "moment_sweep" / "index.html").read_text(encoding="utf-8")
    assert "too short to settle" in notebook and "data:image/png;base64," in notebook


def test_broken_links_fail_the_build(tmp_path):
    """mkdocs reports a link to a missing heading or file only at INFO level unless told
    otherwise: with mkdocs.yml's `validation` table, a one-page site with such a link fails the
    strict build, and the same page with the link fixed builds."""
    yaml = pytest.importorskip("yaml", reason="the docs extra is not installed")
    pytest.importorskip("mkdocs", reason="the docs extra is not installed")
    validation = yaml.safe_load((ROOT / "mkdocs.yml").read_text(encoding="utf-8"))["validation"]
    (tmp_path / "docs").mkdir()
    (tmp_path / "mkdocs.yml").write_text(
        yaml.safe_dump({"site_name": "probe", "strict": True, "validation": validation}), encoding="utf-8")

    def build(page: str) -> subprocess.CompletedProcess:
        (tmp_path / "docs" / "index.md").write_text(page, encoding="utf-8")
        return _build_strictly(tmp_path, tmp_path / "site")

    for broken in ("[there](#no-such-heading)", "[there](missing.json)"):
        result = build(f"# Probe\n\n## Here\n\n{broken}\n")
        assert result.returncode != 0, broken
    assert build("# Probe\n\n## Here\n\n[there](#here)\n").returncode == 0


def test_the_api_reference_documents_every_public_name():
    """docs/api.md promises that every function and class of `import bearingsim` is in the
    API reference: each public name is an entry of docs/reference.md, or a member of a module
    entry that lists no members (so that mkdocstrings renders them all)."""
    import importlib

    import bearingsim

    text = (ROOT / "docs" / "reference.md").read_text(encoding="utf-8")
    entries = re.findall(r"^::: (\S+)((?:\n    .*)*)", text, re.M)
    documented = set()
    for path, options in entries:
        members = re.findall(r"^\s+- (\w+)$", options, re.M)
        if members:
            documented |= {f"{path}.{m}" for m in members}
        else:
            documented.add(path)
    missing = []
    for name in bearingsim.__all__:
        if name == "__version__":
            continue
        obj = getattr(bearingsim, name)
        module = importlib.import_module(obj.__module__)
        where = f"{obj.__module__}.{obj.__qualname__}"
        if (f"bearingsim.{name}" not in documented and where not in documented
                and not (obj.__module__ in documented and getattr(module, name, None) is obj)):
            missing.append(f"{name} ({where})")
    assert not missing, f"public names missing from docs/reference.md: {', '.join(missing)}"


def test_docstrings_use_markdown_not_sphinx_roles():
    """mkdocstrings prints a Sphinx role such as :class:`Run` as it is written."""
    roles = re.compile(r":(?:class|func|meth|mod|attr|exc|obj):`")
    found = [f"{path.relative_to(ROOT)}:{n}" for package in ("pipeline", "dynamics", "fe_model")
             for path in sorted((ROOT / package).rglob("*.py"))
             for n, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1) if roles.search(line)]
    assert not found, f"Sphinx roles in docstrings: {', '.join(found)}"


def test_the_validation_folder_holds_only_figures_a_page_shows():
    """Study outputs (JSON, tables, tolerance sets, figures no page shows) are kept beside the
    script that makes them, in benchmarks/<study>/data/; docs/validation/ holds the figures that a
    documentation page embeds, and nothing else."""
    pages = "\n".join(path.read_text(encoding="utf-8") for path in (ROOT / "docs").rglob("*.md"))
    stray = sorted(f.name for f in (ROOT / "docs" / "validation").iterdir()
                   if f.suffix != ".png" or f"(validation/{f.name})" not in pages)
    assert not stray, f"docs/validation/ holds files no page shows: {', '.join(stray)}"
