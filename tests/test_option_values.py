"""Option values that cannot work are usage errors (exit 2) with the option named, before
anything runs or is written: a scheduler address that is none, a stability window without
samples (docs/reliability.md)."""

from __future__ import annotations

import pytest
from typer.testing import CliRunner

from bearingsim.pipeline.cli.commands import app


@pytest.mark.parametrize("address", ["not a url", "tcp://host", "http://host:8786", "tcp://host:0", ""])
def test_a_scheduler_address_that_is_none_is_a_usage_error(address, tmp_path):
    result = CliRunner().invoke(app, ["sweep", "helicopter-b-given-hinge", "--vary", "load.moment=0,1",
                                      "--scheduler", address, "--out", str(tmp_path / "s")])
    assert result.exit_code == 2, result.output
    assert "--scheduler" in result.stderr and "tcp://host:8786" in result.stderr.replace("\n", " ")
    assert not (tmp_path / "s").exists()
    assert result.exception is None or isinstance(result.exception, SystemExit)


@pytest.mark.parametrize("window", ["1e-300", "1.5e-5", "0", "-1", "nan", "inf", "1e308"])
def test_a_stability_window_without_samples_is_a_usage_error(window, tmp_path):
    result = CliRunner().invoke(app, ["stability", "dry-contact", "--window", window, "--out", str(tmp_path / "s")])
    assert result.exit_code == 2, result.output
    assert "--window" in result.stderr and "Traceback" not in result.output
    assert not (tmp_path / "s").exists()
