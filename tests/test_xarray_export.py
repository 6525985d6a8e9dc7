"""Time series to xarray and netCDF: a selection keeps its time coordinate, names and units
are what netCDF and UDUNITS take, `to_netcdf` writes and reopens, and timeseries.h5 itself
opens in xarray with named dimensions (HDF5 dimension scales)."""

from __future__ import annotations

import numpy as np
import pytest
import tomli_w

import bearingsim
from bearingsim.pipeline.results.named_arrays import netcdf_name, udunits
from bearingsim.pipeline.results.timeseries import Series, read_timeseries, write_timeseries

xr = pytest.importorskip("xarray")
pytest.importorskip("h5netcdf")

N, Z = 120, 4


@pytest.fixture()
def run_dir(tmp_path):
    """A run directory holding a scene and a simulate/timeseries.h5 of known series."""
    scene = bearingsim.load_scene("helicopter-b-given-hinge")
    (tmp_path / "scene.toml").write_text(tomli_w.dumps(scene.raw))
    t = np.linspace(0.0, 0.012, N)
    series = {
        "time": Series(t, "s", "sample time"),
        "cage_race/force": Series(np.c_[np.sin(t), np.cos(t)], "N", "land force on the cage", ("time", "xy")),
        "cage_race/torque": Series(3.0 * t, "N.m", "land torque", ("time",)),
        "cage_race/eccentricity_ratio": Series(0.5 + t, "-", "eps", ("time",)),
        "balls/position": Series(np.ones((N, Z, 3)), "m", "ball centres", ("time", "ball", "xyz"), True),
        "solver/step_size": Series(np.zeros((7, 2)), "s", "(time, step)", ("sample", "t_h")),
    }
    write_timeseries(tmp_path / "simulate" / "timeseries.h5", series, {"scene": scene.name, "ball_count": Z})
    return tmp_path, t


def test_selection_to_netcdf_keeps_time_and_units(run_dir, tmp_path):
    path, t = run_dir
    ts = bearingsim.open_run(path).timeseries(["cage_race/force"])
    assert list(ts) == ["cage_race/force"]  # time is the coordinate, not an extra variable
    ds = ts.to_xarray()
    np.testing.assert_array_equal(ds["time"].values, t)
    window = ds.sel(time=slice(0.005, 0.006))  # failed without the coordinate
    assert 0 < window.sizes["time"] < N
    out = tmp_path / "force.nc"
    ds.to_netcdf(out)
    back = xr.open_dataset(out)
    try:
        np.testing.assert_array_equal(back["time"].values, t)
        assert back["time"].attrs["units"] == "s"
        force = back["cage_race_force"]
        assert force.dims == ("time", "xy") and force.attrs["units"] == "N"
        assert force.attrs["bearingsim_name"] == "cage_race/force"
        np.testing.assert_allclose(force.sel(xy="y").values, np.cos(t))
    finally:
        back.close()


def test_every_series_writes_to_netcdf_with_udunits_strings(run_dir, tmp_path):
    path, _ = run_dir
    ds = bearingsim.open_run(path).timeseries().to_xarray()
    assert ds["cage_race_torque"].attrs["units"] == "N m"
    assert ds["cage_race_eccentricity_ratio"].attrs["units"] == "1"
    assert ds["balls_position"].dims == ("time", "ball", "xyz")
    ds.to_netcdf(tmp_path / "all.nc")
    with xr.open_dataset(tmp_path / "all.nc") as back:
        assert set(back.data_vars) >= {"cage_race_force", "balls_position", "solver_step_size"}


def test_timeseries_h5_opens_in_xarray_with_named_dimensions(run_dir):
    path, t = run_dir
    h5 = path / "simulate" / "timeseries.h5"
    with xr.open_dataset(h5, engine="h5netcdf", group="cage_race") as ds:
        assert ds["force"].dims == ("time", "xy")
        assert not any(d.startswith("phony_dim") for d in ds.dims)
    with xr.open_dataset(h5, engine="h5netcdf", group="balls") as ds:
        assert ds["position"].dims == ("time", "ball", "xyz")
    with xr.open_dataset(h5, engine="h5netcdf") as root:
        np.testing.assert_array_equal(root["time"].values, t)
    back, _ = read_timeseries(h5)  # the dimension labels are not series
    assert set(back) == {"time", "cage_race/force", "cage_race/torque", "cage_race/eccentricity_ratio",
                         "balls/position", "solver/step_size"}


def test_unit_and_name_conversions():
    assert udunits("-") == "1" and udunits("N.m/rad") == "N m/rad" and udunits("rad/s") == "rad/s"
    assert netcdf_name("cage_race/force") == "cage_race_force" and netcdf_name("time") == "time"
