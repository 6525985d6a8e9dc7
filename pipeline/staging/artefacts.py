"""Artefacts: atomic writes, input hashing, the per-stage cache manifest, run-directory ownership.

A stage writes into a fresh temporary directory next to its final one and the directory
is swapped in only when the stage finished: a crash or Ctrl-C never leaves a
half-written stage that a later run could mistake for a cached result. The manifest
(`stage.json`) records the size and sha256 of every file the stage wrote, so a damaged
or edited result is recomputed instead of served from the cache.

bearingsim writes only into directories that are its own: new, empty, or marked by it
(`.bearingsim-run`); it never replaces or deletes a file or folder it did not write.
Files and folders follow the process umask like any other program's output.
"""

from __future__ import annotations

import contextlib
import errno
import hashlib
import json
import math
import os
import re
import shutil
import tempfile
import time
from contextlib import contextmanager
from dataclasses import asdict, is_dataclass
from pathlib import Path
from typing import Any, Iterator

from .no_follow import OutputRefused, out_name, refused_special_file  # noqa: F401 - OutputRefused is re-exported

MANIFEST = "stage.json"
RUN_MARKER = ".bearingsim-run"
SCENE_HEADER = "# Resolved scene"  # first line of the scene.toml a run directory holds
STALE_TEMPORARY_AGE_S = 3600.0
# what atomic writes and staged directories leave behind when a process is killed
_TEMPORARY = re.compile(r"^\..+(\.tmp|\.old-\d+)$")


# --- permissions -----------------------------------------------------------------------
def current_umask() -> int:
    """The process umask (Linux reports it in /proc; elsewhere it is set and restored)."""
    try:
        with open("/proc/self/status", encoding="ascii") as fh:
            for line in fh:
                if line.startswith("Umask:"):
                    return int(line.split()[1], 8)
    except (OSError, ValueError):
        pass
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


def file_mode() -> int:
    return 0o666 & ~current_umask()


def dir_mode() -> int:
    return 0o777 & ~current_umask()


def follow_umask(tree: Path) -> None:
    """Give `tree` and everything under it the modes a plain `open`/`mkdir` would have:
    temporary-file helpers (mkstemp, mkdtemp) create owner-only files and folders."""
    tree = Path(tree)
    mask = current_umask()
    fmode, dmode, xmode = 0o666 & ~mask, 0o777 & ~mask, 0o111 & ~mask
    os.chmod(tree, dmode)
    for root, dirs, files in os.walk(tree):
        for d in dirs:
            os.chmod(os.path.join(root, d), dmode)
        for f in files:
            path = os.path.join(root, f)
            if not os.path.islink(path):
                executable = os.stat(path).st_mode & 0o100
                os.chmod(path, fmode | (xmode if executable else 0))


