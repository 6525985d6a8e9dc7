"""User-facing studies behind `bearingsim bench` (work-precision of the dynamics, precision
of the identification) and `bearingsim stability` (stiff and extreme cases)."""

from __future__ import annotations


def write_study_files(study, out_dir, stem: str, markdown: str, plot) -> list:
    """`<stem>.json`, `<stem>.md` and `<stem>.png` (drawn by plot(path)) in `out_dir`,
    each written atomically (temporary file + rename)."""
    import json
    from pathlib import Path

    from bearingsim.pipeline.artefacts import atomic_write_text

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
