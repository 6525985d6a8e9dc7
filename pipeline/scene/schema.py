"""Build frozen dataclasses from TOML tables, validating as we go.

Each dataclass field may carry metadata: ``unit`` (str), bounds ``gt``/``ge``/``lt``/``le``,
``choices`` (allowed values) and ``doc``. A bad value raises `SceneError` naming the
dotted key, the value, what is allowed and the unit — before anything is computed.
"""

from __future__ import annotations

import dataclasses
import math
import types
import typing
from typing import Any


class SceneError(ValueError):
    """A scene value is missing, unknown, of the wrong type or out of range."""

    def __init__(self, key: str, message: str):
        self.key = key
        super().__init__(f"{key}: {message}" if key else message)


def describe_bounds(meta: dict) -> str:
    parts = []
    for name, sym in (("gt", ">"), ("ge", ">="), ("lt", "<"), ("le", "<=")):
        if name in meta:
            parts.append(f"{sym} {meta[name]:g}")
    return " and ".join(parts)


def unit_suffix(meta: dict) -> str:
    unit = meta.get("unit")
    return f" [{unit}]" if unit and unit != "-" else ""


# Every number of a scene is one the model can compute with. A real number lies within
# MAGNITUDE in size, or is zero where its key allows zero: no quantity of a bearing in SI units
# comes within decades of these bounds (the smallest, a film floor or a solver tolerance, are
# 1e-15 .. 1e-10; the largest, elastic moduli and stiffnesses, 1e12), and a product of ten such
# numbers still fits a double (1e-308 .. 1e308), so no formula of the model overflows to
# infinity or underflows to zero on a scene's input (docs/reliability.md). An integer fits the
# 64 bits of the compiled kernels' integers.
MAGNITUDE = (1e-30, 1e30)
INTEGER_LIMIT = 2**63 - 1


def shown_number(value: Any) -> str:
    """A number as a message shows it: an integer too long to read (or to print: Python
    refuses beyond 4300 digits) by its size."""
    if isinstance(value, bool):  # as the scene file writes it
        return "true" if value else "false"
    if isinstance(value, int) and abs(value) >= 10**20:
        try:
            digits = f"{len(str(abs(value)))}"
        except ValueError:  # longer than Python prints
            digits = f"about {int(abs(value).bit_length() * math.log10(2)) + 1}"
        return f"{'-' if value < 0 else ''}an integer of {digits} digits"
    return repr(value)


def check_number(key: str, value: Any, meta: dict, *, integer: bool = False) -> float | int:
    """Type, finiteness and range check of one scalar: the key's own bounds, then what the
    model can compute with (MAGNITUDE, INTEGER_LIMIT)."""
    unit = unit_suffix(meta)
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        kind = "an integer" if integer else "a number"
        raise SceneError(key, f"expected {kind}{unit}, got {shown_number(value)} ({type(value).__name__})")
    if integer and not isinstance(value, int):
        raise SceneError(key, f"expected an integer{unit}, got {value!r}")
    if isinstance(value, float) and not math.isfinite(value):
        raise SceneError(key, f"must be a finite number{unit}, got {value!r}")
    ok = (
        ("gt" not in meta or value > meta["gt"])
        and ("ge" not in meta or value >= meta["ge"])
        and ("lt" not in meta or value < meta["lt"])
        and ("le" not in meta or value <= meta["le"])
    )
    if not ok:
        raise SceneError(key, f"{shown_number(value)} is out of range: allowed {describe_bounds(meta)}{unit}")
    if integer:
        if abs(value) > INTEGER_LIMIT:
            allowed = _joined(describe_bounds(meta), "at most 2**63 - 1 in size")
            raise SceneError(key, f"{shown_number(value)} is out of range: allowed {allowed}{unit}")
        return value
    if not _within(value):
        small, large = MAGNITUDE
        zero = " (or 0)" if _allows_zero(meta) else ""
        limit = f"{_e(small)} <= |value| <= {_e(large)}{zero}, the sizes of a bearing's quantities in SI units"
        raise SceneError(key, f"{shown_number(value)} is out of range: allowed {_joined(describe_bounds(meta), limit)}{unit}")
    return float(value)


def _within(value: float) -> bool:
    """Zero, or a size inside MAGNITUDE."""
    return value == 0 or MAGNITUDE[0] <= abs(value) <= MAGNITUDE[1]


def _e(x: float) -> str:
    return f"{x:g}".replace("e+", "e")


def _joined(bounds: str, limit: str) -> str:
    return f"{bounds} and {limit}" if bounds else limit


def _allows_zero(meta: dict) -> bool:
    return (("gt" not in meta or 0 > meta["gt"]) and ("ge" not in meta or 0 >= meta["ge"])
            and ("lt" not in meta or 0 < meta["lt"]) and ("le" not in meta or 0 <= meta["le"]))


