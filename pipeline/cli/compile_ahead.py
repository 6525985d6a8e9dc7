"""Compile a scene's dynamic-run kernels in a second process while this one runs the stages
before the dynamic run.

On a machine whose cache lacks the scene's kernels, the dynamic run waits minutes for numba
to compile them, yet they depend on no result of the stages before it (identify, the
quasi-static solution): only on the scene's kernel configuration (`kernel_cache`). So the
command line starts a child process that compiles the force kernel (without its tangent kernel)
and the time loop on another core, under their own lock; they need no quasi-static solution. This
process compiles the quasi-static kernels in their stage and the tangent kernel at the start of
the dynamic run, then waits on the child's lock for what it has not finished: the two halves take
about as long. On one core, or with the kernels cached, nothing is started.
"""

from __future__ import annotations

import logging
import pickle
import subprocess
import sys

log = logging.getLogger("bearingsim")


def start(scene, stage_names: list[str]) -> subprocess.Popen | None:
    """Start the child for `scene` when `stage_names` (the stages this command will run,
    dependencies included) contain the dynamic run, numba's cache is configured and lacks the
    scene's kernels, and this process may use more than one core. Returns the child, or None."""
    from ..machine.cores import usable_cores
    from ..machine.kernel_cache import cache_directory, compiled_marker, force_configuration, kernel_configuration

    cache = cache_directory()
    if "simulate" not in stage_names or cache is None or usable_cores() < 2:
        return None
    if any(compiled_marker(cache, key).exists() for key in (kernel_configuration(scene), force_configuration(scene))):
        return None
    try:
        child = subprocess.Popen([sys.executable, "-m", "bearingsim.pipeline.cli.compile_ahead"], stdin=subprocess.PIPE,
                                 stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        child.stdin.write(pickle.dumps(scene))
        child.stdin.close()
    except (OSError, pickle.PicklingError) as exc:
        log.info("kernels not compiled ahead (%s): the dynamic run compiles them", exc)
        return None
    log.info("compiling the dynamic run's kernels in process %d while the stages before it run", child.pid)
    return child


def stop(child: subprocess.Popen | None) -> None:
    """End the child if it still runs (the command is over, or failed before its dynamic run):
    an interrupted compile leaves no marker, and the lock is released with the process."""
    if child is None or child.poll() is not None:
        return
    child.terminate()
    try:
        child.wait(timeout=10)
    except subprocess.TimeoutExpired:
        child.kill()
        child.wait()


def _main() -> None:
    from ..machine.kernel_cache import ensure_compiled, force_configuration
    from .warmup import compile_force_and_loop

    scene = pickle.loads(sys.stdin.buffer.read())
    ensure_compiled(scene, lambda: compile_force_and_loop(scene), force_configuration(scene))


if __name__ == "__main__":
    _main()