# --- atomic writes ---------------------------------------------------------------------
def atomic_write_bytes(path: Path, data: bytes) -> None:
    """Write `data` to `path` via a temporary file in the same directory + rename."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    try:
        with os.fdopen(fd, "wb") as fh:
            fh.write(data)
            fh.flush()
            os.fchmod(fh.fileno(), file_mode())
            os.fsync(fh.fileno())
        os.replace(tmp, path)
    except BaseException as exc:
        Path(tmp).unlink(missing_ok=True)
        if isinstance(exc, OSError) and exc.filename is None:  # a write: name the file it was for
            raise type(exc)(exc.errno, exc.strerror, str(path)) from exc
        raise


def atomic_write_text(path: Path, text: str) -> None:
    atomic_write_bytes(path, text.encode("utf-8"))


def to_jsonable(obj: Any) -> Any:
    """Dataclasses, tuples, numpy scalars/arrays and paths to plain JSON types; a NaN or an
    infinity becomes null (JSON has neither, and a result must never be silently NaN)."""
    if is_dataclass(obj) and not isinstance(obj, type):
        return to_jsonable(asdict(obj))
    if isinstance(obj, dict):
        return {str(k): to_jsonable(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [to_jsonable(v) for v in obj]
    if isinstance(obj, Path):
        return str(obj)
    if isinstance(obj, float):
        return obj if math.isfinite(obj) else None
    if hasattr(obj, "tolist"):  # numpy arrays and scalars
        return to_jsonable(obj.tolist())
    return obj


def dumps_json(obj: Any, **kwargs: Any) -> str:
    """Strict JSON (RFC 8259) of `obj`: non-finite numbers are written as null."""
    return json.dumps(to_jsonable(obj), allow_nan=False, **kwargs)


def atomic_write_json(path: Path, obj: Any) -> None:
    atomic_write_text(path, dumps_json(obj, indent=2, sort_keys=False) + "\n")


# --- cache keys and manifests ----------------------------------------------------------
def canonical(obj: Any) -> Any:
    """The value a cache key hashes: numbers compare by their exact value (430 == 430.0,
    -0.0 == 0.0), so writing a number differently never recomputes a stage, and two different
    numbers never share a key: an integer that no float holds exactly (2**53 + 1, a seed)
    stays an integer."""
    obj = to_jsonable(obj)
    if isinstance(obj, dict):
        return {k: canonical(v) for k, v in obj.items()}
    if isinstance(obj, list):
        return [canonical(v) for v in obj]
    if isinstance(obj, bool):
        return obj
    if isinstance(obj, int):
        try:
            value = float(obj)
        except OverflowError:
            return obj
        return (0.0 if value == 0.0 else value) if int(value) == obj else obj
    if isinstance(obj, float):
        return 0.0 if obj == 0.0 else obj
    return obj


def input_key(stage: str, inputs: Any, version: str) -> str:
    """sha256 of the canonical JSON of exactly what a stage depends on."""
    blob = json.dumps({"stage": stage, "version": version, "inputs": canonical(inputs)},
                      sort_keys=True, separators=(",", ":"))
    return hashlib.sha256(blob.encode("utf-8")).hexdigest()


def file_digest(path: Path) -> str:
    with open(path, "rb") as fh:
        return hashlib.file_digest(fh, "sha256").hexdigest()


def stage_files(stage_dir: Path) -> dict[str, dict]:
    """{relative path: {size, sha256}} of every file of a stage directory but its manifest."""
    stage_dir = Path(stage_dir)
    out = {}
    for path in sorted(p for p in stage_dir.rglob("*") if p.is_file() and p.name != MANIFEST):
        out[path.relative_to(stage_dir).as_posix()] = {"size": path.stat().st_size, "sha256": file_digest(path)}
    return out


def read_manifest(stage_dir: Path) -> dict | None:
    try:
        manifest = json.loads((Path(stage_dir) / MANIFEST).read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    return manifest if isinstance(manifest, dict) else None


def damaged_files(stage_dir: Path, manifest: dict) -> list[str]:
    """Files the manifest lists that are missing or changed since the stage wrote them
    (a manifest without checksums, written by hand or by an older version, is trusted)."""
    stage_dir = Path(stage_dir)
    damaged = []
    for name, record in (manifest.get("files") or {}).items():
        path = stage_dir / name
        try:
            if path.stat().st_size != record.get("size") or file_digest(path) != record.get("sha256"):
                damaged.append(name)
        except OSError:
            damaged.append(name)
    return damaged


def cache_state(stage_dir: Path, key: str) -> tuple[str, list[str]]:
    """("fresh", []) when `stage_dir` holds an intact finished stage computed from inputs
    hashing to `key`; ("damaged", files) when its files changed since; ("stale", [])
    otherwise (absent, unfinished or other inputs)."""
    manifest = read_manifest(stage_dir)
    if not manifest or manifest.get("key") != key or manifest.get("status") != "done":
        return "stale", []
    damaged = damaged_files(stage_dir, manifest)
    return ("damaged", damaged) if damaged else ("fresh", [])


def is_fresh(stage_dir: Path, key: str) -> bool:
    """True when `stage_dir` holds an intact finished stage computed from inputs hashing to `key`."""
    return cache_state(stage_dir, key)[0] == "fresh"


# --- directories -----------------------------------------------------------------------
@contextmanager
def staged_directory(final_dir: Path) -> Iterator[Path]:
    """Yield a temporary directory; on success it replaces `final_dir` whole.

    Only a folder bearingsim wrote (one with a stage manifest) is ever replaced: a folder
    of the user's own in its place raises OutputRefused before anything is computed.
    """
    final_dir = Path(final_dir)
    refuse_foreign_stage_dir(final_dir)
    final_dir.parent.mkdir(parents=True, exist_ok=True)
    tmp = Path(tempfile.mkdtemp(prefix=f".{final_dir.name}.", suffix=".tmp", dir=final_dir.parent))
    try:
        yield tmp
        follow_umask(tmp)
        refuse_foreign_stage_dir(final_dir)
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)
        raise
    old = None
    if final_dir.exists():
        old = final_dir.with_name(f".{final_dir.name}.old-{os.getpid()}")
        shutil.rmtree(old, ignore_errors=True)
        os.replace(final_dir, old)
    os.replace(tmp, final_dir)
    if old is not None:
        shutil.rmtree(old, ignore_errors=True)


def foreign_files(stage_dir: Path) -> list[str]:
    """Files in a stage folder that its manifest does not list, as relative paths: put
    there by someone else, so never replaced or deleted with the folder. A manifest
    without a file list (written by hand or by an older version) vouches for every file."""
    stage_dir = Path(stage_dir)
    listed = (read_manifest(stage_dir) or {}).get("files")
    if not isinstance(listed, dict):
        return []
    found = (p.relative_to(stage_dir).as_posix() for p in stage_dir.rglob("*") if p.is_file() or p.is_symlink())
    return sorted(name for name in found if name != MANIFEST and name not in listed)


def refuse_foreign_stage_dir(path: Path) -> None:
    """Raise OutputRefused when `path` exists and is not a stage folder bearingsim wrote
    (a stage folder always holds its manifest, even when a result file in it is damaged),
    or when it holds files its manifest does not list (the stage replaces the folder whole)."""
    if path.is_symlink() or (path.exists() and not (path.is_dir() and (path / MANIFEST).is_file())):
        raise OutputRefused(
            f"{path} is in the way of the {path.name} stage and was not written by bearingsim "
            f"(no {MANIFEST}); bearingsim never replaces a file or folder of yours: move it away, "
            f"or give the run its own directory with {out_name()}")
    extra = foreign_files(path) if path.is_dir() else []
    if extra:
        more = f" and {len(extra) - 1} more" if len(extra) > 1 else ""
        raise OutputRefused(
            f"{path / extra[0]}{more}: not written by the {path.name} stage, which replaces {path} "
            f"whole; bearingsim never deletes a file of yours: move it out of {path} and run again")


def remove_stage_dir(path: Path) -> bool:
    """Delete a stage folder bearingsim wrote (True), never anything else (False): not a
    folder holding files its manifest does not list (`foreign_files`)."""
    path = Path(path)
    if path.is_dir() and not path.is_symlink() and (path / MANIFEST).is_file() and not foreign_files(path):
        shutil.rmtree(path)
        return True
    return False


def is_temporary(name: str) -> bool:
    """A file or folder name of what atomic writes and staged directories leave behind."""
    return bool(_TEMPORARY.match(name))


def sweep_stale_temporaries(directory: Path, max_age_s: float = STALE_TEMPORARY_AGE_S) -> list[str]:
    """Remove what a killed run left in `directory` (`.<name>.*.tmp`, `.<name>.old-<pid>`)
    when older than `max_age_s`; a live run's temporaries are younger. Returns the names."""
    removed = []
    now = time.time()
    try:
        entries = list(Path(directory).iterdir())
    except OSError:
        return removed
    for entry in entries:
        if not _TEMPORARY.match(entry.name):
            continue
        try:
            if now - entry.lstat().st_mtime < max_age_s:
                continue
            if entry.is_dir() and not entry.is_symlink():
                shutil.rmtree(entry)
            else:
                entry.unlink()
            removed.append(entry.name)
        except OSError:
            continue
    return removed


