"""Self-describing HDF5 time series: every dataset carries `units` and `description`.

Written atomically (temporary file + rename) so a reader never sees a half-written file.
Opens in any HDF5 tool (h5py, h5dump, HDFView, ParaView's HDF5 reader, xarray via h5netcdf).
Dimensions are named with HDF5 dimension scales, as netCDF-4 names them, so xarray and
netCDF tools see "time", "ball", "xyz" rather than anonymous dimensions.

Storage: every dataset of at least :data:`COMPRESS_MIN_BYTES` is chunked along its first
(time) axis and compressed with gzip (deflate) behind the byte-shuffle filter. gzip is the
one compression filter every HDF5 build reads (h5dump, HDFView, MATLAB, netCDF-4, ParaView);
lzf is slightly faster but only h5py reads it. The shuffle filter groups the bytes of
neighbouring floats by significance, which is what lets deflate find repeats in smooth
signals. A chunk holds whole rows (all balls, all components of a block of samples) of at
most :data:`CHUNK_BYTES`, so reading one instant, or a time window, decompresses only the
chunks that hold it and stays within HDF5's default 1 MiB chunk cache. Readers need nothing
special: the filters are applied transparently.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Iterable

import numpy as np

from .named_arrays import udunits

COMPRESSION = "gzip"
COMPRESSION_LEVEL = 4  # levels 6-9 gain < 1 % on these series and write 1.5-3x slower
CHUNK_BYTES = 256 * 1024
COMPRESS_MIN_BYTES = 4096  # below this a chunk index costs about what compression saves


@dataclass(frozen=True)
class Series:
    """One saved variable: data, unit, description and the names of its dimensions."""

    data: np.ndarray
    units: str
    description: str
    dims: tuple[str, ...] = ("time",)
    store_float32: bool = False  # bulky per-ball series: 7 significant digits are plenty


def chunk_shape(shape: tuple[int, ...], itemsize: int, chunk_bytes: int = CHUNK_BYTES) -> tuple[int, ...]:
    """Chunks of whole rows along the first axis, at most `chunk_bytes` (at least one row)."""
    row_bytes = itemsize * int(np.prod(shape[1:], dtype=np.int64))
    rows = max(1, min(shape[0], chunk_bytes // max(1, row_bytes)))
    return (rows, *shape[1:])


def storage_options(data: np.ndarray) -> dict:
    """h5py `create_dataset` keywords for `data`: chunked + gzip + shuffle, or contiguous
    when the dataset is a scalar, empty or smaller than COMPRESS_MIN_BYTES."""
    if data.ndim == 0 or data.size == 0 or data.nbytes < COMPRESS_MIN_BYTES:
        return {}
    return {"chunks": chunk_shape(data.shape, data.dtype.itemsize), "compression": COMPRESSION,
            "compression_opts": COMPRESSION_LEVEL, "shuffle": True}


def write_timeseries(path: Path, series: dict[str, Series], attrs: dict | None = None) -> None:
    """Write `series` (name -> Series; names may contain '/' for groups) to `path`.

    The file is built in memory (HDF5's core driver) and written by Python atomically: HDF5
    writing to a full disk fails in its own way (a RuntimeError on close, then a segmentation
    fault when Python collects the broken file object), a Python write raises OSError (ENOSPC)
    and leaves nothing. The compressed image is smaller than the series it holds, which the
    dynamic run's memory check counts (pipeline.scene.validity.SAMPLE_COPIES)."""
    import h5py

    from ..staging.artefacts import atomic_write_bytes

    path = Path(path)
    with h5py.File(path.name, "w", driver="core", backing_store=False) as h5:
        _fill(h5, series, attrs)
        h5.flush()
        image = h5.id.get_file_image()
    atomic_write_bytes(path, image)


def _fill(h5, series: dict[str, Series], attrs: dict | None) -> None:
    """The datasets of `series` and the file attributes `attrs` in the open file `h5`."""
    for key, value in (attrs or {}).items():
        h5.attrs[key] = value
    written = {}
    for name, s in series.items():
        data = np.asarray(s.data)
        if data.ndim != len(s.dims):
            raise ValueError(f"{name}: data has {data.ndim} dimensions but dims are {s.dims}")
        if s.store_float32:
            data = data.astype(np.float32)
        ds = h5.create_dataset(name, data=data, **storage_options(data))
        ds.attrs["units"] = udunits(s.units)  # what netCDF and pint read (docs/outputs.md)
        ds.attrs["description"] = s.description
        ds.attrs["dims"] = ",".join(s.dims)
        written[name] = (ds, s.dims)
    attach_dimension_scales(h5, written)


# coordinate values of the dimensions that are not a series of their own
DIMENSION_LABELS = {"xyz": ["x", "y", "z"], "xy": ["x", "y"], "t_h": ["time", "step_size"]}


def attach_dimension_scales(h5, written: dict) -> None:
    """Name every dataset's dimensions as netCDF-4 does, with HDF5 dimension scales: the
    `time` series is the scale of dimension "time"; the others ("ball", "xyz", ...) get a
    small root dataset of their labels or indices. xarray (h5netcdf engine) then reads named
    dimensions instead of phony_dim_*; read_timeseries skips these label datasets."""
    import h5py

    sizes: dict[str, int] = {}
    for ds, dims in written.values():
        for dim, size in zip(dims, ds.shape):
            if sizes.setdefault(dim, size) != size:
                return  # one name, two lengths: not a netCDF dimension; leave the file unnamed
    scales = {}
    for dim, size in sizes.items():
        if dim in written and written[dim][0].shape == (size,):
            scale = written[dim][0]
        elif dim in h5:
            return  # a series of another shape holds the name
        else:
            labels = DIMENSION_LABELS.get(dim)
            data = (np.array(labels, dtype=h5py.string_dtype()) if labels is not None and len(labels) == size
                    else np.arange(size, dtype=np.int32))
            scale = h5.create_dataset(dim, data=data)
            scale.attrs["description"] = f"coordinate of dimension {dim!r}"
        scale.make_scale(dim)
        scales[dim] = scale
    for ds, dims in written.values():
        for i, dim in enumerate(dims):
            if scales[dim] != ds:
                ds.dims[i].attach_scale(scales[dim])


def read_timeseries(path: Path, names: Iterable[str] | None = None) -> tuple[dict[str, Series], dict]:
    """Read back what `write_timeseries` wrote: (name -> Series, file attributes).

    `names`: only these datasets (a KeyError names a missing one and lists what the file
    holds); None reads them all.
    """
    import h5py

    out: dict[str, Series] = {}
    with h5py.File(path, "r") as h5:
        attrs = {k: v for k, v in h5.attrs.items()}

        def read(name, obj):
            if isinstance(obj, h5py.Dataset) and not (names is None and _is_label_scale(obj)):
                out[name] = Series(obj[()], str(obj.attrs.get("units", "")),
                                   str(obj.attrs.get("description", "")),
                                   tuple(str(obj.attrs.get("dims", "")).split(",")))

        if names is None:
            h5.visititems(read)
        else:
            for name in names:
                obj = h5.get(name)
                if not isinstance(obj, h5py.Dataset):
                    held = []
                    h5.visititems(lambda n, o: held.append(n) if isinstance(o, h5py.Dataset)
                                  and not _is_label_scale(o) else None)
                    raise KeyError(f"{path} holds no dataset {name!r}; it holds: {', '.join(held)}")
                read(name, obj)
    return out, attrs


def _is_label_scale(ds) -> bool:
    """A dimension's label dataset of `attach_dimension_scales` (not a saved series)."""
    return ds.is_scale and "units" not in ds.attrs
