"""Self-describing HDF5 time series: every dataset carries `units` and `description`.

Written atomically (temporary file + rename) so a reader never sees a half-written file.
Opens in any HDF5 tool (h5py, h5dump, HDFView, ParaView's HDF5 reader, xarray via h5netcdf).
"""

from __future__ import annotations

import os
import tempfile
from dataclasses import dataclass
from pathlib import Path

import numpy as np


@dataclass(frozen=True)
class Series:
    """One saved variable: data, unit, description and the names of its dimensions."""

    data: np.ndarray
    units: str
    description: str
    dims: tuple[str, ...] = ("time",)
    store_float32: bool = False  # bulky per-ball series: 7 significant digits are plenty


def write_timeseries(path: Path, series: dict[str, Series], attrs: dict | None = None) -> None:
    """Write `series` (name -> Series; names may contain '/' for groups) to `path`."""
    import h5py

    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    os.close(fd)
    try:
        with h5py.File(tmp, "w") as h5:
            for key, value in (attrs or {}).items():
                h5.attrs[key] = value
            for name, s in series.items():
                data = np.asarray(s.data)
                if data.ndim != len(s.dims):
                    raise ValueError(f"{name}: data has {data.ndim} dimensions but dims are {s.dims}")
                if s.store_float32:
                    data = data.astype(np.float32)
                big = data.size > 4096
                ds = h5.create_dataset(name, data=data, compression="gzip" if big else None,
                                       compression_opts=4 if big else None, shuffle=big)
                ds.attrs["units"] = s.units
                ds.attrs["description"] = s.description
                ds.attrs["dims"] = ",".join(s.dims)
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


def read_timeseries(path: Path) -> tuple[dict[str, Series], dict]:
    """Read back what :func:`write_timeseries` wrote."""
    import h5py

    out: dict[str, Series] = {}
    with h5py.File(path, "r") as h5:
        attrs = {k: v for k, v in h5.attrs.items()}

        def visit(name, obj):
            if isinstance(obj, h5py.Dataset):
                out[name] = Series(obj[()], str(obj.attrs.get("units", "")),
                                   str(obj.attrs.get("description", "")),
                                   tuple(str(obj.attrs.get("dims", "")).split(",")))

        h5.visititems(visit)
    return out, attrs
