"""The shape of the product code (docs/contributing.md, docs/architecture.md), read with `ast`:
no import cycles, function-level imports included; the layer contracts of pyproject.toml
(import-linter); at most 12 parameters a function; no hand-written LLVM IR; no dated lines.

Import cycles through function-level imports hide from a module-level import graph, and a
function of 21 parameters is a bundle that was never named; both were found in review, so this
test reads every import statement and every signature of the installed packages.
"""

from __future__ import annotations

import ast
import re
import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[1]
PACKAGES = {"pipeline": "bearingsim.pipeline", "dynamics": "bearingsim.dynamics", "fe_model": "bearingsim.fe_model",
            "meshes": "bearingsim.meshes"}
MAX_PARAMETERS = 12
# the imports that writing LLVM IR by hand needs: llvmlite itself, numba's IR-building helpers and
# its intrinsic/lowering extension points (numba's first-class functions and jit options need none)
IR_BUILDING = ("llvmlite", "numba.core.cgutils", "numba.core.imputils", "numba.extending.intrinsic",
               "numba.extending.lower_builtin", "numba.core.extending.intrinsic")


def module_name(path: Path) -> str:
    """The repository root is the package bearingsim: <root>/pipeline/api.py is bearingsim.pipeline.api."""
    parts = ["bearingsim", *path.relative_to(REPO).parts]
    parts[-1] = parts[-1].removesuffix(".py")
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def product_modules(root: Path = REPO) -> dict[str, Path]:
    files = [*sorted(root.glob("*.py")), *(p for top in PACKAGES for p in sorted((root / top).rglob("*.py")))]
    return {module_name(p): p for p in files}


def imports_of(name: str, path: Path, source: str, known: set[str]) -> set[str]:
    """Every bearingsim module `source` imports, at any depth (functions included)."""
    package = name.split(".") if path.name == "__init__.py" else name.split(".")[:-1]
    found = set()
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Import):
            found |= {alias.name for alias in node.names}
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package[:len(package) - (node.level - 1)]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module or ""
            found.add(target)
            found |= {f"{target}.{alias.name}" for alias in node.names}
    return {m for m in found if m in known and m != name}


def import_graph(modules: dict[str, Path]) -> dict[str, set[str]]:
    known = set(modules)
    return {name: imports_of(name, path, path.read_text(encoding="utf-8"), known) for name, path in modules.items()}


def cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """Strongly connected components of more than one module (Tarjan)."""
    index, low, stack, on_stack, found = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in sorted(graph[v]):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                found.append(sorted(component))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return found


def long_signatures(path: Path) -> list[tuple[str, int]]:
    """(function name, parameter count) of every function of more than MAX_PARAMETERS
    (self and cls not counted; *args and **kwargs neither)."""
    out = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            a = node.args
            names = [x.arg for x in a.posonlyargs + a.args + a.kwonlyargs]
            if names and names[0] in ("self", "cls"):
                names = names[1:]
            if len(names) > MAX_PARAMETERS:
                out.append((node.name, len(names)))
    return out


# a calendar date (2026-11-27) or a month and year (Nov 2026): measurement-diary lines, which live
# in git and docs/performance.md, not in code (docs/contributing.md); a citation's bare year is fine
DATED = re.compile(r"\b(19|20)\d\d-[01]\d-[0-3]\d\b|\b(Jan|Feb|Mar|Apr|May|Jun|Jul|Aug|Sep|Oct|Nov|Dec)[a-z]*\.? (19|20)\d\d\b")


def dated_lines(source: str) -> list[str]:
    return [line.strip() for line in source.splitlines() if DATED.search(line)]


def ir_building_imports(source: str) -> list[str]:
    """The imports in `source`, at any depth, that build LLVM IR by hand (IR_BUILDING)."""
    found = []
    for node in ast.walk(ast.parse(source)):
        names = []
        if isinstance(node, ast.Import):
            names = [alias.name for alias in node.names]
        elif isinstance(node, ast.ImportFrom) and node.module:
            names = [node.module] + [f"{node.module}.{alias.name}" for alias in node.names]
        found += [n for n in names if any(n == p or n.startswith(p + ".") for p in IR_BUILDING)]
    return found


def test_the_checks_find_a_cycle_and_a_long_signature(tmp_path):
    graph = {"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}
    assert cycles(graph) == [["a", "b", "c"]]
    source = "def f():\n    from .b import g\n"
    assert imports_of("bearingsim.pipeline.a", Path("a.py"), source, {"bearingsim.pipeline.b"}) == {"bearingsim.pipeline.b"}
    long = tmp_path / "m.py"
    long.write_text("def f(" + ", ".join(f"x{i}" for i in range(13)) + "):\n    pass\n"
                    "def g(self, " + ", ".join(f"x{i}" for i in range(12)) + "):\n    pass\n")
    assert long_signatures(long) == [("f", 13)]
    assert dated_lines("x = 1  # measured 2026-11-27\n# Lugt (2001), eq. 3\n# as of Nov 2026\n") == [
        "x = 1  # measured 2026-11-27", "# as of Nov 2026"]
    ir = "import llvmlite.ir as ir\ndef f():\n    from numba.extending import intrinsic, overload\n"
    assert ir_building_imports(ir) == ["llvmlite.ir", "numba.extending.intrinsic"]


def test_no_import_cycles():
    assert cycles(import_graph(product_modules())) == []


def test_the_graph_sees_the_relative_imports():
    """Every product import is relative, so an empty graph would pass the cycle test vacuously."""
    graph = import_graph(product_modules())
    assert "bearingsim.dynamics.bearing.model" in graph["bearingsim.dynamics.bearing.run"]
    assert "bearingsim.pipeline.staging.runner" in graph["bearingsim.pipeline.stages"]
    assert "bearingsim.fe_model" in graph["bearingsim.pipeline.stages.identify"]


def test_the_import_contracts_hold():
    """pyproject.toml's [tool.importlinter] contracts: the package directions of docs/architecture.md
    and the layers of pipeline/ (import-linter reads every import, function-level ones too)."""
    pytest.importorskip("importlinter", reason="import-linter is not installed (the test extra installs it)")
    lint_imports = "import sys; from importlinter.cli import lint_imports_command; sys.exit(lint_imports_command())"
    result = subprocess.run([sys.executable, "-c", lint_imports, "--no-cache"], cwd=REPO, capture_output=True, text=True)
    assert result.returncode == 0 and "0 broken" in result.stdout, result.stdout[-3000:] + result.stderr[-2000:]


def test_functions_take_at_most_twelve_parameters():
    found = {f"{path.relative_to(REPO)} {name}": n for path in product_modules().values()
             for name, n in long_signatures(path)}
    assert found == {}, "functions of more than 12 parameters: use named bundles"


def test_no_hand_written_llvm_ir():
    """Kernels are numba functions: IR written by hand ties the code to one LLVM's intrinsic
    names and to numba's internal calling convention (docs/contributing.md)."""
    found = {str(path.relative_to(REPO)): names for path in product_modules().values()
             if (names := ir_building_imports(path.read_text(encoding="utf-8")))}
    assert found == {}


def test_no_dated_lines():
    found = {str(path.relative_to(REPO)): lines for path in product_modules().values()
             if (lines := dated_lines(path.read_text(encoding="utf-8")))}
    assert found == {}
