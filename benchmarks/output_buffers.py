"""First write to the step-end records of a full run: `np.zeros` against `buffers.zeroed`.

    python -m benchmarks.output_buffers [--rounds N] [--mb SIZE]
    taskset -c 1 python -m benchmarks.output_buffers

The compiled time loop writes its step-end records (t, q, v and the diagnostics) row by row:
for 0.8 s of helicopter-b at the scene's 1e-5 s that is 80 000 rows of 634 float64, ≈ 400 MB
(the default SIZE). Each round allocates that much in a fresh Python process — the cost
depends on the state of the kernel's free memory, which a process that has already allocated
and freed the same size no longer sees — and times allocation plus one pass of writes, once
with numpy's zeros (which advises huge pages for arrays >= 4 MB) and once with
`bearingsim.dynamics.multibody.buffers.zeroed` (ordinary pages), the two alternated. It also
prints the kernel's THP settings, which decide whether the difference exists at all.
"""

from __future__ import annotations

import argparse
import statistics
import subprocess
import sys
from pathlib import Path

CHILD = """
import sys, time
import numpy as np
from bearingsim.dynamics.multibody.buffers import zeroed
rows = int(sys.argv[2]); cols = 634
make = np.zeros if sys.argv[1] == "numpy" else zeroed
t = time.perf_counter()
a = make((rows, cols))
for i in range(0, rows, 256):  # a block of rows at a time, as the loop fills them in order
    a[i:i + 256] = 1.0
print(time.perf_counter() - t)
"""


def _thp() -> str:
    base = Path("/sys/kernel/mm/transparent_hugepage")
    try:
        return ", ".join(f"{name} = {(base / name).read_text().strip()}" for name in ("enabled", "defrag"))
    except OSError:
        return "no transparent huge pages (not Linux, or not exposed)"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--mb", type=float, default=406.0, help="size of the records [MB]")
    args = ap.parse_args()
    rows = int(args.mb * 1e6 / (634 * 8))
    print(f"THP: {_thp()}")
    print(f"{rows} rows x 634 float64 = {rows * 634 * 8 / 1e6:.0f} MB, allocate + first write, "
          f"fresh process each, {args.rounds} rounds alternated")
    times = {"numpy": [], "zeroed": []}
    for r in range(args.rounds):
        order = ("numpy", "zeroed") if r % 2 == 0 else ("zeroed", "numpy")
        for kind in order:
            out = subprocess.run([sys.executable, "-c", CHILD, kind, str(rows)], capture_output=True, text=True,
                                 check=True)
            times[kind].append(float(out.stdout))
    for kind, ts in times.items():
        print(f"  {kind:7s} median {statistics.median(ts):.3f} s   ({', '.join(f'{t:.3f}' for t in ts)})")


if __name__ == "__main__":
    main()
