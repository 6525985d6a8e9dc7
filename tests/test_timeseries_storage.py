"""timeseries.h5 storage: datasets chunked by whole rows along time and gzip-compressed
behind the shuffle filter, read back bit for bit by plain h5py and by read_timeseries."""

from __future__ import annotations

import h5py
import numpy as np
import pytest

from bearingsim.pipeline.results.timeseries import (
    CHUNK_BYTES,
    COMPRESS_MIN_BYTES,
    Series,
    chunk_shape,
    read_timeseries,
    write_timeseries,
)

N, Z = 20_001, 22  # samples of a 0.2 s run at 1e-5 s; balls of the reference bearing


def _series() -> dict[str, Series]:
    t = np.linspace(0.0, 0.2, N)
    phase = 2 * np.pi * 23.0 * t[:, None] + np.linspace(0, 2 * np.pi, Z, endpoint=False)[None, :]
    xyz = np.stack([0.079 * np.cos(phase), 0.079 * np.sin(phase), 1e-6 * np.sin(3 * phase)], axis=-1)
    return {
        "time": Series(t, "s", "sample time"),
        "balls/position": Series(xyz, "m", "ball centres", ("time", "ball", "xyz"), True),
        "cage/speed": Series(143.7 + 0.1 * np.sin(2 * np.pi * 50 * t), "rad/s", "cage speed"),
        "solver/step_size": Series(np.zeros((7, 2)), "s", "(time, step)", ("sample", "t_h")),
    }


def test_large_datasets_are_chunked_and_compressed_small_ones_contiguous(tmp_path):
    series = _series()
    path = tmp_path / "ts.h5"
    write_timeseries(path, series, {"scene": "x"})
    with h5py.File(path, "r") as h5:
        for name in ("time", "balls/position", "cage/speed"):
            ds = h5[name]
            assert ds.compression == "gzip" and ds.shuffle, name
            # whole rows per chunk (one chunk holds every ball and component of its samples)
            assert ds.chunks[1:] == ds.shape[1:] and ds.chunks == chunk_shape(ds.shape, ds.dtype.itemsize)
            assert ds.chunks[0] * ds.dtype.itemsize * int(np.prod(ds.shape[1:])) <= CHUNK_BYTES
        assert h5["balls/position"].chunks[0] < N  # 5.3 MB of ball positions span several chunks
        small = h5["solver/step_size"]
        assert small.nbytes < COMPRESS_MIN_BYTES and small.compression is None and small.chunks is None
        stored = sum(h5[n].id.get_storage_size() for n in series)
        raw = sum(h5[n].nbytes for n in series)
    # smooth signals: shuffle + deflate must gain well over 10 % (measured ~40-60 %)
    assert stored < 0.9 * raw


def test_compressed_file_round_trips_exactly(tmp_path):
    series = _series()
    path = tmp_path / "ts.h5"
    write_timeseries(path, series, {"scene": "x", "ball_count": Z})
    back, attrs = read_timeseries(path)
    assert attrs["scene"] == "x" and attrs["ball_count"] == Z
    assert set(back) == set(series)
    for name, s in series.items():
        expected = np.asarray(s.data, dtype=np.float32) if s.store_float32 else np.asarray(s.data)
        assert back[name].data.dtype == expected.dtype
        np.testing.assert_array_equal(back[name].data, expected)
        assert (back[name].units, back[name].description, back[name].dims) == (s.units, s.description, s.dims)
    with h5py.File(path, "r") as h5:  # plain h5py, slices across chunk boundaries
        rows = slice(N // 2 - 3, N // 2 + 3)
        np.testing.assert_array_equal(h5["time"][rows], series["time"].data[rows])


def test_read_selected_names(tmp_path):
    path = tmp_path / "ts.h5"
    write_timeseries(path, _series())
    back, _ = read_timeseries(path, ["cage/speed", "time"])
    assert list(back) == ["cage/speed", "time"]
    with pytest.raises(KeyError, match="no dataset 'cage/position'.*balls/position"):
        read_timeseries(path, ["cage/position"])


def test_chunk_shape_limits():
    assert chunk_shape((10, 22, 3), 4) == (10, 22, 3)  # short run: one chunk
    assert chunk_shape((10**6,), 8) == (CHUNK_BYTES // 8,)
    assert chunk_shape((5, 10**6), 8) == (1, 10**6)  # a row larger than a chunk: one row each
