"""The example notebook docs/examples/moment_sweep.ipynb runs: its code cells are executed in
order in one namespace, in a fresh directory (no Jupyter needed), as a reader would run them."""

from __future__ import annotations

import json
import os
from pathlib import Path

NOTEBOOK = Path(__file__).resolve().parents[1] / "docs" / "examples" / "moment_sweep.ipynb"


def run_notebook(path: Path, where: Path) -> dict:
    cells = json.loads(path.read_text(encoding="utf-8"))["cells"]
    namespace: dict = {"__name__": "__main__"}
    cwd = os.getcwd()
    os.chdir(where)
    try:
        for n, cell in enumerate(cells):
            if cell["cell_type"] == "code":
                exec(compile("".join(cell["source"]), f"{path.name}[{n}]", "exec"), namespace)  # noqa: S102
    finally:
        os.chdir(cwd)
    return namespace


def test_example_notebook_runs(tmp_path):
    ns = run_notebook(NOTEBOOK, tmp_path)
    result = ns["result"]
    assert [r["load.moment"] for r in result.rows] == [200.0, 430.0, 600.0]
    assert all(r["status"] == "done" for r in result.rows), [r["error"] for r in result.rows]
    assert (tmp_path / "runs" / "notebook-moment-sweep" / "stability_map.png").is_file()
    assert "verdict" in ns["run"].summary
    if ns["orbit"] is not None:
        assert (tmp_path / "runs" / "notebook-cage-orbit.nc").is_file()
    kwargs = ns["ross_arguments"]["bearing_element"]
    assert len(kwargs["kxx"]) == 5 and kwargs["frequency"][0] == 0.0
