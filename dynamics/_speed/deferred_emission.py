"""Machine code for a numba library only when something needs its address.

numba compiles each jitted function into a library, links the optimised modules of its callees
into it, and emits machine code for the whole linked module as soon as the function is compiled.
A callee that only other kernels call is thus turned into machine code in its own library, where
nothing ever calls it, and again inside each caller's library, where it runs. In a machine's first
run of the reference bearing that first emission is about half of LLVM's machine-code time
(docs/performance.md, "Why the first run compiles for minutes").

`install()` makes numba's CPU target defer that step for the functions of this package and numba's
own implementations (`DEFERRED_MODULES`): their libraries are linked and optimised as before, so
every caller links the same module and runs the same code, but emitted only when an address is
asked for, by a call from Python (the dispatcher then gets the compiled entry), a first-class
function value, or `get_pointer_to_function`. Until then their entry in the dispatcher is a
`Deferred` stand-in, and the disk cache keeps them as optimised bitcode (numba's own "bitcode"
form of a cache entry); once emitted, the entry is written again as object code, so that later
runs load what the first one called as numba would have cached it. A caller's library holds copies of its callees'
environment pointers, which numba otherwise fills from the callee's own library: they are set
after every emission, as numba does for a caller loaded from its cache.

If numba's code generation is not laid out as this module expects (another numba), nothing is
replaced and numba emits as it always does.
"""

from __future__ import annotations

import threading
import weakref

from numba.core import codegen, cpu, dispatcher, environment
from numba.core.compiler_lock import global_compiler_lock

# top-level packages whose functions are emitted on demand: this package and numba's own
# implementations (`np.empty`, array indexing, ...), which only kernels call
DEFERRED_MODULES = {__name__.split(".")[0], "numba"}

_LIBRARY = codegen.CPUCodeLibrary
_JIT_LIBRARY = codegen.JITCodeLibrary
_JIT_CODEGEN = codegen.JITCPUCodegen


def _original(owner, name):
    """numba's function behind a method, also when this module is imported again after
    `install()`."""
    method = owner.__dict__[name]
    function = method.__func__ if isinstance(method, classmethod) else method
    return getattr(function, "numba_original", function)


# numba's methods that `install()` replaces, by (class, name)
_ORIGINAL = {(owner, name): _original(owner, name) for owner, name in (
    (_LIBRARY, "_finalize_final_module"),
    (_LIBRARY, "serialize_using_object_code"),
    (_LIBRARY, "_unserialize"),
    (_JIT_LIBRARY, "get_pointer_to_function"),
    (cpu.CPUContext, "get_executable"),
    (dispatcher._DispatcherBase, "add_overload"),
    (_JIT_CODEGEN, "set_env"),
)}
_FINALIZE = _ORIGINAL[_LIBRARY, "_finalize_final_module"]
_GET_POINTER = _ORIGINAL[_JIT_LIBRARY, "get_pointer_to_function"]
_GET_EXECUTABLE = _ORIGINAL[cpu.CPUContext, "get_executable"]
_ADD_OVERLOAD = _ORIGINAL[dispatcher._DispatcherBase, "add_overload"]
_SERIALIZE = _ORIGINAL[_LIBRARY, "serialize_using_object_code"]
_UNSERIALIZE = _ORIGINAL[_LIBRARY, "_unserialize"]
_SET_ENV = _ORIGINAL[_JIT_CODEGEN, "set_env"]

# names of the environment globals defined in libraries kept without machine code
_ENVIRONMENTS_OF_PENDING: set[str] = set()
# set while numba loads a cache entry kept as bitcode in this thread
_LOADING = threading.local()

# the attribute numba's object-code hooks read on a final module (`ll_module.__library` inside
# CPUCodeLibrary)
_HOOK_ATTRIBUTE = "_CPUCodeLibrary__library"


def _names(function) -> set[str]:
    code = getattr(function, "__code__", None)
    return set(code.co_names) if code is not None else set()


def _laid_out_as_expected() -> bool:
    """True when numba's methods do what the replacements below split or stand in for."""
    return (_names(_FINALIZE) >= {"_finalize_dynamic_globals", "_verify_declare_only_symbols", "_add_module",
                                  "_finalize_specific", "_finalized", _HOOK_ATTRIBUTE}
            and _names(_GET_EXECUTABLE) >= {"get_pointer_to_function", "make_function", "set_env"}
            and _names(_ADD_OVERLOAD) >= {"_insert", "overloads", "entry_point"}
            and "bitcode" in _UNSERIALIZE.__code__.co_consts
            and _names(_UNSERIALIZE) >= {"_finalize_final_module"}
            and _names(_SET_ENV) >= {"get_global_value_address"}
            and hasattr(_LIBRARY, "serialize_using_bitcode")
            and hasattr(environment, "lookup_environment"))


def _pending(library) -> bool:
    return getattr(library, "_emission_pending", False)


def _environment_names(library) -> list[str]:
    return [variable.name for variable in library._final_module.global_variables
            if variable.name.startswith("_ZN08NumbaEnv") and not variable.is_declaration]


def _set_environments(library) -> None:
    """Point every environment global defined in the library's module at its environment."""
    for name in _environment_names(library):
        env = environment.lookup_environment(name)
        if env is not None:
            library.codegen.set_env(name, env)


def _set_env(self, env_name, env):
    """numba's setting of an environment pointer, which it also does for a function loaded from
    the cache; one that only a library without machine code defines is set when it is emitted
    (`_set_environments`): the execution engine has no address for it before."""
    if env_name in _ENVIRONMENTS_OF_PENDING and not self._engine.is_symbol_defined(env_name):
        return
    _SET_ENV(self, env_name, env)


