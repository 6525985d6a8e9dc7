"""First-run cost of the numba kernels (docs/performance.md).

    python -m benchmarks.cold_start [SCENE]

Runs a 1 ms `simulate` of the scene twice in this process's children: once with an empty numba
cache (a fresh machine, or the first run after the dynamics code changed) and once with the cache
that run filled, and reports the difference. Then, in-process with an empty cache, it splits the
simulate stage's compiling into the time spent inside LLVM (numba's `numba:llvm_lock` events: every
call into the LLVM library holds that lock) and the rest, numba's typing and lowering in Python,
counts the variables numba typed and the calls it resolved (by wrapping numba's type-inference
pass for that run), by module and how many of them are in fast-math code (whose rounding follows
the shape of the code, so that rewriting it changes a run's steps), and lists the kernels that
take longest to compile (`numba:compile` events, outermost dispatchers only, nested
compilations counted inside their caller). Run it on a quiet machine.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path


CLI = "from bearingsim.pipeline.cli.commands import main; main()"


def timed_run(scene: str, cache: Path, out: Path, program: str = CLI) -> float:
    env = dict(os.environ, NUMBA_CACHE_DIR=str(cache))
    t0 = time.perf_counter()
    subprocess.run([sys.executable, "-c", program, "simulate", scene, "--out", str(out),
                    "--force", "--set", "solver.duration=1e-3"], env=env, check=True, capture_output=True)
    return time.perf_counter() - t0


def compile_profile(scene: str, cache: Path, top: int = 12) -> tuple[float, float, dict, list[tuple[str, float]]]:
    """(seconds compiling, of them inside LLVM, {"compilations", "variables", "calls", "by_module"}
    typed, [(kernel, seconds)] of the outermost compilations) of a 1 ms run with an empty cache;
    "by_module" maps a module to [compilations, variables, variables in fast-math code]."""
    os.environ["NUMBA_CACHE_DIR"] = str(cache)
    from numba.core import event, typed_passes

    from benchmarks.numba_events import Outermost

    from bearingsim.dynamics.bearing.run import simulate_bearing
    from bearingsim.pipeline.scene.load import load_scene
    from bearingsim.pipeline.stages.simulate import build_model

    stack: list[list] = []
    totals: dict[str, float] = {}

    class Kernels(event.Listener):
        def on_start(self, ev):
            stack.append([ev.data["dispatcher"].py_func.__qualname__, time.perf_counter()])

        def on_end(self, ev):
            name, t0 = stack.pop()
            if not stack:
                totals[name] = totals.get(name, 0.0) + time.perf_counter() - t0

    typed: dict = {"compilations": 0, "variables": 0, "calls": 0, "by_module": {}}
    infer = typed_passes.BaseTypeInference.run_pass

    def counting_inference(self, state):
        changed = infer(self, state)
        typed["compilations"] += 1
        typed["variables"] += len(state.typemap)
        typed["calls"] += len(state.calltypes)
        row = typed["by_module"].setdefault(state.func_id.modname, [0, 0, 0])
        row[0] += 1
        row[1] += len(state.typemap)
        row[2] += len(state.typemap) if state.flags.fastmath else 0
        return changed

    compiling, llvm = Outermost(), Outermost()
    scene_obj = load_scene(scene, ["solver.duration=1e-3"])
    typed_passes.BaseTypeInference.run_pass = counting_inference
    try:
        with event.install_listener("numba:compile", Kernels()), event.install_listener("numba:compile", compiling), \
                event.install_listener("numba:llvm_lock", llvm):
            params, start = build_model(scene_obj, None)
            simulate_bearing(params, start, scene_obj.solver, 1e-3, 1e-5)
    finally:
        typed_passes.BaseTypeInference.run_pass = infer
    return compiling.seconds, llvm.seconds, typed, sorted(totals.items(), key=lambda kv: -kv[1])[:top]


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("scene", nargs="?", default="helicopter-b-given-hinge")
    args = ap.parse_args(argv)
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        cold = timed_run(args.scene, tmp / "cache", tmp / "cold")
        warm = timed_run(args.scene, tmp / "cache", tmp / "warm")
        print(f"{args.scene}, 1 ms simulate: cold cache {cold:.1f} s, warm cache {warm:.1f} s: "
              f"compiling costs {cold - warm:.1f} s once (load average {os.getloadavg()[0]:.2f})")
        compiling, llvm, typed, rows = compile_profile(args.scene, tmp / "cache2")
    print(f"in-process, simulate stage only: {compiling:.1f} s compiling, of which {llvm:.1f} s inside LLVM and "
          f"{compiling - llvm:.1f} s numba's typing and lowering in Python; {typed['compilations']} compilations "
          f"typed {typed['variables']} variables and resolved {typed['calls']} calls")
    by_module = sorted(typed["by_module"].items(), key=lambda kv: -kv[1][1])
    fast = sum(row[2] for _, row in by_module)
    print(f"typed variables by module ({fast} of them, {fast / typed['variables']:.0%}, in fast-math code):")
    for module, (count, variables, in_fast) in by_module[:12]:
        print(f"  {variables:6d} in {count:3d} compilations, {in_fast:5d} fast-math  {module}")
    print("longest compilations (outermost kernels):")
    for name, seconds in rows:
        print(f"  {seconds:6.1f} s  {name}")


if __name__ == "__main__":
    main()
