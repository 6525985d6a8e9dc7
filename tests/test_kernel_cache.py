"""Compiling once per machine (pipeline.kernel_cache): the lock and marker, the configuration
key, and the sweep worker's cache location."""

from __future__ import annotations

import multiprocessing
import os
import time
from pathlib import Path

import pytest

from bearingsim.pipeline import kernel_cache
from bearingsim.pipeline.scene import load_scene


def _compile_in_child(cache: str, log: str, delay: float) -> None:
    """A stand-in compile: appends to `log` and takes `delay` seconds."""
    os.environ["NUMBA_CACHE_DIR"] = cache
    scene = load_scene("helicopter-b-given-hinge")

    def compile_kernels() -> float:
        with open(log, "a") as f:
            f.write(f"{os.getpid()}\n")
        time.sleep(delay)
        return delay

    kernel_cache.ensure_compiled(scene, compile_kernels)


def test_processes_starting_together_compile_once(tmp_path):
    """Three processes on one cold cache: one compiles, the others wait and find the marker."""
    cache, log = tmp_path / "cache", tmp_path / "compiles.log"
    ctx = multiprocessing.get_context("spawn")
    procs = [ctx.Process(target=_compile_in_child, args=(str(cache), str(log), 1.0)) for _ in range(3)]
    for p in procs:
        p.start()
    for p in procs:
        p.join(60)
        assert p.exitcode == 0
    assert len(log.read_text().splitlines()) == 1
    notes = (cache / kernel_cache.LOG_FILE).read_text().splitlines()
    assert len(notes) == 1 and "compiled configuration" in notes[0]


def test_configuration_key_follows_the_physics_not_the_loads():
    base = kernel_cache.kernel_configuration(load_scene("helicopter-b-given-hinge"))
    assert kernel_cache.kernel_configuration(load_scene("helicopter-b-given-hinge", ["load.moment=100"])) == base
    assert kernel_cache.kernel_configuration(load_scene("helicopter-b-given-hinge", ["physics.traction=coulomb"])) != base


def test_a_sweep_worker_uses_the_machines_cache(tmp_path, monkeypatch):
    """A Dask worker process that did not come through the command line (as under an outside
    scheduler) points numba at the per-user cache before running a point."""
    distributed = pytest.importorskip("distributed")
    from bearingsim.pipeline.numba_cache import source_fingerprint
    from bearingsim.pipeline.sweep.point_runner import prepare_worker

    monkeypatch.delenv("NUMBA_CACHE_DIR", raising=False)
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster, distributed.Client(cluster) as client:
        before = client.run(lambda: os.environ.get("NUMBA_CACHE_DIR"))
        assert list(before.values()) == [None]
        found = client.submit(prepare_worker, pure=False).result()
    import bearingsim.dynamics

    expected = tmp_path / "xdg" / "bearingsim" / "numba" / source_fingerprint(
        Path(bearingsim.dynamics.__file__).resolve().parent)
    assert Path(found) == expected


@pytest.mark.slow
def test_two_workers_of_an_outside_scheduler_compile_once(tmp_path):
    """A real `dask scheduler` with two `dask worker` processes on this machine, an empty
    per-user cache and no NUMBA_CACHE_DIR: a two-point sweep compiles the kernels once."""
    import socket
    import subprocess
    import sys

    pytest.importorskip("distributed")
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    env = {k: v for k, v in os.environ.items() if k != "NUMBA_CACHE_DIR"}
    env["XDG_CACHE_HOME"] = str(tmp_path / "xdg")
    dask = str(Path(sys.executable).parent / "dask")
    address = f"tcp://127.0.0.1:{port}"
    procs = [subprocess.Popen([dask, "scheduler", "--host", "127.0.0.1", "--port", str(port),
                               "--dashboard-address", ":0"], env=env, cwd=tmp_path,
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)]
    try:
        time.sleep(3)
        procs += [subprocess.Popen([dask, "worker", address, "--nthreads", "1", "--nworkers", "1",
                                    "--dashboard-address", ":0"], env=env, cwd=tmp_path,
                                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL) for _ in range(2)]
        time.sleep(5)
        exe = str(Path(sys.executable).parent / "bearingsim")
        done = subprocess.run([exe, "sweep", "helicopter-b-given-hinge", "--vary", "load.moment=100,430",
                               "--set", "solver.duration=0.001", "--scheduler", address,
                               "--out", str(tmp_path / "sweep")], env=env, capture_output=True, text=True,
                              timeout=1800)
        assert done.returncode == 0, done.stderr[-3000:]
    finally:
        for p in procs:
            p.terminate()
            p.wait(30)
    logs = list((tmp_path / "xdg" / "bearingsim" / "numba").glob(f"*/{kernel_cache.LOG_FILE}"))
    assert len(logs) == 1
    # one line for the quasi-static kernels, one for the force kernels: each compiled once
    assert len(logs[0].read_text().splitlines()) == 2
