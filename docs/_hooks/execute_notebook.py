"""Execute the example notebook and keep its outputs, which the docs site shows (mkdocs-jupyter,
`execute: false`, so that `mkdocs build` stays fast and needs no kernel).

    python docs/_hooks/execute_notebook.py [docs/examples/moment_sweep.ipynb]

Runs it in a fresh temporary directory (its runs/ go there), with nbclient and the python3
kernel of this environment (`pip install nbclient ipykernel`). tests/test_notebook.py runs the
same cells in the default suite, so a notebook whose code no longer works fails there.
"""

from __future__ import annotations

import sys
import tempfile
from pathlib import Path

NOTEBOOK = Path(__file__).resolve().parents[1] / "examples" / "moment_sweep.ipynb"


def main(path: Path = NOTEBOOK) -> None:
    import nbformat
    from nbclient import NotebookClient

    nb = nbformat.read(path, as_version=4)
    with tempfile.TemporaryDirectory() as where:
        NotebookClient(nb, timeout=600, kernel_name="python3", resources={"metadata": {"path": where}}).execute()
    for cell in nb.cells:  # outputs only: no timings or kernel ids in the committed file
        cell.get("metadata", {}).pop("execution", None)
    nbformat.write(nb, path)
    print(f"executed {path}")


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else NOTEBOOK)
