"""Static checks of the package's own source (reads it with `ast`; runs nothing).

A `for` loop whose target rebinds a name the function assigned before, and which the function
reads again after the loop, is how a race contact's tangent calls came to read the film at the
wrong contact angle (the damping block's `for j in range(3)` overwrote the race table position
`j`; tests/test_bearing_model.py). numba kernels use short index names a lot,
so the check covers the whole package.

An array assigned to a slice inside a numba kernel (`K[:3, :3] = A`, `K[3:, 3:] += A`) makes numba
compile its shape-mismatch error path, string formatting included, into that kernel: seconds of a
machine's first run each (docs/performance.md, *Why the first run compiles for minutes*). Kernels
copy such blocks with loops (`multibody.small.add_into`, `copy_into`); filling a slice with a
constant stays allowed.
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


def hits_in_the_package(check) -> list[str]:
    """'file hit' for every hit of `check` (source -> list of hits) in the package's sources."""
    found = []
    for package in PACKAGES:
        for path in sorted((REPO / package).rglob("*.py")):
            found += [f"{path.relative_to(REPO)} {hit}" for hit in check(path.read_text())]
    return found


def test_no_loop_target_clobbers_a_live_name_in_the_package():
    assert hits_in_the_package(loop_targets_that_clobber) == []


def _is_kernel(fn) -> bool:
    for decorator in fn.decorator_list:
        f = decorator.func if isinstance(decorator, ast.Call) else decorator
        if (isinstance(f, ast.Attribute) and f.attr in ("njit", "jit")) or (isinstance(f, ast.Name) and f.id in ("njit", "jit")):
            return True
    return False


def arrays_assigned_to_slices(source: str) -> list[str]:
    """'function:line' of every assignment (plain or augmented) of a non-constant value to a sliced
    subscript inside a function decorated with numba's `njit` or `jit`."""
    found = []
    for fn in ast.walk(ast.parse(source)):
        if not (isinstance(fn, ast.FunctionDef) and _is_kernel(fn)):
            continue
        for node in ast.walk(fn):
            targets = node.targets if isinstance(node, ast.Assign) else [node.target] if isinstance(node, ast.AugAssign) else []
            value = getattr(node, "value", None)
            constant = isinstance(value, ast.Constant) or (isinstance(value, ast.UnaryOp) and isinstance(value.operand, ast.Constant))
            for target in targets:
                index = target.slice if isinstance(target, ast.Subscript) else None
                parts = index.elts if isinstance(index, ast.Tuple) else [index]
                if any(isinstance(part, ast.Slice) for part in parts) and not constant:
                    found.append(f"{fn.name}:{node.lineno}")
    return found


def test_the_check_finds_an_array_assigned_to_a_slice_in_a_kernel():
    source = """
@numba.njit(**KERNEL)
def tangent(K, A, g):
    K[:3, :3] += A
    g[3:] = A[0]
    K[3:, 3:] = 0.0
    g[0] = A[0, 0]


def python_side(K, A):
    K[:3, :3] = A
"""
    assert arrays_assigned_to_slices(source) == ["tangent:4", "tangent:5"]


def test_no_kernel_in_the_package_assigns_an_array_to_a_slice():
    assert hits_in_the_package(arrays_assigned_to_slices) == []
