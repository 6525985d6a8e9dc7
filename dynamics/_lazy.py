"""Lazy package exports: a package names what it offers without importing its submodules (and
numba with them) until a name is first used, so loading a scene stays light."""

from __future__ import annotations

import importlib


def lazy_exports(package: str, exports: dict[str, str]):
    """(`__getattr__`, `__all__`) for `package`, whose `exports` map a name to the relative
    module defining it (PEP 562)."""

    def __getattr__(name):
        if name not in exports:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        module = importlib.import_module(exports[name], package)
        value = getattr(module, name)
        setattr(importlib.import_module(package), name, value)  # later lookups skip this hook
        return value

    return __getattr__, sorted(exports)
