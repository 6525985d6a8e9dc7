"""User-facing studies behind `bearingsim bench` (work-precision of the dynamics, precision
of the identification) and `bearingsim stability` (stiff and extreme cases)."""

from __future__ import annotations


STUDY_MARKER = ".bearingsim-study"
STUDY_STEMS = ("stability", "work_precision", "identification_precision")


def _study_file_names() -> set[str]:
    return {f"{stem}.{ext}" for stem in STUDY_STEMS for ext in ("json", "md", "png")}


def claim_study_directory(out_dir) -> None:
    """Make sure `out_dir` may take a study's files (new, empty, or a study folder bearingsim
    wrote) and mark it; anything else raises OutputRefused before a study runs, so that a
    file of the user's named stability.md, say, is never replaced."""
    from pathlib import Path

    from ..staging.artefacts import OutputRefused, mark_directory, refused_unless_usable
    from ..staging.no_follow import out_name

    out = Path(out_dir)
    with refused_unless_usable(out):
        if out.is_symlink() or (out.exists() and not out.is_dir()):
            raise OutputRefused(f"{out_name(out)}: exists and is not a directory; give a new or empty "
                                f"directory, e.g. {out_name(out.with_name(out.name + '-study'))}")
        out.mkdir(parents=True, exist_ok=True)
        # a folder without the marker is the user's, even when its names are a study's: an
        # earlier version wrote no marker, but a stability.md of the user's looks the same
        entries = [p.name for p in out.iterdir()]
        if entries and not (out / STUDY_MARKER).is_file():
            earlier = (" If they are the tables of an earlier bearingsim version, delete them first."
                       if set(entries) <= _study_file_names() else "")
            raise OutputRefused(
                f"{out_name(out)}: the directory holds files that are not bearingsim's studies (no "
                f"{STUDY_MARKER} marker); bearingsim never writes into a folder of yours, so that none "
                f"of your files is replaced. Give a new or empty directory, e.g. {out_name(out / 'study')}."
                + earlier)
        mark_directory(out, STUDY_MARKER, "bearingsim study folder: its tables and plots are replaced by bearingsim")


def write_study_files(study, out_dir, stem: str, markdown: str, plot) -> list:
    """`<stem>.json`, `<stem>.md` and `<stem>.png` (drawn by plot(path)) in `out_dir`,
    each written atomically (temporary file + rename), in a folder `claim_study_directory`
    accepts."""
    import json
    from pathlib import Path

    from ..staging.artefacts import atomic_write_text

    out = Path(out_dir)
    claim_study_directory(out)
    js, md = out / f"{stem}.json", out / f"{stem}.md"
    atomic_write_text(js, json.dumps(study, indent=1, default=_json_default))
    atomic_write_text(md, markdown + "\n")
    return [js, md, plot(out / f"{stem}.png")]


def _json_default(obj):
    if hasattr(obj, "tolist"):  # numpy arrays and scalars
        return obj.tolist()
    return str(obj)
