"""Named arrays: values with their unit, dimension names and description (the Python API's
results; `bearingsim.pipeline.api`). Plain numpy; `.to_xarray()` converts when xarray is
installed, which bearingsim does not require."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np


@dataclass(frozen=True)
class NamedArray:
    """An array with its unit, the names of its dimensions and what it is.

    `np.asarray(a)` gives the values; `a.to_xarray()` an `xarray.DataArray` (xarray needed).
    """

    values: np.ndarray
    unit: str
    dims: tuple[str, ...]
    description: str = ""
    name: str = ""

    def __array__(self, dtype=None, copy=None):
        values = np.asarray(self.values, dtype=dtype)
        return values.copy() if copy else values

    def __len__(self) -> int:
        return len(self.values)

    @property
    def shape(self) -> tuple[int, ...]:
        return np.shape(self.values)

    def __repr__(self) -> str:
        return (f"NamedArray({self.name!r}, shape={self.shape}, dims={self.dims}, unit={self.unit!r}: "
                f"{self.description})")

    def to_xarray(self, coords: Mapping[str, Any] | None = None):
        """An `xarray.DataArray` (attrs `units`, `description`); `coords` by dimension name."""
        xr = _xarray()
        used = {d: c for d, c in (coords or {}).items() if d in self.dims}
        return xr.DataArray(self.values, dims=self.dims, coords=used, name=self.name or None,
                            attrs={"units": self.unit, "description": self.description})


def _xarray():
    try:
        import xarray
    except ImportError:
        raise ImportError("to_xarray() needs xarray, which bearingsim does not require: "
                          "pip install xarray (the arrays themselves are in .values)") from None
    return xarray


COMPONENT_LABELS = {"xyz": ["x", "y", "z"], "xy": ["x", "y"], "t_h": ["time", "step_size"]}


class TimeSeries(Mapping):
    """`timeseries.h5` as a read-only mapping: name (e.g. "cage/position") -> NamedArray.
    `attrs` holds the file's attributes (scene, version, ball count, guide clearance)."""

    def __init__(self, arrays: dict[str, NamedArray], attrs: dict, path: Path | None = None):
        self._arrays, self.attrs, self.path = arrays, attrs, path

    def __getitem__(self, name: str) -> NamedArray:
        try:
            return self._arrays[name]
        except KeyError:
            raise KeyError(f"no time series {name!r}; available: {', '.join(self._arrays)}") from None

    def __iter__(self):
        return iter(self._arrays)

    def __len__(self) -> int:
        return len(self._arrays)

    def __repr__(self) -> str:
        lines = [f"TimeSeries({self.path or ''}, {len(self)} variables)"]
        lines += [f"  {n:<32} {a.shape!s:<16} [{a.unit}]  {a.description}" for n, a in self._arrays.items()]
        return "\n".join(lines)

    def coords(self) -> dict[str, np.ndarray]:
        """Coordinates by dimension: time (from "time"), ball index, component labels."""
        out: dict[str, Any] = {d: np.array(labels) for d, labels in COMPONENT_LABELS.items()}
        if "time" in self._arrays:
            out["time"] = np.asarray(self._arrays["time"].values)
        balls = next((a.shape[a.dims.index("ball")] for a in self._arrays.values() if "ball" in a.dims), None)
        if balls is not None:
            out["ball"] = np.arange(balls)
        return out

    def to_xarray(self):
        """An `xarray.Dataset` of every series (time as coordinate; xarray needed)."""
        xr = _xarray()
        coords = self.coords()
        variables = {n: a.to_xarray(coords) for n, a in self._arrays.items() if n != "time"}
        return xr.Dataset(variables, coords={"time": coords["time"]} if "time" in coords else None,
                          attrs={k: _plain(v) for k, v in self.attrs.items()})


def _plain(value):
    return value.item() if isinstance(value, np.generic) else value