SWEEP_POINT_RECORD = "point.json"  # what makes a run directory a point of a sweep


def is_own_run_dir(run_dir: Path) -> bool:
    """A directory bearingsim made a run directory: its marker, or (runs of older versions)
    a resolved scene.toml beside versions.json."""
    run_dir = Path(run_dir)
    if (run_dir / RUN_MARKER).is_file():
        return True
    # a stage folder alone says nothing: a user may keep a copy of one in a folder of theirs
    return is_own_scene_file(run_dir / "scene.toml") and (run_dir / "versions.json").is_file()


def is_own_scene_file(path: Path) -> bool:
    """A resolved scene.toml that a run wrote (its first line is SCENE_HEADER's), not a
    user's scene file."""
    try:
        with Path(path).open(encoding="utf-8") as handle:
            return handle.readline().startswith(SCENE_HEADER)
    except (OSError, ValueError):
        return False


@contextmanager
def refused_unless_usable(out: Path, example: str = "") -> Iterator[None]:
    """Turn an OS error while claiming the --out directory `out` (no permission, a NUL byte in
    the path, ...) into OutputRefused naming it; an OutputRefused passes through."""
    try:
        yield
    except OutputRefused:
        raise
    except OSError as exc:
        if exc.errno in (errno.ENOSPC, getattr(errno, "EDQUOT", errno.ENOSPC)):
            raise  # a full disk is no fault of the directory: the caller names it (exit 1)
        _refuse_unusable(out, example, exc)
    except ValueError as exc:  # a NUL byte in the path
        _refuse_unusable(out, example, exc)


def _refuse_unusable(out: Path, example: str, exc: Exception) -> None:
    reason = exc.strerror if isinstance(exc, OSError) and exc.strerror else str(exc)
    raise OutputRefused(f"{out_name(out)}: cannot use this directory ({reason}); give a writable "
                        f"directory{', e.g. ' + out_name(example) if example else ''}") from None


