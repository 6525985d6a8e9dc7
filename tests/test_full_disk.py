"""A write that the disk refuses (full, or beyond the file-size limit) ends with a message, exit 1
and nothing half-written (docs/reliability.md). HDF5 and VTK fail natively on such a write:
h5py raised a RuntimeError on close and then the process died with a segmentation fault when
the broken file was collected; VTK's XML writer aborted the process (free(): invalid pointer) on
a full disk and wrote a truncated file without an error under a file-size limit. Both now build
the file in memory and Python writes it atomically. The tests set a file-size limit (ulimit -f)
in a child process, which makes writes fail as a full disk does, without a file system of
their own."""

from __future__ import annotations

import errno
import resource
import signal
import subprocess
import sys
import textwrap

import pytest

LIMIT = 60_000  # [B] per file: the small files of a short run fit, its time series does not


def _limited():
    signal.signal(signal.SIGXFSZ, signal.SIG_IGN)  # a write past the limit fails with EFBIG
    resource.setrlimit(resource.RLIMIT_FSIZE, (LIMIT, LIMIT))


def _child(script: str, tmp_path):
    return subprocess.run([sys.executable, "-c", textwrap.dedent(script), str(tmp_path)], capture_output=True,
                          text=True, preexec_fn=_limited, cwd=tmp_path)


def test_a_vtk_file_too_large_to_write_raises_and_leaves_nothing(tmp_path):
    done = _child("""
        import sys
        from pathlib import Path
        import numpy as np, pyvista as pv
        from bearingsim.pipeline.render.vtk_files import save_xml
        mesh = pv.Sphere(theta_resolution=200, phi_resolution=200)
        mesh.point_data["x"] = np.random.default_rng(0).random(mesh.n_points)
        out = Path(sys.argv[1])
        try:
            save_xml(mesh, out / "big.vtp")
        except OSError as exc:
            print("raised", exc.errno, exc.filename == str(out / "big.vtp"))
        print("files", sorted(p.name for p in out.iterdir()))
    """, tmp_path)
    assert done.returncode == 0, done.stderr[-2000:]
    assert f"raised {errno.EFBIG} True" in done.stdout and "files []" in done.stdout, done.stdout


def test_a_vtk_file_that_fits_is_the_file_pyvista_writes(tmp_path):
    import pyvista as pv

    from bearingsim.pipeline.render.vtk_files import save_xml

    mesh = pv.Sphere()
    mesh.field_data["warp_scale"] = [2.5]
    for suffix, data in ((".vtp", mesh), (".vtu", mesh.cast_to_unstructured_grid())):
        data.save(tmp_path / f"pyvista{suffix}")
        save_xml(data, tmp_path / f"ours{suffix}")
        assert (tmp_path / f"ours{suffix}").read_bytes() == (tmp_path / f"pyvista{suffix}").read_bytes()
        assert pv.read(tmp_path / f"ours{suffix}").n_points == mesh.n_points


def test_a_time_series_too_large_to_write_raises_without_a_crash(tmp_path):
    done = _child("""
        import sys
        from pathlib import Path
        import numpy as np
        from bearingsim.pipeline.results.timeseries import Series, write_timeseries
        out = Path(sys.argv[1])
        data = np.random.default_rng(0).random((20_000, 3))  # 480 kB, incompressible
        try:
            write_timeseries(out / "timeseries.h5", {"x": Series(data, "m", "x", ("time", "xyz"))})
        except OSError as exc:
            print("raised", exc.errno)
        import gc; gc.collect()
        print("files", sorted(p.name for p in out.iterdir()))
    """, tmp_path)
    assert done.returncode == 0, (done.returncode, done.stderr[-2000:])  # no segmentation fault
    assert f"raised {errno.EFBIG}" in done.stdout and "files []" in done.stdout, done.stdout


@pytest.mark.filterwarnings("ignore")
def test_simulate_on_a_disk_that_refuses_its_results_exits_1_with_a_message(tmp_path):
    argv = [sys.executable, "-m", "bearingsim", "simulate", "helicopter-b-given-hinge", "--set", "solver.duration=0.002",
            "--set", "output.figures=false"]
    # the kernels first, unlimited: a cold cache's compiled kernels are larger than the limit
    assert subprocess.run([*argv, "--out", str(tmp_path / "warm")], capture_output=True).returncode == 0
    run = tmp_path / "run"
    done = subprocess.run([*argv, "--out", str(run)], capture_output=True, text=True, preexec_fn=_limited)
    assert done.returncode == 1, (done.returncode, done.stderr[-3000:])
    assert "timeseries.h5" in done.stderr and "nothing half-written is kept" in done.stderr.replace("\n", " ")
    assert "Traceback" not in done.stderr and "Logging error" not in done.stderr
    assert not (run / "simulate").exists() and not [p for p in run.iterdir() if p.name.endswith(".tmp")]
    assert (run / "quasistatic" / "stage.json").is_file()  # the finished stage is kept
