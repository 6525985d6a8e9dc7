"""The VTK/pyvista edge of the renderers: import on demand, off-screen by default.

VTK loads EGL and Mesa's DRI driver at import and segfaults rather than raising when they
are missing, so `pyvista_offscreen` checks them first (`pipeline.machine.system_libraries`).
Every render is drawn off-screen at a fixed window size; an interactive window is opened
only on request and only when a display exists (`DISPLAY` or `WAYLAND_DISPLAY`).
"""

from __future__ import annotations

import io
import os
from pathlib import Path
from typing import Callable

from ..staging.artefacts import atomic_write_bytes

WINDOW_SIZE = (1600, 900)  # px; fixed so that renders of two runs compare pixel for pixel


def display_available() -> bool:
    """True when an interactive window can open (an X11 or Wayland display is set)."""
    return bool(os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY"))


def pyvista_offscreen():
    """Import pyvista for off-screen rendering, after checking VTK's system libraries."""
    from ..machine.system_libraries import require_libraries

    require_libraries("vtk")
    import pyvista
    import vtk

    pyvista.OFF_SCREEN = True
    # Without a display VTK tries X11 first and logs "bad X server connection" before it
    # falls back to EGL; that is expected here, not a fault worth showing the user.
    vtk.vtkLogger.SetStderrVerbosity(vtk.vtkLogger.VERBOSITY_ERROR)
    vtk.vtkObject.GlobalWarningDisplayOff()
    return pyvista


def render_png(path: Path, populate: Callable, shape: tuple[int, int] = (1, 1),
               window_size: tuple[int, int] = WINDOW_SIZE, show: bool = False) -> None:
    """Draw `populate(plotter)` off-screen into the PNG `path` (atomically); with `show`
    and a display, draw it again in an interactive window after the file is written."""
    pv = pyvista_offscreen()
    plotter = pv.Plotter(off_screen=True, shape=shape, window_size=list(window_size))
    try:
        populate(plotter)
        buf = io.BytesIO()
        plotter.screenshot(buf, return_img=False)
    finally:
        plotter.close()
    atomic_write_bytes(Path(path), buf.getvalue())
    if show and display_available():
        window = pv.Plotter(off_screen=False, shape=shape, window_size=list(window_size))
        populate(window)
        window.show(title=Path(path).stem)
