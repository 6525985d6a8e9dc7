"""numba's resolution of calls to its own functions and operators, remembered per argument types.

To type `a[i]`, `x * y`, `min(a, b)` or `np.empty(n)`, numba asks the function's type for the
signature that matches the argument types (`numba.core.types.functions.BaseFunction.get_call_type`).
That tries the function's registered templates one by one, in an order it sorts again at each
call, formatting a message for each template that does not match; an array index first tries the
templates of strings, lists, tuples and typed dicts. Lowering asks again for every index,
assignment and operator (numba's `lower_getitem`, `lower_setitem`, `lower_binop`). In a machine's
first run of the reference bearing about 21 000 such resolutions take about a tenth of the
compile, and all but about 1 300 of them repeat an earlier one (docs/performance.md, "Why the
first run compiles for minutes").

`install()` keeps each successful resolution under the function type (whose key includes its
templates, so a newly registered overload makes a new type), the typing context, the target, the
argument types and the compile flags in force; the flags are also part of the key under which
numba keeps the implementations of its `@overload` functions. A repeated resolution returns the
signature found before and records the implementation it selected again, the one effect of a
resolution that lowering reads (`_impl_keys`, looked up by `BaseContext.get_function`). A failed
resolution is not kept: it raises numba's error again. If numba's functions are laid out
otherwise (another numba), nothing is replaced.
"""

from __future__ import annotations

from numba.core import targetconfig
from numba.core.target_extension import get_local_target
from numba.core.types import functions

_FUNCTION = functions.BaseFunction
# numba's own method, also when this module is imported again after `install()`
_ORIGINAL = getattr(_FUNCTION.get_call_type, "numba_original", _FUNCTION.get_call_type)

# (function type, typing context, target, argument types, keyword types, flags)
#   -> (signature, implementation key)
_RESOLVED: dict[tuple, tuple] = {}


def _get_call_type(self, context, args, kws):
    """numba's `get_call_type`, answered from `_RESOLVED` when it resolved the same call before."""
    try:
        key = (self, context, get_local_target(context), tuple(args), tuple(kws.items()),
               targetconfig.ConfigStack.top_or_none())
        found = _RESOLVED.get(key)
    except TypeError:  # an argument type that cannot be hashed
        return _ORIGINAL(self, context, args, kws)
    if found is not None:
        sig, impl_key = found
        self._impl_keys[sig.args] = impl_key
        return sig
    sig = _ORIGINAL(self, context, args, kws)
    if sig is not None:
        _RESOLVED[key] = sig, self._impl_keys[sig.args]
    return sig


_get_call_type.numba_original = _ORIGINAL


def _laid_out_as_expected() -> bool:
    """numba's `get_call_type` records the implementation it selects in `_impl_keys`, which its
    `get_impl_key` reads."""
    names = _ORIGINAL.__code__.co_names
    get_impl_key = getattr(functions.Function, "get_impl_key", None)
    return ("_impl_keys" in names and "get_impl_key" in names and get_impl_key is not None
            and "_impl_keys" in get_impl_key.__code__.co_names)


def install() -> bool:
    """Remember numba's resolved calls; True if in place."""
    if not _laid_out_as_expected():
        return False
    _FUNCTION.get_call_type = _get_call_type
    return True


def installed() -> bool:
    return _FUNCTION.get_call_type is _get_call_type
