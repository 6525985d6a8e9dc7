"""Static checks of the package's own source (reads it with `ast`; runs nothing).

A `for` loop whose target rebinds a name the function assigned before, and which the function
reads again after the loop, is how a race contact's tangent calls came to read the film at the
wrong contact angle (the damping block's `for j in range(3)` overwrote the race table position
`j`; tests/test_bearing_model.py). numba kernels use short index names a lot,
so the check covers the whole package.
"""

import ast
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
PACKAGES = ("dynamics", "fe_model", "pipeline", "meshes")


def loop_targets_that_clobber(source: str) -> list[str]:
    """'function:line name' of every loop target that rebinds a name assigned earlier in its
    function and read after the loop before any new assignment."""
    found = []
    for fn in ast.walk(ast.parse(source)):
        if not isinstance(fn, (ast.FunctionDef, ast.AsyncFunctionDef)):
            continue
        stores, loads, loops = {}, {}, []
        for node in ast.walk(fn):
            if isinstance(node, (ast.For, ast.AsyncFor)):
                loops += [(t.id, node.lineno, node.end_lineno) for t in ast.walk(node.target) if isinstance(t, ast.Name)]
            elif isinstance(node, ast.Name):
                (stores if isinstance(node.ctx, ast.Store) else loads).setdefault(node.id, []).append(node.lineno)
        for name, start, end in loops:
            reads_after = [line for line in loads.get(name, []) if line > end]
            if not reads_after or not any(line < start for line in stores.get(name, [])):
                continue
            first_read = min(reads_after)
            if not any(end < line <= first_read for line in stores.get(name, [])):
                found.append(f"{fn.name}:{start} {name}")
    return found


def test_the_check_finds_the_film_bug_it_was_written_for():
    buggy = """
def race_contact(table, alpha, n, res):
    j, t = position(table, alpha)
    for i in range(3):
        for j in range(3):
            res[3 * i + j] = n[i] * n[j]
    return film(table, j, t)
"""
    assert loop_targets_that_clobber(buggy) == ["race_contact:5 j"]
    fixed = buggy.replace("for j in range(3)", "for c in range(3)").replace("3 * i + j] = n[i] * n[j]", "3 * i + c] = n[i] * n[c]")
    assert loop_targets_that_clobber(fixed) == []


def test_no_loop_target_clobbers_a_live_name_in_the_package():
    found = []
    for package in PACKAGES:
        for path in sorted((REPO / package).rglob("*.py")):
            found += [f"{path.relative_to(REPO)} {hit}" for hit in loop_targets_that_clobber(path.read_text())]
    assert found == []
