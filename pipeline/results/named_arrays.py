"""Named arrays: values with their unit, dimension names and description (the Python API's
results; `bearingsim.pipeline.api`). Plain numpy; `.to_xarray()` converts when xarray is
installed, which bearingsim does not require."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np


@dataclass(frozen=True)
class NamedArray:
    """An array with its unit, the names of its dimensions and what it is.

    `np.asarray(a)` gives the values; `a.to_xarray()` an `xarray.DataArray` (xarray needed)
    with the coordinates of `coords` (set on the arrays a `TimeSeries` hands out).
    """

    values: np.ndarray
    unit: str
    dims: tuple[str, ...]
    description: str = ""
    name: str = ""
    coords: Mapping[str, Any] | None = field(default=None, repr=False, compare=False)

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
        """An `xarray.DataArray` that netCDF takes as it is: its name netCDF-safe
        (`cage/position` -> `cage_position`; the original in attribute `bearingsim_name`),
        `units` a UDUNITS string ("N m", "1"), `long_name` the description; `coords` by
        dimension name [default: the array's own `coords`]."""
        xr = _xarray()
        coords = self.coords if coords is None else coords
        used = {d: c for d, c in (coords or {}).items() if d in self.dims}
        attrs = {"units": udunits(self.unit), "long_name": self.description, "description": self.description}
        if self.name:
            attrs["bearingsim_name"] = self.name
        return xr.DataArray(self.values, dims=self.dims, coords=used, name=netcdf_name(self.name) or None,
                            attrs=attrs)


# bearingsim's unit strings that UDUNITS (netCDF's CF conventions, pint) reads otherwise
UDUNITS = {"-": "1", "": "1", "count": "1", "N.m": "N m", "N.m/rad": "N m/rad", "N.m/m": "N m/m",
           "N·m": "N m", "N·m/rad": "N m/rad", "deg": "degree", "µm": "um"}


def udunits(unit: str) -> str:
    """A unit string UDUNITS parses: "-" -> "1", "N.m" -> "N m"; others unchanged."""
    return UDUNITS.get(unit, unit.replace("N.m", "N m").replace("·", " "))


def netcdf_name(name: str) -> str:
    """A netCDF variable name: the group separator and other characters netCDF refuses
    become "_" (`cage_race/force` -> `cage_race_force`)."""
    out = "".join(c if c.isalnum() or c in "_-." else "_" for c in name)
    return out if not out or out[0].isalpha() or out[0] == "_" else f"v_{out}"


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

    def __init__(self, arrays: dict[str, NamedArray], attrs: dict, path: Path | None = None,
                 time: np.ndarray | None = None):
        """`time` [s]: the sample times, the time coordinate even when "time" is not one of
        the arrays (a selection of names); taken from `arrays["time"]` when not given."""
        self._arrays, self.attrs, self.path = arrays, attrs, path
        self._time = np.asarray(time) if time is not None else (
            np.asarray(arrays["time"].values) if "time" in arrays else None)

    def __getitem__(self, name: str) -> NamedArray:
        try:
            return replace(self._arrays[name], coords=self.coords())  # a.to_xarray() has them too
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
        if self._time is not None:
            out["time"] = self._time
        balls = next((a.shape[a.dims.index("ball")] for a in self._arrays.values() if "ball" in a.dims), None)
        if balls is not None:
            out["ball"] = np.arange(balls)
        return out

    def to_xarray(self):
        """An `xarray.Dataset` of every series, time as coordinate (with its unit), names
        netCDF-safe (`NamedArray.to_xarray`): `.to_netcdf(path)` writes it as it is."""
        xr = _xarray()
        coords = self.coords()
        variables = {}
        for n, a in self._arrays.items():
            if n == "time":
                continue
            da = a.to_xarray(coords)
            if da.name in variables:
                raise ValueError(f"{n!r} and {variables[da.name].attrs['bearingsim_name']!r} share the "
                                 f"netCDF name {da.name!r}")
            variables[da.name] = da
        ds = xr.Dataset(variables, attrs={k: _plain(v) for k, v in self.attrs.items()})
        if "time" in coords:
            ds = ds.assign_coords(time=("time", coords["time"], {"units": "s", "long_name": "sample time",
                                                                 "standard_name": "time"}))
        return ds


def _plain(value):
    return value.item() if isinstance(value, np.generic) else value
