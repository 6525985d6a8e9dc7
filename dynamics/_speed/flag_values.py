"""Faster equality and hash for numba's compile flags, with the same results.

numba resolves each call to one of its own `@overload` implementations (`np.empty`, `min`,
array methods, ...) through a cache keyed by the compile flags in force
(`numba.core.typing.templates._OverloadFunctionTemplate._get_impl`). Looking a key up hashes
the flags and compares them with the stored ones. `TargetConfig.__hash__` and `__eq__` both
build `values()`, a dict of every option (about twenty) read through a Python property each;
and as the hash covers only the option names, every stored entry for the same argument types
matches it and is compared value by value: about 240 000 comparisons in a machine's first run of
the reference bearing, about a twentieth of its compile (docs/performance.md, "Why the first run
compiles for minutes").

`install()` gives `TargetConfig` an `__eq__` that compares only the options set on either side
(an option set on neither holds the same default on both) and an `__hash__` that is the
original's value, computed once per class. Both fall back to numba's own methods for a class
whose options are not all served by the property numba generates for them, or for flags of two
different classes; if numba's flags are not laid out as expected (another numba), nothing is
replaced.
"""

from __future__ import annotations

from numba.core import targetconfig

_CONFIG = targetconfig.TargetConfig
# numba's own methods, also when this module is imported again after `install()`
_ORIGINAL_EQ = getattr(_CONFIG.__eq__, "numba_original", _CONFIG.__eq__)
_ORIGINAL_HASH = getattr(_CONFIG.__hash__, "numba_original", _CONFIG.__hash__)


def _generated_getter_code():
    """The code object shared by the properties numba's `_MetaTargetConfig` makes for the
    options (each returns `self._values.get(name, option.default)`), or None if numba's flags
    are not built that way."""
    from numba.core.compiler import Flags

    prop = getattr(Flags, "nrt", None)
    if not isinstance(prop, property) or prop.fget is None:
        return None
    code = prop.fget.__code__
    if code.co_freevars != ("name", "option") or "_values" not in getattr(_CONFIG, "__slots__", ()):
        return None
    return code


_GETTER_CODE = _generated_getter_code()
_PLAIN: dict[type, bool] = {}
_CLASS_HASH: dict[type, int] = {}


def _reads_options_plainly(cls: type) -> bool:
    """True when each option of `cls` is read by numba's generated property for that option."""
    plain = _PLAIN.get(cls)
    if plain is None:
        plain = True
        for name, option in cls.options.items():
            prop = getattr(cls, name, None)
            fget = prop.fget if isinstance(prop, property) else None
            if fget is None or fget.__code__ is not _GETTER_CODE:
                plain = False
                break
            cells = dict(zip(fget.__code__.co_freevars, (c.cell_contents for c in fget.__closure__)))
            if cells["name"] != name or cells["option"] is not option:
                plain = False
                break
        _PLAIN[cls] = plain
    return plain


def _eq(self, other):
    """`values() == other.values()`, comparing only the options set on either side."""
    cls = type(self)
    if type(other) is not cls or not _reads_options_plainly(cls):
        return _ORIGINAL_EQ(self, other)
    mine, theirs, options = self._values, other._values, cls.options
    for name in mine.keys() | theirs.keys():
        option = options.get(name)
        if option is None:  # not an option: values() does not read it
            continue
        a = mine.get(name, option.default)
        b = theirs.get(name, option.default)
        if a is not b and not a == b:
            return False
    return True


def _hash(self) -> int:
    """numba's hash of the flags, `hash(tuple(sorted(values())))`: sorting the dict sorts its
    keys, the option names, so the value depends only on the class."""
    cls = type(self)
    if not _reads_options_plainly(cls):
        return _ORIGINAL_HASH(self)
    value = _CLASS_HASH.get(cls)
    if value is None:
        value = _CLASS_HASH[cls] = _ORIGINAL_HASH(self)
    return value


_eq.numba_original = _ORIGINAL_EQ
_hash.numba_original = _ORIGINAL_HASH


def install() -> bool:
    """Give numba's `TargetConfig` the faster `__eq__` and `__hash__`; True if they are in place.

    Subclasses created before this call copied nothing: they inherit both methods."""
    if _GETTER_CODE is None:
        return False
    _CONFIG.__eq__ = _eq
    _CONFIG.__hash__ = _hash
    return True
