"""Machine code on demand (dynamics/_speed/deferred_emission.py): a function that only other
kernels call gets none of its own, and everything that needs an address still gets one: a call
from Python, a first-class function value, the environment a callee's code reads, a later process
loading the cache. Each case runs in a fresh process with an empty numba cache, with its kernels
defined in a module of the test's own that is added to the deferred ones."""

import json

import pytest

from .fresh_process import run_script

_KERNELS = r"""
import json
import numba
import numpy as np
from bearingsim.dynamics._speed import compile_policy, deferred_emission  # compile_policy installs it
deferred_emission.DEFERRED_MODULES.add(__name__)
assert deferred_emission.installed()

@numba.njit(cache=True)
def callee(x):
    print("callee sum", x.sum())  # boxing the sum for print reads the function's environment
    return 2.0 * x.sum()

@numba.njit(cache=True)
def caller(x):
    return callee(x) + 1.0

@numba.njit(cache=True)
def square(v):
    return v * v

@numba.njit(cache=True)
def apply(fn, v):
    return fn(v)

def pending(dispatcher, *types):
    return bool(getattr(dispatcher.overloads[types].library, "_emission_pending", False))

x = np.arange(4.0)
vector = numba.typeof(x)
out = {}
"""


_CACHE_KINDS = """
from numba.core.caching import FunctionCache
for name, dispatcher in (("caller", caller), ("callee", callee)):
    cache_file = FunctionCache(dispatcher.py_func)._cache_file
    index = cache_file._load_index()
    if index:
        libdata = cache_file._load_data(next(iter(index.values())))[0]
        out["kind_" + name] = libdata[1]  # numba's form of the entry: "object" or "bitcode"
"""


def _run(tmp_path, body: str) -> dict:
    """Run `body` after importing the kernels above from a module of their own, which stays the
    same file from run to run (numba caches only functions from files, and keys the cache by the
    file's time stamp)."""
    kernels = tmp_path / "kernels.py"
    if not kernels.exists():
        kernels.write_text(_KERNELS)
    done = run_script(tmp_path, "from kernels import *\n" + body + "\nprint(json.dumps(out))\n")
    assert done.returncode == 0, done.stderr[-3000:]
    lines = done.stdout.splitlines()
    return {"printed": lines[:-1], **json.loads(lines[-1])}


def test_a_callee_only_other_kernels_call_has_no_machine_code_of_its_own(tmp_path):
    out = _run(tmp_path, """
out["caller"] = caller(x)
out["callee_pending"] = pending(callee, vector)
out["caller_pending"] = pending(caller, vector)
out["callee_entry"] = type(callee.overloads[(vector,)].entry_point).__name__
""")
    assert out["caller"] == 13.0  # 2 * (0 + 1 + 2 + 3) + 1
    assert out["printed"] == ["callee sum 6.0"]
    assert out["callee_pending"] is True
    assert out["caller_pending"] is False
    assert out["callee_entry"] == "Deferred"


def test_a_callee_called_from_python_later_gets_its_machine_code_then(tmp_path):
    out = _run(tmp_path, """
caller(x)
out["before"] = pending(callee, vector)
out["first"] = callee(x)
out["after"] = pending(callee, vector)
out["again"] = callee(x + 1.0)
""")
    assert out["before"] is True and out["after"] is False
    assert out["first"] == 12.0 and out["again"] == 20.0
    assert out["printed"] == ["callee sum 6.0", "callee sum 6.0", "callee sum 10.0"]


def test_a_first_class_function_value_gets_an_address(tmp_path):
    out = _run(tmp_path, """
out["squared"] = apply(square, 3.0)
""")
    assert out["squared"] == 9.0


def test_the_environment_a_callee_reads_is_set_in_its_callers_code(tmp_path):
    """Without the environments set after emission, the callee's print inside the caller fails
    ("missing Environment"): this is what the first test's print checks."""
    done = run_script(tmp_path, _KERNELS.replace("assert deferred_emission.installed()",
                                                 "deferred_emission._set_environments = lambda library: None")
                      + "\ncaller(x)\n")
    assert done.returncode != 0
    assert "missing Environment" in done.stderr


def test_the_cache_keeps_object_code_for_what_was_emitted_and_bitcode_for_the_rest(tmp_path):
    first = _run(tmp_path, "out['caller'] = caller(x)\n" + _CACHE_KINDS)
    # the caller ran: its entry was written again as object code; the callee's machine code
    # exists only inside the caller's, so its own entry stays an optimised module
    assert first["caller"] == 13.0
    assert (first["kind_caller"], first["kind_callee"]) == ("object", "bitcode")
    # a later process that calls the callee first loads it from its optimised module, with no
    # library yet that defines its environment
    second = _run(tmp_path, """
out["callee_pending_loaded"] = pending(callee, vector) if callee.compile((vector,)) else None
out["callee"] = callee(x)
out["caller"] = caller(x)
""" + _CACHE_KINDS)
    assert second["callee_pending_loaded"] is True
    assert second["callee"] == 12.0 and second["caller"] == 13.0
    assert second["printed"] == ["callee sum 6.0", "callee sum 6.0"]
    assert (second["kind_caller"], second["kind_callee"]) == ("object", "object")
    third = _run(tmp_path, "out['callee'] = callee(x)\nout['pending'] = pending(callee, vector)\n")
    assert third["callee"] == 12.0 and third["pending"] is False


def test_importing_the_kernels_installs_it():
    import bearingsim.dynamics.multibody.compiled  # noqa: F401  (imports compile_policy)
    from bearingsim.dynamics._speed import deferred_emission

    assert deferred_emission.installed()


def test_another_numba_layout_is_left_alone(monkeypatch):
    from bearingsim.dynamics._speed import deferred_emission

    def finalize_otherwise(self):
        return None

    monkeypatch.setattr(deferred_emission, "_FINALIZE", finalize_otherwise)
    assert not deferred_emission._laid_out_as_expected()


@pytest.mark.parametrize("name", ["_finalize_final_module", "get_pointer_to_function", "get_executable",
                                  "add_overload", "serialize_using_object_code", "_unserialize", "set_env"])
def test_numbas_methods_are_kept(name):
    from bearingsim.dynamics._speed import deferred_emission

    originals = {key[1]: function for key, function in deferred_emission._ORIGINAL.items()}
    assert originals[name].__module__.startswith("numba.")
