"""Benchmark scripts (`python -m pipeline.bench.<name>`): measurements, not tests."""

from __future__ import annotations

import time


def best_time(fn, repeat: int = 5, number: int = 20) -> float:
    """Best mean time of `number` calls over `repeat` runs [s]: the machine may be shared,
    and other work only ever makes a run slower, so the quietest run is the measurement."""
    best = float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter()
        for _ in range(number):
            fn()
        best = min(best, (time.perf_counter() - t0) / number)
    return best


def write_study_files(study, out_dir, stem: str, markdown: str, plot) -> list:
    """`<stem>.json`, `<stem>.md` and `<stem>.png` (drawn by plot(path)) in `out_dir`,
    each written atomically (temporary file + rename)."""
    import json
    from pathlib import Path

    from pipeline.artefacts import atomic_write_text

    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    js, md = out / f"{stem}.json", out / f"{stem}.md"
    atomic_write_text(js, json.dumps(study, indent=1, default=_json_default))
    atomic_write_text(md, markdown + "\n")
    return [js, md, plot(out / f"{stem}.png")]


def _json_default(obj):
    if hasattr(obj, "tolist"):  # numpy arrays and scalars
        return obj.tolist()
    return str(obj)
