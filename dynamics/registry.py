"""Registries of contact laws: one per kind of contact (ball–race traction, EHD film, ball–pocket
impact, cage–land), each mapping a law's name to the module that states it (docs/contact_laws.md).

An entry is plain Python, so that a scene's choices and checks read it without importing any
law's module and its numba functions: `Law` names the module, says whether the law needs a lubricant film,
and carries the few facts the rest of the model asks of it (`flags`). The module, imported the
first time a kernel needs it, holds the law itself as numba functions, its parameter bundle
`Params` (a NamedTuple of floats and integer codes, with a `UNITS` mapping of field -> unit) and
`pack(...)`, which builds that bundle from the scene's options. The kernels never name a law:
they call the kind's operations (`<kind>/…/operations.py`), which numba resolves, by the class of
the bundle they are given, to the registered module's function of the same name. A new law is
therefore one module and one `register` call.
"""

from __future__ import annotations

import importlib
from collections.abc import Iterator, Mapping
from dataclasses import dataclass, field
from types import ModuleType
from typing import Any


@dataclass(frozen=True)
class Law:
    """One law of a registry: `name` (the scene's choice), `module` (dotted, relative to the
    registry's package, or a module object), `doc` (one line for the scene reference), `film`
    (needs a lubricant and its film) and `flags` (what the model asks of the law, by key)."""

    name: str
    module: str | ModuleType
    doc: str
    film: bool = False
    flags: Mapping[str, Any] = field(default_factory=dict)


class Registry:
    """Laws of one kind by name. `operations`: the functions every module of a film law defines;
    `dry_operations`: those of a law without film (None: the same)."""

    def __init__(self, kind: str, package: str, operations: tuple[str, ...],
                 dry_operations: tuple[str, ...] | None = None):
        self.kind, self.package = kind, package
        self.operations = tuple(operations)
        self.dry_operations = self.operations if dry_operations is None else tuple(dry_operations)
        self._laws: dict[str, Law] = {}
        self._modules: dict[str, ModuleType] = {}

    # --- entries (plain Python) -------------------------------------------------------------
    def register(self, law: Law) -> Law:
        """Add `law`; a name already taken raises ValueError."""
        if law.name in self._laws:
            raise ValueError(f"{self.kind} law {law.name!r} is registered already")
        self._laws[law.name] = law
        return law

    def unregister(self, name: str) -> None:
        """Remove the law `name` (a toy law of a test, say)."""
        self._laws.pop(name)
        self._modules.pop(name, None)

    def __getitem__(self, name: str) -> Law:
        try:
            return self._laws[name]
        except KeyError:
            raise KeyError(f"no {self.kind} law {name!r}; choose from {', '.join(self._laws)}") from None

    def __contains__(self, name: object) -> bool:
        return isinstance(name, str) and name in self._laws

    def __iter__(self) -> Iterator[str]:
        return iter(list(self._laws))

    def __len__(self) -> int:
        return len(self._laws)

    def names(self) -> tuple[str, ...]:
        return tuple(self._laws)

    def items(self):
        return list(self._laws.items())

    def film_laws(self) -> tuple[str, ...]:
        return tuple(name for name, law in self._laws.items() if law.film)

    # --- modules (numba) -------------------------------------------------------------------
    def module(self, name: str) -> ModuleType:
        """The module of law `name`, imported and checked on first use: it must define `Params`,
        `pack` and the kind's operations."""
        if name not in self._modules:
            law = self[name]
            module = (law.module if isinstance(law.module, ModuleType)
                      else importlib.import_module(law.module, self.package))
            wanted = ("Params", "pack", *(self.operations if law.film else self.dry_operations))
            missing = [w for w in wanted if not hasattr(module, w)]
            if missing:
                raise TypeError(f"{self.kind} law {name!r}: its module {module.__name__} lacks "
                                f"{', '.join(missing)}")
            self._modules[name] = module
        return self._modules[name]

    def pack(self, name: str, *args, **kwargs):
        """The parameter bundle of law `name` (its module's `pack`)."""
        return self.module(name).pack(*args, **kwargs)

    def law_of(self, params_class: type) -> Law:
        """The law whose bundle class is `params_class` (TypeError if none is)."""
        for name in self._laws:
            if self.module(name).Params is params_class:
                return self._laws[name]
        raise TypeError(f"{params_class!r} is the bundle of no {self.kind} law ({', '.join(self._laws)})")

    def kernel(self, numba_type, operation: str):
        """The function `operation` of the law whose bundle numba typed as `numba_type` (or whose
        bundle class it is): what the kind's overloads return and its Python stubs call
        (`operations.py`)."""
        law = self.law_of(getattr(numba_type, "instance_class", numba_type))
        function = getattr(self.module(law.name), operation, None)
        if function is None:
            raise TypeError(f"{self.kind} law {law.name!r} has no {operation!r} "
                            f"({'a film law' if law.film else 'a law without film'})")
        return function
