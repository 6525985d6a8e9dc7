"""Compiling once per machine (pipeline.machine.kernel_cache): the lock and marker, the configuration
key, and the sweep worker's cache location."""

from __future__ import annotations

import multiprocessing
import os
import pickle
import time
from pathlib import Path

import pytest

from bearingsim.pipeline.machine import kernel_cache
from bearingsim.pipeline.scene.load import load_scene


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


def _hold_lock(cache: str, configuration: str, seconds: float) -> None:
    """Holds the compile lock of `configuration` for `seconds` (a long compile)."""
    os.environ["NUMBA_CACHE_DIR"] = cache
    kernel_cache.ensure_compiled(load_scene("helicopter-b-given-hinge"), lambda: time.sleep(seconds), configuration)


def test_one_configurations_compile_does_not_hold_up_anothers(tmp_path, monkeypatch):
    """The quasi-static kernels of one process must not wait for another process's dynamic
    compile (`compile_ahead` runs both at once): each configuration has its own lock."""
    cache = tmp_path / "cache"
    ctx = multiprocessing.get_context("spawn")
    holder = ctx.Process(target=_hold_lock, args=(str(cache), None, 30.0))
    holder.start()
    try:
        for _ in range(200):  # until the holder has its lock
            if list(cache.glob(".bearingsim-compile-*.lock")):
                break
            time.sleep(0.05)
        monkeypatch.setenv("NUMBA_CACHE_DIR", str(cache))
        kernel_cache.ensure_compiled(load_scene("helicopter-b-given-hinge"), lambda: None, "quasistatic")
        assert holder.is_alive()  # had it waited for the holder's lock, the holder would be done
    finally:
        holder.terminate()
        holder.join()


def test_compile_ahead_starts_only_for_a_dynamic_run_on_a_cold_cache_and_several_cores(tmp_path, monkeypatch):
    from bearingsim.pipeline.cli import compile_ahead
    from bearingsim.pipeline.machine import cores

    started = []
    monkeypatch.setattr(compile_ahead.subprocess, "Popen", lambda *a, **k: started.append(a) or _FakeChild())
    scene = load_scene("helicopter-b-given-hinge")
    cache = tmp_path / "cache"
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(cache))
    monkeypatch.setattr(cores, "usable_cores", lambda: 2)
    assert compile_ahead.start(scene, ["quasistatic"]) is None  # no dynamic run
    monkeypatch.setattr(cores, "usable_cores", lambda: 1)
    assert compile_ahead.start(scene, ["quasistatic", "simulate"]) is None  # one core: nothing to overlap
    monkeypatch.setattr(cores, "usable_cores", lambda: 2)
    child = compile_ahead.start(scene, ["quasistatic", "simulate"])
    assert isinstance(child, _FakeChild) and len(started) == 1
    assert pickle.loads(bytes(child.stdin.data)) == scene  # the child compiles for this very scene
    cache.mkdir()
    kernel_cache.compiled_marker(cache, kernel_cache.kernel_configuration(scene)).touch()
    assert compile_ahead.start(scene, ["quasistatic", "simulate"]) is None  # compiled already
    monkeypatch.delenv("NUMBA_CACHE_DIR")
    assert compile_ahead.start(scene, ["quasistatic", "simulate"]) is None  # numba's own cache: no lock to share


class _FakeStdin:
    def __init__(self):
        self.data = bytearray()

    def write(self, b):
        self.data += b

    def close(self):
        pass


class _FakeChild:
    def __init__(self):
        self.stdin = _FakeStdin()
        self.pid = 0


def test_configuration_key_follows_the_physics_not_the_loads():
    base = kernel_cache.kernel_configuration(load_scene("helicopter-b-given-hinge"))
    assert kernel_cache.kernel_configuration(load_scene("helicopter-b-given-hinge", ["load.moment=100"])) == base
    assert kernel_cache.kernel_configuration(load_scene("helicopter-b-given-hinge", ["physics.traction=coulomb"])) != base


def test_a_sweep_worker_uses_the_machines_cache(tmp_path, monkeypatch):
    """A Dask worker process that did not come through the command line (as under an outside
    scheduler) points numba at the per-user cache before running a point."""
    distributed = pytest.importorskip("distributed")
    from bearingsim.pipeline.machine.numba_cache import source_fingerprint
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
    # one line a compiled configuration (the quasi-static kernels, the tangent kernel, the force
    # kernel and time loop, the rest of the dynamic run's): each compiled once, by one of the workers
    import re

    compiled = [re.search(r"compiled configuration (\S+) ", line).group(1) for line in logs[0].read_text().splitlines()]
    assert sorted(compiled) == sorted(set(compiled)) and len(compiled) == 4, compiled


