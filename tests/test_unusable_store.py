"""An unusable stage store (a file, an unwritable folder) is named with what to do, and the run
falls back to computing the stage in its own directory instead of failing (docs/reliability.md)."""

from __future__ import annotations

import os

import pytest
from typer.testing import CliRunner

from bearingsim.pipeline.cli.commands import app

# a coarse, uniform mesh: the identification in a few seconds (accuracy is not the point here)
COARSE = ["--set", "fe.mesh_size=0.035", "--set", "fe.edge_refinement=1.0", "--set", "fe.element_order=1"]


def _a_file(tmp_path):
    (tmp_path / "afile").write_text("mine\n")
    return tmp_path / "afile"


def _read_only(tmp_path):
    (tmp_path / "ro").mkdir()
    (tmp_path / "ro").chmod(0o555)
    return tmp_path / "ro"


@pytest.mark.skipif(os.geteuid() == 0, reason="root writes into read-only folders")
def test_read_only_store_is_reported(tmp_path, monkeypatch):
    _check_fallback(_read_only(tmp_path), tmp_path, monkeypatch)


@pytest.mark.filterwarnings("ignore")
def test_a_store_that_is_a_file_falls_back_to_local_computing(tmp_path, monkeypatch):
    store = _a_file(tmp_path)
    _check_fallback(store, tmp_path, monkeypatch)
    assert store.read_text() == "mine\n"


def _check_fallback(store, tmp_path, monkeypatch):
    monkeypatch.setenv("BEARINGSIM_STAGE_STORE", str(store))
    out = tmp_path / "x"
    result = CliRunner().invoke(app, ["identify", "helicopter-b", "--out", str(out), *COARSE])
    assert result.exit_code == 0, result.output[-3000:]
    assert f"the stage store {store} cannot be used" in result.stderr
    assert "--no-store" in result.stderr and "BEARINGSIM_STAGE_STORE" in result.stderr
    assert (out / "identify" / "hinge.toml").is_file()
    assert "cannot be used" in (out / "run.log").read_text()
