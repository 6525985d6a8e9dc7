"""Compile the force kernels once per machine, however many processes start at once.

numba writes compiled kernels to the cache directory of `pipeline.machine.numba_cache` (one per
version of the dynamics sources). Two processes that start on a cold cache would each compile
the same kernels (minutes of CPU each): the sweep's workers, parallel test processes, a user
running two scenes at once. So the first process of a kernel configuration takes an exclusive
file lock of that configuration in the cache directory, compiles by running the first two steps
of its model, and leaves a marker; the others wait on the lock and then load what it compiled. A
process that finds the marker takes no lock at all. Each configuration has its own lock, so that
the quasi-static kernels of one process are not held up by another's dynamic compile
(`compile_ahead`).

The kernel configuration is what selects compiled specialisations: the `[physics]` options and
whether the scene has a cage, a lubricant and a hinge. Loads, dimensions and solver tolerances
are run-time values and share the kernels.
"""

from __future__ import annotations

import dataclasses
import hashlib
import json
import logging
import os
import time
from pathlib import Path

from .file_lock import exclusive_lock

log = logging.getLogger("bearingsim")
LOG_FILE = "bearingsim-compile.log"


def kernel_configuration(scene) -> str:
    """A short key of what selects the compiled specialisations of a scene's dynamic run."""
    what = {"physics": dataclasses.asdict(scene.physics), "cage": scene.cage is not None,
            "lubricant": scene.lubricant is not None, "hinge": scene.hinge.source != "none"}
    return hashlib.sha256(json.dumps(what, sort_keys=True).encode()).hexdigest()[:12]


def force_configuration(scene) -> str:
    """The configuration key of the scene's force kernel and time loop, which a `compile_ahead`
    child compiles while this process runs the stages before the dynamic run."""
    return kernel_configuration(scene) + "-force"


def tangent_configuration(scene) -> str:
    """The configuration key of the scene's tangent kernel, which this process compiles at the
    start of the dynamic run while a `compile_ahead` child may still compile the force kernel."""
    return kernel_configuration(scene) + "-tangent"


def cache_directory() -> Path | None:
    """numba's cache directory of this process (None: numba's default, next to the sources)."""
    value = os.environ.get("NUMBA_CACHE_DIR")
    return Path(value) if value else None


def compiled_marker(cache: Path, configuration: str) -> Path:
    """The file that says `cache` holds the kernels of `configuration` (a key of
    `kernel_configuration`, `force_configuration`, `tangent_configuration`, or "quasistatic")."""
    return cache / f".compiled-{configuration}"


def ensure_compiled(scene, compile_kernels, configuration: str | None = None) -> float:
    """Call `compile_kernels()` (which compiles or loads the scene's kernels) under the cache's
    lock unless another process already did it for this configuration (default: the scene's
    dynamic-run configuration; "quasistatic" for the quasi-static solver's kernels, which the
    physics options do not select); returns the seconds spent here (waiting included), 0 when
    the marker was there."""
    t0 = time.perf_counter()
    cache = cache_directory()
    if cache is None:
        compile_kernels()
        return time.perf_counter() - t0
    key = configuration or kernel_configuration(scene)
    marker = compiled_marker(cache, key)
    if marker.exists():
        return 0.0
    cache.mkdir(parents=True, exist_ok=True)
    with exclusive_lock(cache / f".bearingsim-compile-{key}.lock"):
        if not marker.exists():
            t1 = time.perf_counter()
            compile_kernels()
            marker.touch()
            _note(cache, f"{time.strftime('%Y-%m-%dT%H:%M:%S')} pid {os.getpid()} compiled configuration {key} "
                         f"of scene {scene.name} in {time.perf_counter() - t1:.1f} s")
    return time.perf_counter() - t0


def _note(cache: Path, line: str) -> None:
    """One line a compile in the cache's own log (read by tests and by people asking why a
    first run was slow)."""
    try:
        with open(cache / LOG_FILE, "a", encoding="utf-8") as f:
            f.write(line + "\n")
    except OSError as exc:
        log.warning("could not note the compile in %s: %s", cache / LOG_FILE, exc)
