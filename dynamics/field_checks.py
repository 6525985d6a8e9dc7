"""Validation of a settings dataclass from its field metadata (docs/contributing.md, "Three
kinds of input"): `unit`, bounds `gt`/`ge`/`lt`/`le`, `choices`.

The scene loader (pipeline/scene/schema.py) enforces the same metadata on the scene's tables, with
its own messages, before anything is built; this check holds a settings object built
directly in code to the same rules.
"""

from __future__ import annotations

import math
import operator
from dataclasses import fields

_BOUNDS = {"gt": operator.gt, "ge": operator.ge, "lt": operator.lt, "le": operator.le}


def check_fields(obj, section: str) -> None:
    """Raise ValueError naming `section.key`, the value, the unit and what is allowed, for the
    first field of the dataclass `obj` whose value breaks its metadata."""
    for f in fields(obj):
        meta, value = f.metadata, getattr(obj, f.name)
        if "choices" in meta:
            if value not in meta["choices"]:
                allowed = ", ".join(repr(c) for c in meta["choices"])
                raise ValueError(f"{section}.{f.name} = {value!r} is not allowed; choose one of {allowed}")
            continue
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            continue
        bounds = {k: meta[k] for k in _BOUNDS if k in meta}
        if not math.isfinite(value) or not all(_BOUNDS[k](value, b) for k, b in bounds.items()):
            allowed = ", ".join(f"{k} {b:.6g}" for k, b in bounds.items()) or "a finite number"
            raise ValueError(f"{section}.{f.name} = {value!r} [{meta.get('unit', '-')}] is out of "
                             f"range; allowed: {allowed}")
