"""System-library check for the gmsh and VTK wheels (monkeypatched finder)."""

import pytest

from bearingsim.pipeline.machine import system_libraries as sl


def test_nothing_missing_when_every_library_is_found(monkeypatch):
    monkeypatch.setattr(sl, "_library_present", lambda soname, name: True)
    assert sl.missing_libraries("gmsh") == []
    assert sl.missing_libraries("vtk") == []
    sl.require_libraries("gmsh")  # does not raise


def test_missing_gmsh_libraries_give_the_apt_line(monkeypatch):
    absent = {"libGLU.so.1", "libXft.so.2"}
    monkeypatch.setattr(sl, "_library_present", lambda soname, name: soname not in absent)
    assert set(sl.missing_libraries("gmsh")) == absent
    with pytest.raises(RuntimeError) as err:
        sl.require_libraries("gmsh")
    message = str(err.value)
    assert "apt-get install" in message and "libglu1-mesa" in message and "libxft2" in message
    assert "libx11-6" not in message  # only what is missing


def test_missing_vtk_driver_names_mesa_dri(monkeypatch):
    monkeypatch.setattr(sl, "_library_present", lambda soname, name: soname != "mesa-dri-driver")
    with pytest.raises(RuntimeError, match="libgl1-mesa-dri"):
        sl.require_libraries("vtk")


def test_dri_driver_search_honours_libgl_drivers_path(monkeypatch, tmp_path):
    monkeypatch.setattr(sl, "DRI_DIRS", ())
    monkeypatch.setenv("LIBGL_DRIVERS_PATH", str(tmp_path))
    assert not sl._dri_driver_present()
    (tmp_path / "swrast_dri.so").write_bytes(b"")
    assert sl._dri_driver_present()


def test_the_brief_library_list_is_complete():
    sonames = {s for s, _, _ in sl.REQUIRED["gmsh"]}
    assert {"libGLU.so.1", "libGL.so.1", "libXrender.so.1", "libXcursor.so.1", "libXfixes.so.3",
            "libXext.so.6", "libXft.so.2", "libfontconfig.so.1", "libXinerama.so.1",
            "libX11.so.6", "libgomp.so.1"} == sonames


def test_unknown_kind_is_an_error():
    with pytest.raises(ValueError, match="unknown library set"):
        sl.missing_libraries("paraview")
