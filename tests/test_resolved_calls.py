"""numba's resolved calls remembered (dynamics/_speed/resolved_calls.py) give numba's own answers:
the expected signatures and implementations come from numba's original `get_call_type`, which the
module keeps, or from a process in which the module is not installed."""

import math
import operator

import numpy as np
import pytest
from numba.core import errors, types
from numba.core.registry import cpu_target

from bearingsim.dynamics._speed import resolved_calls

from .fresh_process import run_script


def test_importing_the_kernels_installs_it():
    import bearingsim.dynamics.multibody.compiled  # noqa: F401  (imports compile_policy)

    assert resolved_calls.installed()


vector = types.float64[::1]
matrix = types.float64[:, ::1]
CALLS = [
    (operator.getitem, (vector, types.int64)),
    (operator.getitem, (vector, types.intp)),
    (operator.getitem, (matrix, types.UniTuple(types.int64, 2))),
    (operator.getitem, (matrix, types.Tuple((types.slice2_type, types.int64)))),
    (operator.getitem, (types.UniTuple(types.float64, 3), types.literal(1))),
    (operator.setitem, (vector, types.int64, types.float64)),
    (operator.mul, (types.float64, types.int64)),
    (operator.mul, (types.int64, types.int64)),
    (operator.mul, (vector, types.float64)),
    (operator.truediv, (types.int64, types.int64)),
    (operator.lt, (types.float64, types.float64)),
    (min, (types.float64, types.float64)),
    (math.sqrt, (types.float64,)),
    (np.empty, (types.int64,)),
]


@pytest.mark.parametrize("function, args", CALLS, ids=[f"{f.__name__}{a}" for f, a in CALLS])
def test_a_resolution_and_its_repeats_are_numbas(function, args):
    context = cpu_target.typing_context
    context.refresh()
    fnty = context.resolve_value_type(function)
    expected = resolved_calls._ORIGINAL(fnty, context, args, {})
    expected_impl = fnty._impl_keys[expected.args]
    for _ in range(3):
        sig = fnty.get_call_type(context, args, {})
        assert sig == expected
        assert sig.pysig == expected.pysig
        assert fnty._impl_keys[sig.args] == expected_impl


def test_a_failed_resolution_raises_numbas_error_each_time_and_is_not_kept():
    context = cpu_target.typing_context
    context.refresh()
    fnty = context.resolve_value_type(operator.getitem)
    args = (types.float64, types.float64)
    with pytest.raises(errors.TypingError):
        resolved_calls._ORIGINAL(fnty, context, args, {})
    kept = len(resolved_calls._RESOLVED)
    for _ in range(2):
        with pytest.raises(errors.TypingError):
            fnty.get_call_type(context, args, {})
    assert len(resolved_calls._RESOLVED) == kept


# An @overload used by two kernels with different error models: numba compiles one implementation
# per caller's flags (a callee inherits the error model), and lowers each kernel with its own, also
# when the other kernel is compiled while the first is being typed.
_TWO_FLAGS = r"""
import sys
from bearingsim.dynamics._speed import resolved_calls
if sys.argv[1] == "numba":
    resolved_calls.install = lambda: False
import bearingsim.dynamics._speed.compile_policy  # noqa: F401  (installs it unless disabled)
import numba
from numba.extending import overload

def halve(x):
    raise NotImplementedError

@overload(halve)
def _halve(x):
    return lambda x: 1.0 / x

@numba.njit(error_model="numpy")
def lenient(x):
    return halve(x)

@numba.njit
def strict(x):
    first = halve(x)
    return first, lenient(x)

for name, call in (("strict", lambda: strict(0.0)), ("lenient", lambda: lenient(0.0))):
    try:
        print(name, call())
    except ZeroDivisionError as error:
        print(name, "ZeroDivisionError", error)
print("installed", resolved_calls.installed())
"""


def _two_flags(tmp_path, which: str) -> list[str]:
    done = run_script(tmp_path, _TWO_FLAGS, which, name="two_flags.py")
    assert done.returncode == 0, done.stderr[-3000:]
    return done.stdout.splitlines()


def test_each_callers_flags_keep_their_own_overload_implementation(tmp_path):
    numbas = _two_flags(tmp_path, "numba")
    remembered = _two_flags(tmp_path, "remembered")
    assert numbas[-1] == "installed False" and remembered[-1] == "installed True"
    assert remembered[:-1] == numbas[:-1]
    # the case is the one meant: the two kernels lower different implementations
    assert numbas[0].startswith("strict ZeroDivisionError") and numbas[1] == "lenient inf"


def test_another_numba_layout_is_left_alone(monkeypatch):
    def get_call_type(self, context, args, kws):  # no _impl_keys
        return None

    monkeypatch.setattr(resolved_calls, "_ORIGINAL", get_call_type)
    monkeypatch.setattr(types.functions.BaseFunction, "get_call_type", get_call_type)
    assert not resolved_calls.install()
    assert types.functions.BaseFunction.get_call_type is get_call_type


def test_numbas_method_is_kept():
    assert resolved_calls._get_call_type.numba_original is resolved_calls._ORIGINAL
    assert "_impl_keys" in resolved_calls._ORIGINAL.__code__.co_names
