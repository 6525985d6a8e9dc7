"""The prestarted plotting process of `bearingsim quasistatic` (pipeline/figures/worker.py)."""

from __future__ import annotations

import json

import pytest
from typer.testing import CliRunner

from bearingsim.pipeline.cli.commands import app
from bearingsim.pipeline.figures import worker as figure_worker

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


def _quasistatic(tmp_path, *extra):
    result = CliRunner().invoke(app, ["quasistatic", "deep-groove-209", "--json", "--out", str(tmp_path), *extra])
    assert result.exit_code == 0, result.output
    return json.loads(result.stdout), tmp_path / "quasistatic" / "load_distribution.png"


def test_quasistatic_cli_writes_json_and_figure_through_the_worker(tmp_path, monkeypatch):
    drawn = []
    real_draw = figure_worker.FigureWorker.draw
    monkeypatch.setattr(figure_worker.FigureWorker, "draw",
                        lambda self, figure, *a, **k: (drawn.append(figure), real_draw(self, figure, *a, **k)))
    doc, png = _quasistatic(tmp_path)
    assert len(doc["balls"]) == 9
    assert drawn == ["load_distribution"]
    assert png.read_bytes()[:8] == PNG_MAGIC
    assert figure_worker._prestarted is None  # handed to the stage, not left running


def test_a_failing_worker_falls_back_to_drawing_in_process(tmp_path, monkeypatch, caplog):
    def broken(self, figure, *a, **k):
        raise figure_worker.FigureWorkerError("simulated failure")

    monkeypatch.setattr(figure_worker.FigureWorker, "draw", broken)
    _, png = _quasistatic(tmp_path, "--force")
    assert png.read_bytes()[:8] == PNG_MAGIC
    assert "simulated failure" in caplog.text


def test_worker_reports_its_error_and_unused_workers_are_stopped(tmp_path):
    with figure_worker.FigureWorker() as w:
        with pytest.raises(figure_worker.FigureWorkerError, match="no_such_figure"):
            w.draw("no_such_figure", {}, tmp_path / "x.png")
    figure_worker.prestart()
    w = figure_worker._prestarted
    assert w is not None and w.alive()
    figure_worker._release_prestarted()
    assert not w.alive() and figure_worker._prestarted is None


def test_without_a_prestarted_worker_the_figure_is_drawn_here(tmp_path, monkeypatch):
    # `run`, sweeps and library calls draw in-process: no plotting process per stage
    def no_process(self):
        raise AssertionError("a figure worker was started without prestart()")

    monkeypatch.setattr(figure_worker.FigureWorker, "__init__", no_process)
    monkeypatch.setattr(figure_worker, "prestart", lambda: None)
    _, png = _quasistatic(tmp_path)
    assert png.read_bytes()[:8] == PNG_MAGIC