def _strip_optional(tp: Any) -> tuple[Any, bool]:
    """`float | None` -> (float, True); `float | tuple[float, float] | None` ->
    (float | tuple[float, float], True)."""
    origin = typing.get_origin(tp)
    if origin in (typing.Union, types.UnionType):
        args = [a for a in typing.get_args(tp) if a is not type(None)]
        optional = len(args) < len(typing.get_args(tp))
        if len(args) == 1:
            return args[0], optional
        return typing.Union[tuple(args)], optional
    return tp, False


def _one_or_list(key: str, value: Any, tp: Any, meta: dict) -> Any:
    """A union of a scalar type and a tuple of it (`float | tuple[float, float]`: one value, or
    one a side): a list takes the tuple form, anything else the scalar's."""
    args = typing.get_args(tp)
    scalar = [a for a in args if typing.get_origin(a) is not tuple]
    listed = [a for a in args if typing.get_origin(a) is tuple]
    if len(scalar) != 1 or len(listed) != 1:
        raise TypeError(f"schema: unsupported field type {tp!r} for {key}")
    if isinstance(value, (list, tuple)):
        return _convert_tuple(key, value, listed[0], meta)
    return convert(key, value, scalar[0], {k: v for k, v in meta.items() if k != "length"})


def convert(key: str, value: Any, tp: Any, meta: dict) -> Any:
    """Convert a TOML value to the annotated type, validating it."""
    tp, optional = _strip_optional(tp)
    if value is None and optional:
        return None
    if "choices" in meta and value not in meta["choices"]:
        allowed = ", ".join(repr(c) for c in meta["choices"])
        raise SceneError(key, f"{value!r} is not allowed: choose one of {allowed}")
    if tp is bool:
        if not isinstance(value, bool):
            raise SceneError(key, f"expected true or false, got {value!r}")
        return value
    if tp is int:
        return check_number(key, value, meta, integer=True)
    if tp is float:
        return check_number(key, value, meta)
    if tp is str:
        if not isinstance(value, str):
            raise SceneError(key, f"expected a string, got {value!r} ({type(value).__name__})")
        return value
    if dataclasses.is_dataclass(tp):
        return build(tp, value, key)
    origin = typing.get_origin(tp)
    if origin is tuple:
        return _convert_tuple(key, value, tp, meta)
    if origin in (typing.Union, types.UnionType):
        return _one_or_list(key, value, tp, meta)
    raise TypeError(f"schema: unsupported field type {tp!r} for {key}")


def _convert_tuple(key: str, value: Any, tp: Any, meta: dict) -> tuple:
    args = typing.get_args(tp)
    if not isinstance(value, (list, tuple)):
        raise SceneError(key, f"expected a list, got {value!r}{unit_suffix(meta)}")
    if len(args) == 2 and args[1] is Ellipsis:
        item_types = [args[0]] * len(value)
    else:
        if len(value) != len(args):
            raise SceneError(key, f"expected a list of {len(args)} values{unit_suffix(meta)}, got {len(value)}")
        item_types = list(args)
    n = meta.get("length")
    if n is not None and len(value) not in (n if isinstance(n, tuple) else (n,)):
        raise SceneError(key, f"expected a list of {n} values{unit_suffix(meta)}, got {len(value)}")
    return tuple(convert(f"{key}[{i}]", v, t, meta) for i, (v, t) in enumerate(zip(value, item_types)))


def build(cls: type, table: Any, path: str) -> Any:
    """Instantiate dataclass `cls` from TOML `table` found at dotted `path`."""
    if not isinstance(table, dict):
        raise SceneError(path, f"expected a table, got {table!r}")
    hints = typing.get_type_hints(cls)
    fields = {f.name: f for f in dataclasses.fields(cls) if f.init}
    unknown = sorted(set(table) - set(fields))
    if unknown:
        allowed = ", ".join(sorted(fields))
        raise SceneError(f"{path}.{unknown[0]}" if path else unknown[0],
                         f"unknown key; allowed keys here: {allowed}")
    kwargs = {}
    for name, f in fields.items():
        key = f"{path}.{name}" if path else name
        if name in table:
            kwargs[name] = convert(key, table[name], hints[name], dict(f.metadata))
        elif f.default is dataclasses.MISSING and f.default_factory is dataclasses.MISSING:
            unit = unit_suffix(dict(f.metadata))
            raise SceneError(key, f"required key is missing{unit}")
    try:
        return cls(**kwargs)
    except SceneError:
        raise
    except (ValueError, TypeError) as exc:  # __post_init__ cross-checks
        raise SceneError(path, str(exc)) from exc


def field_unit(cls: type, name: str) -> str:
    for f in dataclasses.fields(cls):
        if f.name == name:
            return f.metadata.get("unit", "")
    return ""