def _finalize_final_module(self) -> None:
    """numba's last finalisation step; a library marked `_emission_wanted_later` stops before
    handing its module to the execution engine."""
    wanted_later = getattr(self, "_emission_wanted_later", False) or getattr(_LOADING, "bitcode", False)
    if wanted_later and not _pending(self):
        self._finalize_dynamic_globals()
        self._verify_declare_only_symbols()
        _ENVIRONMENTS_OF_PENDING.update(_environment_names(self))
        self._emission_pending = True
        self._finalized = True
        return
    _FINALIZE(self)
    _set_environments(self)


def _emit(library) -> None:
    """The part of numba's finalisation that `_finalize_final_module` left for later; then the
    function's cache entry is written again, as object code, so that later runs load it."""
    with global_compiler_lock:
        if not _pending(library):
            return
        setattr(library._final_module, _HOOK_ATTRIBUTE, weakref.proxy(library))
        cleanup = library._codegen._add_module(library._final_module)
        if cleanup:
            weakref.finalize(library, cleanup)
        library._finalize_specific()
        library._emission_pending = False
        _set_environments(library)
        entry = getattr(library, "_deferred_entry", None)
        if entry is not None:
            entry.cache_as_object_code()


def _get_pointer_to_function(self, name):
    if _pending(self):
        _emit(self)
    return _GET_POINTER(self, name)


def _serialize_using_object_code(self):
    """A library without machine code is cached as its optimised module."""
    if _pending(self):
        return self.serialize_using_bitcode()
    return _SERIALIZE(self)


def _unserialize(cls, codegen_, state):
    """numba's loading of a cache entry; one kept as bitcode stays without machine code."""
    if state[1] != "bitcode" or not issubclass(cls, _JIT_LIBRARY):
        return _UNSERIALIZE(cls, codegen_, state)
    _LOADING.bitcode = True
    try:
        library = _UNSERIALIZE(cls, codegen_, state)
    finally:
        _LOADING.bitcode = False
    library.enable_object_caching()  # so that its object code can be cached once emitted
    return library


class Deferred:
    """The dispatcher entry of a function whose library has no machine code yet. Calling it
    emits the library, makes numba's entry, gives that to the dispatcher and calls it; as a key
    (numba registers the entry as the function's implementation) it stands for the function."""

    __slots__ = ("context", "library", "fndesc", "env", "entry", "dispatcher", "compile_result")

    def __init__(self, context, library, fndesc, env):
        self.context, self.library, self.fndesc, self.env = context, library, fndesc, env
        self.entry = None
        self.dispatcher = None  # weak reference, set when the dispatcher takes this overload
        self.compile_result = None

    def materialize(self):
        with global_compiler_lock:
            if self.entry is None:
                self.entry = _GET_EXECUTABLE(self.context, self.library, self.fndesc, self.env)
                owner = self.dispatcher() if self.dispatcher is not None else None
                if owner is not None:
                    result = self.compile_result
                    owner._insert([a._code for a in result.signature.args], self.entry, result.objectmode)
        return self.entry

    def cache_as_object_code(self) -> None:
        """Replace the function's cache entry (its optimised module) by its object code."""
        owner = self.dispatcher() if self.dispatcher is not None else None
        cache = getattr(owner, "_cache", None)
        if cache is not None:
            cache.save_overload(tuple(self.compile_result.signature.args), self.compile_result)

    def __call__(self, *args, **kwargs):
        return self.materialize()(*args, **kwargs)

    def __repr__(self) -> str:
        state = "emitted" if self.entry is not None else "no machine code yet"
        return f"<Deferred {self.fndesc.qualname}: {state}>"


def _in_scope(fndesc) -> bool:
    module = getattr(fndesc, "modname", None)
    return isinstance(module, str) and module.split(".")[0] in DEFERRED_MODULES


def _get_executable(self, library, fndesc, env):
    if not isinstance(library, _JIT_LIBRARY) or not _in_scope(fndesc) or (library._finalized and not _pending(library)):
        return _GET_EXECUTABLE(self, library, fndesc, env)
    library._emission_wanted_later = True
    library._ensure_finalized()
    return Deferred(self, library, fndesc, env)


def _add_overload(self, cres):
    entry = cres.entry_point
    if not isinstance(entry, Deferred):
        return _ADD_OVERLOAD(self, cres)
    entry.dispatcher = weakref.ref(self)
    entry.compile_result = cres
    entry.library._deferred_entry = entry
    self.overloads[tuple(cres.signature.args)] = cres
    return None


_REPLACEMENTS = {
    (_LIBRARY, "_finalize_final_module"): _finalize_final_module,
    (_LIBRARY, "serialize_using_object_code"): _serialize_using_object_code,
    (_LIBRARY, "_unserialize"): _unserialize,
    (_JIT_LIBRARY, "get_pointer_to_function"): _get_pointer_to_function,
    (cpu.CPUContext, "get_executable"): _get_executable,
    (dispatcher._DispatcherBase, "add_overload"): _add_overload,
    (_JIT_CODEGEN, "set_env"): _set_env,
}
for _key, _replacement in _REPLACEMENTS.items():
    _replacement.numba_original = _ORIGINAL[_key]


def install() -> bool:
    """Defer machine code in numba's CPU target as described above; True if it is in place."""
    if not _laid_out_as_expected():
        return False
    for (owner, name), replacement in _REPLACEMENTS.items():
        setattr(owner, name, classmethod(replacement) if name == "_unserialize" else replacement)
    return True


def installed() -> bool:
    return _LIBRARY.__dict__["_finalize_final_module"] is _finalize_final_module
