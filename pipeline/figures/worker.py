"""Draw a figure in a second process, started before the numbers it plots exist.

Importing matplotlib costs about as much as loading the quasi-static solver's numba
kernels; the two are independent, so `bearingsim quasistatic` calls `prestart()` before it
loads the scene (the worker imports matplotlib on the second core while the solver loads
and runs) and the stage's `draw(...)` hands the result to that worker. Without a prestarted
worker (`run`, sweeps, tests) `draw` plots in this process: a worker per call would only add
a process start. One job per worker: a JSON object {"figure", "data", "path", "options"} on
stdin; exit status 0 when the PNG is written (atomically, see figures.save_png). If the
worker fails, `draw` logs why and plots in this process instead.
"""

from __future__ import annotations

import atexit
import json
import logging
import subprocess
import sys
from pathlib import Path


def _figures() -> dict:
    from .quasistatic import plot_load_distribution
    from .tolerances import plot_crush_probability

    return {"load_distribution": plot_load_distribution, "crush_probability": plot_crush_probability}


class FigureWorkerError(RuntimeError):
    pass


class FigureWorker:
    """A prewarmed plotting process; a context manager that never leaves it running."""

    def __init__(self) -> None:
        self._proc = subprocess.Popen(
            [sys.executable, "-m", "bearingsim.pipeline.figures.worker"], stdin=subprocess.PIPE,
            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)

    def draw(self, figure: str, data: dict, path: Path, timeout: float = 120.0, **options) -> None:
        job = json.dumps({"figure": figure, "data": data, "path": str(Path(path).resolve()), "options": options})
        try:
            _, err = self._proc.communicate(job.encode(), timeout=timeout)
        except subprocess.TimeoutExpired:
            self._proc.kill()
            raise FigureWorkerError(f"figure worker drawing {figure!r} took over {timeout:.0f} s; killed") from None
        if self._proc.returncode != 0:
            raise FigureWorkerError(f"figure worker failed drawing {figure!r} into {path} "
                                    f"(exit {self._proc.returncode}): {err.decode(errors='replace').strip()[-2000:]}")

    def alive(self) -> bool:
        return self._proc.poll() is None

    def close(self) -> None:
        """Stop the process if it never got a job, and release its pipes."""
        if self._proc.poll() is None:
            self._proc.kill()
            self._proc.wait()
        for stream in (self._proc.stdin, self._proc.stderr):
            if stream is not None:
                stream.close()

    def __enter__(self) -> "FigureWorker":
        return self

    def __exit__(self, *exc) -> None:
        self.close()


_prestarted: FigureWorker | None = None


def prestart() -> None:
    """Start a worker now for a figure this process draws later (released at exit if unused)."""
    global _prestarted
    if _prestarted is None:
        _prestarted = FigureWorker()
        atexit.register(_release_prestarted)


def draw(figure: str, data: dict, path: Path, **options) -> None:
    """Draw `figure` (a key of `_figures`) into `path`: in the prestarted worker if there is
    a live one, else (or if it fails, logged) in this process."""
    global _prestarted
    worker, _prestarted = _prestarted, None
    if worker is not None and worker.alive():
        try:
            worker.draw(figure, data, path, **options)
            return
        except FigureWorkerError as exc:
            logging.getLogger("bearingsim").warning("%s; drawing in this process", exc)
        finally:
            worker.close()
    _figures()[figure](data, Path(path), **options)


def _release_prestarted() -> None:
    global _prestarted
    if _prestarted is not None:
        _prestarted.close()
        _prestarted = None


def main() -> int:
    import matplotlib.backends.backend_agg  # noqa: F401  (the warm-up, while the parent computes)
    import matplotlib.figure  # noqa: F401

    figures = _figures()
    raw = sys.stdin.read()
    if not raw.strip():
        return 0  # released without a job
    job = json.loads(raw)
    figures[job["figure"]](job["data"], Path(job["path"]), **job.get("options", {}))
    return 0


if __name__ == "__main__":
    sys.exit(main())
