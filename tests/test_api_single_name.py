"""`open_run(...).timeseries("cage/position")` reads that one series: a single name is a name,
not a sequence of one-letter names."""

from __future__ import annotations

import warnings

import bearingsim


def test_timeseries_takes_a_single_name(tmp_path):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the run is far too short to settle, and says so
        bearingsim.run("helicopter-b-given-hinge", tmp_path / "run", ["simulate"],
                       overrides=["solver.duration=0.002", "output.figures=false"])
    run = bearingsim.open_run(tmp_path / "run")
    one = run.timeseries("cage/position")
    assert "cage/position" in one and "balls/position" not in one
    assert one["cage/position"].unit == "m" and one["cage/position"].dims == ("time", "xyz")
    both = run.timeseries(["cage/position", "cage/speed"])
    assert (one["cage/position"].values == both["cage/position"].values).all()
