"""Check the system libraries the gmsh and VTK wheels load at run time.

The gmsh wheel links X11/OpenGL/fontconfig/OpenMP libraries that a bare Debian/Ubuntu
image lacks, and VTK (pyvista) needs EGL plus Mesa's DRI driver: without them import
fails or, worse, the process segfaults instead of raising. So the stages that mesh or
render call `require_libraries` first, which looks the libraries up without importing
gmsh or vtk, and prints the apt-get line instead of crashing. Imports nothing of the
project.
"""

from __future__ import annotations

import ctypes
import ctypes.util
import glob
import os

# kind -> [(soname, library name for find_library, Debian/Ubuntu package)]
REQUIRED: dict[str, list[tuple[str, str, str]]] = {
    "gmsh": [
        ("libGLU.so.1", "GLU", "libglu1-mesa"),
        ("libGL.so.1", "GL", "libgl1"),
        ("libXrender.so.1", "Xrender", "libxrender1"),
        ("libXcursor.so.1", "Xcursor", "libxcursor1"),
        ("libXfixes.so.3", "Xfixes", "libxfixes3"),
        ("libXext.so.6", "Xext", "libxext6"),
        ("libXft.so.2", "Xft", "libxft2"),
        ("libfontconfig.so.1", "fontconfig", "libfontconfig1"),
        ("libXinerama.so.1", "Xinerama", "libxinerama1"),
        ("libX11.so.6", "X11", "libx11-6"),
        ("libgomp.so.1", "gomp", "libgomp1"),
    ],
    "vtk": [
        ("libEGL.so.1", "EGL", "libegl1"),
        ("mesa-dri-driver", "", "libgl1-mesa-dri"),
    ],
}

DRI_DIRS = (
    "/usr/lib/x86_64-linux-gnu/dri",
    "/usr/lib/aarch64-linux-gnu/dri",
    "/usr/lib64/dri",
    "/usr/lib/dri",
)


def _dri_driver_present() -> bool:
    """Mesa's DRI drivers (swrast/llvmpipe or a GPU one) live as *_dri.so in a dri dir."""
    dirs = list(DRI_DIRS)
    if os.environ.get("LIBGL_DRIVERS_PATH"):
        dirs = os.environ["LIBGL_DRIVERS_PATH"].split(os.pathsep) + dirs
    return any(glob.glob(os.path.join(d, "*_dri.so")) for d in dirs)


def _library_present(soname: str, name: str) -> bool:
    """True if the dynamic loader can find `soname` (ldconfig cache, then dlopen)."""
    if soname == "mesa-dri-driver":
        return _dri_driver_present()
    if name and ctypes.util.find_library(name):
        return True
    try:
        ctypes.CDLL(soname)  # honours LD_LIBRARY_PATH, which find_library may not
    except OSError:
        return False
    return True


def missing_libraries(kind: str) -> list[str]:
    """Sonames needed by `kind` ("gmsh" or "vtk") that this machine cannot load."""
    if kind not in REQUIRED:
        raise ValueError(f"unknown library set {kind!r}: allowed {sorted(REQUIRED)}")
    return [soname for soname, name, _ in REQUIRED[kind] if not _library_present(soname, name)]


def install_command(kind: str, missing: list[str]) -> str:
    """The apt-get line installing the Debian/Ubuntu packages of `missing`."""
    packages = [pkg for soname, _, pkg in REQUIRED[kind] if soname in missing]
    return "apt-get install -y --no-install-recommends " + " ".join(dict.fromkeys(packages))


def require_libraries(kind: str) -> None:
    """Raise RuntimeError with the install line if any library of `kind` is missing."""
    missing = missing_libraries(kind)
    if missing:
        what = {"gmsh": "meshing (gmsh)", "vtk": "rendering (VTK/pyvista)"}[kind]
        raise RuntimeError(
            f"{what} needs system libraries that are not installed: {', '.join(missing)}.\n"
            f"On Debian/Ubuntu install them with:\n    sudo {install_command(kind, missing)}\n"
            "(without them the library would crash the process instead of raising)."
        )
