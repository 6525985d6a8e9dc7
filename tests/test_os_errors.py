"""Every OSError names what failed (docs/reliability.md): an address-space limit is memory, not
the run folder; a full disk names the device's file; a path outside the run directory is said
to be outside; the dynamic run's memory check reads the process's limit (ulimit -v), not only
the machine's memory."""

from __future__ import annotations

import errno
import subprocess
import sys
import textwrap

from bearingsim.pipeline.cli.os_errors import describe_os_error


def test_out_of_memory_is_not_blamed_on_the_run_folder(tmp_path):
    text = describe_os_error(OSError(errno.ENOMEM, "Cannot allocate memory"), tmp_path)
    assert text.startswith("out of memory (Cannot allocate memory")
    assert "ulimit -v" in text and "solver.duration" in text
    assert "permission" not in text and "space of" not in text and "run" not in text


def test_a_full_disk_names_the_file_and_says_nothing_half_written_is_kept(tmp_path):
    text = describe_os_error(OSError(errno.ENOSPC, "No space left on device", str(tmp_path / "simulate" / "x.h5")),
                             tmp_path)
    assert f"no space left on the device of {tmp_path / 'simulate' / 'x.h5'}" in text
    assert "--out on another file system" in text and "outside" not in text


def test_a_failure_outside_the_run_directory_says_so(tmp_path):
    cache = tmp_path / "cache" / "bearingsim" / "numba"
    text = describe_os_error(NotADirectoryError(errno.ENOTDIR, "Not a directory", str(cache)), tmp_path / "run")
    assert str(cache) in text and f"outside the run directory {tmp_path / 'run'}/" in text
    denied = describe_os_error(PermissionError(errno.EACCES, "Permission denied", "/etc/x"), tmp_path)
    assert denied.startswith("/etc/x: Permission denied (outside the run directory")


def test_the_memory_check_reads_the_address_space_limit():
    """A run of about 0.5 GB of samples, which half the machine's memory allows, is refused before
    it starts under an address-space limit (ulimit -v) that leaves 0.2 GB, naming
    output.sample_interval and the limit."""
    script = textwrap.dedent("""
        import resource
        from bearingsim.pipeline.scene.load import load_scene
        from bearingsim.pipeline.scene.schema import SceneError
        from bearingsim.pipeline.scene.validity import memory_limit
        overrides = ["solver.duration=0.01", "output.sample_interval=4.3e-7"]
        load_scene("helicopter-b-given-hinge", overrides)  # allowed by the machine's memory
        with open("/proc/self/status") as fh:
            mapped = next(int(l.split()[1]) * 1024 for l in fh if l.startswith("VmSize:"))
        resource.setrlimit(resource.RLIMIT_AS, (mapped + 200 * 2**20, resource.RLIM_INFINITY))
        print("left", memory_limit() <= 200 * 2**20)
        try:
            load_scene("helicopter-b-given-hinge", overrides)
            print("accepted")
        except SceneError as exc:
            print("refused", exc.key, "ulimit -v" in str(exc))
    """)
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr[-2000:]
    assert "left True" in done.stdout and "refused output.sample_interval True" in done.stdout, done.stdout