@pytest.mark.slow
def test_a_cold_run_compiles_its_dynamic_kernels_ahead_in_one_child(tmp_path):
    """`bearingsim run` on an empty cache: the force kernel and the time loop are compiled once,
    by the child `compile_ahead` started (its pid in run.log), the tangent kernel once by the run
    itself, which then loads what the child compiled."""
    import re
    import subprocess
    import sys

    if len(os.sched_getaffinity(0)) < 2:
        pytest.skip("one core: nothing is compiled ahead")
    env = {k: v for k, v in os.environ.items() if k != "NUMBA_CACHE_DIR"}
    cache = tmp_path / "numba"
    env["NUMBA_CACHE_DIR"] = str(cache)
    exe = str(Path(sys.executable).parent / "bearingsim")
    subprocess.run([exe, "run", "helicopter-b-given-hinge", "--out", str(tmp_path / "run"), "--set",
                    "solver.duration=1e-3", "--set", "output.sample_interval=5e-5"], env=env, cwd=tmp_path,
                   check=True, capture_output=True)
    child = re.search(r"kernels in process (\d+)", (tmp_path / "run" / "run.log").read_text())
    assert child, "no compile-ahead child in run.log"
    notes = (cache / kernel_cache.LOG_FILE).read_text().splitlines()
    force = [line for line in notes if "-force " in line]
    assert len(force) == 1 and f"pid {child.group(1)} " in force[0], notes
    tangent = [line for line in notes if "-tangent " in line]
    assert len(tangent) == 1 and f"pid {child.group(1)} " not in tangent[0], notes
    rest = [line for line in notes if not any(part in line for part in ("-force ", "-tangent ", "quasistatic"))]
    assert len(rest) == 1 and f"pid {child.group(1)} " not in rest[0], notes


def test_the_time_loop_compiled_alone_is_the_one_a_run_calls():
    """`compile_time_loop` compiles the loop for the argument types of a real run without
    compiling the force kernel: the run that follows must find that overload and compile no
    other (a second overload would be a second compile on a cold cache)."""
    from bearingsim.dynamics.bearing.run import compile_time_loop, simulate_bearing
    from bearingsim.dynamics.multibody.compiled import hht_chunk
    from bearingsim.dynamics.multibody.settings import HHTSettings
    from tests.bearing_fixtures import reference_model

    params, start = reference_model()
    settings = HHTSettings()
    compile_time_loop(params, settings)
    signatures = set(hht_chunk.overloads)
    assert len(signatures) >= 1
    simulate_bearing(params, start, settings, 4 * settings.first_step, 1e-5)
    assert set(hht_chunk.overloads) == signatures


_SAME_BITS_RUN = """
import hashlib, json
import numpy as np
from bearingsim.dynamics.bearing import simulate_bearing
from bearingsim.pipeline.scene.load import load_scene
from bearingsim.pipeline.stages.simulate import build_model

scene = load_scene("helicopter-b-given-hinge")
params, start = build_model(scene)
run = simulate_bearing(params, start, scene.solver, 0.05, 1e-5)
channels = run.channels()
digest = hashlib.sha256(np.ascontiguousarray(run.q).tobytes())
for name in sorted(channels):
    digest.update(np.ascontiguousarray(channels[name].data).tobytes())
print(json.dumps({"steps": run.stats["steps"], "newton": run.stats["newton_iterations"],
                  "factorizations": run.stats["factorizations"], "hash": digest.hexdigest()}))
"""


@pytest.mark.slow
def test_a_run_that_compiled_its_kernels_repeats_bit_for_bit_from_the_cache(tmp_path):
    """The first run on a machine compiles every kernel; later runs load them. Both must run the
    same code: the same steps and the same bits in every channel over 50 ms of case b (a
    multiply-add fused differently in the two parts them after ≈ 15 ms; docs/performance.md,
    *Compiled and cached kernels run the same bits*)."""
    import json
    import subprocess
    import sys

    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path / "numba"))
    runs = [json.loads(subprocess.run([sys.executable, "-c", _SAME_BITS_RUN], env=env, cwd=tmp_path, check=True,
                                      capture_output=True, text=True).stdout.splitlines()[-1]) for _ in range(2)]
    assert (tmp_path / "numba").is_dir()
    assert runs[0] == runs[1]
