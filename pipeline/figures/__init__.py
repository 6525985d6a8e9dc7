"""Figures (matplotlib, Agg) written as PNG files atomically.

pyplot is never imported: a plain `Figure` with an Agg canvas is ~0.2–0.7 s cheaper to
import, which the quick commands (`quasistatic`) feel.
"""

from __future__ import annotations

import io
from pathlib import Path


def new_figure(**kwargs):
    """A matplotlib Figure with an Agg canvas (kwargs as for Figure, e.g. figsize)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    kwargs.setdefault("layout", "constrained")
    fig = Figure(**kwargs)
    FigureCanvasAgg(fig)
    return fig


def save_png(fig, path: Path, dpi: int = 110) -> None:
    from ..staging.artefacts import atomic_write_bytes

    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=dpi)
    atomic_write_bytes(Path(path), buf.getvalue())