def mark_directory(directory: Path, marker: str, note: str) -> None:
    """Write `marker` (one line, `note`) into `directory` unless it is there: what makes a
    folder bearingsim's to write."""
    if not (Path(directory) / marker).is_file():
        atomic_write_text(Path(directory) / marker, note + "\n")


def claim_run_directory(run_dir: Path) -> None:
    """Make sure `run_dir` may be written, and mark it as bearingsim's.

    Allowed: a path that does not exist yet (it is created), an empty directory, or a
    directory bearingsim marked before. Anything else raises OutputRefused, before any file
    (not even the lock) is written: a folder of the user's, a file, a device, an
    unwritable place.
    """
    run_dir = Path(run_dir)
    shown = str(run_dir)
    with refused_unless_usable(run_dir, "runs/my-run"):
        exists = run_dir.exists()
        if not exists and run_dir.is_symlink():
            raise OutputRefused(f"{out_name(shown)}: is a link to {os.readlink(run_dir)}, which does not exist; "
                                f"bearingsim does not create what a link points to: give a directory (new or "
                                f"empty), e.g. {out_name('runs/my-run')}")
        if exists and not run_dir.is_dir():
            raise OutputRefused(f"{out_name(shown)}: exists and is not a directory; give a directory "
                                f"(new or empty), e.g. {out_name('runs/my-run')}")
        if not exists:
            run_dir.mkdir(parents=True, exist_ok=True)  # exist_ok: a concurrent run made it
            try:
                _claim_existing(run_dir, shown)
            except BaseException:
                with contextlib.suppress(OSError):
                    run_dir.rmdir()  # made here, and empty unless a concurrent run writes it
                raise
        else:
            _claim_existing(run_dir, shown)


def _claim_existing(run_dir: Path, shown: str) -> None:
    """The part of `claim_run_directory` after `run_dir` exists."""
    if (run_dir / SWEEP_POINT_RECORD).is_file():
        raise OutputRefused(
            f"{out_name(shown)}: is a point of a sweep ({SWEEP_POINT_RECORD}); its results are a row of the "
            f"sweep's table, which a run with other inputs would leave stale. Run the sweep again (its finished "
            f"points are kept), or give this run its own directory, e.g. {out_name('runs/my-run')}")
    if not is_own_run_dir(run_dir):
        if any(p.name not in (RUN_MARKER, ".lock") and not p.name.startswith(f"{RUN_MARKER}.")
               for p in run_dir.iterdir()):  # (a concurrent run writing the marker)
            raise OutputRefused(
                f"{out_name(shown)}: the directory holds files that are not a bearingsim run "
                f"(no {RUN_MARKER} marker); bearingsim never writes into a folder of yours, "
                f"so that none of your files is overwritten. Give a new or empty directory, "
                f"e.g. {out_name(run_dir / 'run')}")
    if not os.access(run_dir, os.W_OK | os.X_OK):
        raise OutputRefused(f"{out_name(shown)}: the directory is not writable by this user; "
                            "give a directory you may write to")
    mark_directory(run_dir, RUN_MARKER, "bearingsim run directory: stage folders here are replaced "
                                        "and removed by bearingsim")


class RunDirectoryBusy(RuntimeError):
    """Another process holds the run directory's lock."""


@contextmanager
def run_directory_lock(run_dir: Path) -> Iterator[None]:
    """Hold an exclusive lock on `run_dir` (file `.lock` inside) while a pipeline writes it.

    Two runs writing one directory would swap their stage results over each other; the
    second is refused at once with RunDirectoryBusy. The lock (pipeline.machine.file_lock) is
    released when the process ends however it ends; a link or a special file in its place is
    refused with OutputRefused, and a link's target is never created.
    """
    from ..machine.file_lock import LockBusy, NotALockFile, exclusive_lock

    run_dir.mkdir(parents=True, exist_ok=True)
    try:
        with exclusive_lock(run_dir / ".lock", wait=False):
            yield
    except LockBusy:
        raise RunDirectoryBusy(
            f"another bearingsim process is writing {run_dir}/; wait for it to finish or give "
            f"this run its own directory with {out_name()}") from None
    except NotALockFile as exc:
        raise refused_special_file(exc.path, exc.what) from None


# Stages worth sharing between run directories by default: the FE identification (costly, and
# the same for every scene with the same [fe] and ring geometry). Dynamic results are per scene.
SHARED_STAGES = frozenset({"identify"})


def shared_store_dir() -> Path:
    """The stage store shared by all run directories of this user: $BEARINGSIM_STAGE_STORE,
    else $XDG_CACHE_HOME/bearingsim/stages (default ~/.cache/bearingsim/stages)."""
    import os

    if os.environ.get("BEARINGSIM_STAGE_STORE"):
        return Path(os.environ["BEARINGSIM_STAGE_STORE"])
    base = Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache")
    return base / "bearingsim" / "stages"
