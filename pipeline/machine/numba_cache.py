"""Where numba keeps compiled kernels: a directory keyed by a hash of the dynamics sources,
checked for damaged files before numba reads it.

Called by the command line (and the test harness) before any kernel is imported; importing
`bearingsim.dynamics` itself changes no process state.

numba's own cache (next to each source file) is invalidated only when the *defining* file
changes, not when a kernel it calls from another file changes — an edited contact law could
silently run with its old compiled caller. Keying the whole cache by the sources makes any
edit start a fresh cache. A user's own NUMBA_CACHE_DIR is respected.

numba trusts its cache files: a truncated data file (`.nbc`, a full disk, a killed copy) or an
index (`.nbi`) overwritten with garbage stops every later run with EOFError or UnpicklingError.
So every index and data file is read through as a pickle (without building its objects) once
after it changes — a stamp of size and modification time records the files found whole — and a
damaged one is removed, so that numba compiles its kernel again; `cache_notes()` says what was
removed, naming the cache. In a NUMBA_CACHE_DIR of the user's own, nothing is removed: the note
names the damaged files. A cache folder that cannot be made (XDG_CACHE_HOME naming a file) is
replaced by a private one in the temporary directory, with a note naming the variable.
"""

from __future__ import annotations

import hashlib
import importlib.util
import io
import json
import os
import pickletools
import sys
import tempfile
from pathlib import Path

CHECKED_FILE = ".bearingsim-checked.json"  # {file: [size, mtime_ns]} of the files found whole
CACHE_SUFFIXES = (".nbi", ".nbc")
_notes: list[str] = []
_checked: set[str] = set()


def source_fingerprint(root: Path) -> str:
    h = hashlib.sha256()
    for path in sorted(root.rglob("*.py")):
        h.update(str(path.relative_to(root)).encode())
        h.update(path.read_bytes())
    return h.hexdigest()[:16]


def _dynamics_sources() -> Path:
    spec = importlib.util.find_spec("bearingsim.dynamics")
    return Path(next(iter(spec.submodule_search_locations))).resolve()


def configure_numba_cache() -> None:
    """Point numba's cache at ~/.cache/bearingsim/numba/<fingerprint> (or $XDG_CACHE_HOME),
    unless the user set NUMBA_CACHE_DIR; then check it for damaged files (module docstring)."""
    if "NUMBA_CACHE_DIR" not in os.environ:
        base = _usable_base()
        os.environ["NUMBA_CACHE_DIR"] = str(base / source_fingerprint(_dynamics_sources()))
        _prune(base, keep=os.environ["NUMBA_CACHE_DIR"])
        if "numba" in sys.modules:  # numba read its configuration already: make it read again
            from numba.core import config

            config.reload_config()
    cache = os.environ["NUMBA_CACHE_DIR"]
    if cache not in _checked:
        _checked.add(cache)
        _notes.extend(check_cache(Path(cache), remove=is_own_cache(Path(cache))))


def is_own_cache(cache: Path) -> bool:
    """A cache folder this module chose (`.../bearingsim*/numba/<fingerprint>`), also when a
    parent process set NUMBA_CACHE_DIR to it; not a NUMBA_CACHE_DIR of the user's own."""
    return cache.parent.name == "numba" and cache.parent.parent.name.startswith("bearingsim")


def _usable_base() -> Path:
    """~/.cache/bearingsim/numba (or under $XDG_CACHE_HOME), or a private folder in the
    temporary directory when that cannot be a folder."""
    xdg = os.environ.get("XDG_CACHE_HOME")
    base = Path(xdg or Path.home() / ".cache") / "bearingsim" / "numba"
    try:
        base.mkdir(parents=True, exist_ok=True)
        if os.access(base, os.W_OK | os.X_OK):
            return base
        reason = "not writable by this user"
    except OSError as exc:
        reason = exc.strerror or str(exc)
    fallback = _private_temporary()
    where = f"XDG_CACHE_HOME={xdg}" if xdg else f"{base}"
    _notes.append(f"the kernel cache cannot be kept under {where} ({reason}): compiled kernels are kept in "
                  f"{fallback} instead; set XDG_CACHE_HOME to a folder you may write (or unset it)")
    return fallback


def _private_temporary() -> Path:
    """A folder of this user's only in the temporary directory (numba loads code from its cache:
    never one another user could have made)."""
    folder = Path(tempfile.gettempdir()) / f"bearingsim-{os.getuid() if hasattr(os, 'getuid') else 'user'}" / "numba"
    folder.mkdir(parents=True, exist_ok=True, mode=0o700)
    info = os.lstat(folder.parent)
    if hasattr(os, "getuid") and (info.st_uid != os.getuid() or os.path.islink(folder.parent)):
        return Path(tempfile.mkdtemp(prefix="bearingsim-numba-"))
    return folder


def cache_notes() -> list[str]:
    """What configuring the cache found (damaged files removed, a cache folder moved), once each."""
    out = list(_notes)
    _notes.clear()
    return out


_STRING_OPS = {"SHORT_BINUNICODE", "BINUNICODE", "BINUNICODE8", "UNICODE", "SHORT_BINSTRING", "BINSTRING", "STRING"}
_MEMO_PUT_OPS = {"PUT", "BINPUT", "LONG_BINPUT", "MEMOIZE"}
_MEMO_GET_OPS = {"GET", "BINGET", "LONG_BINGET"}
_PYTHON2_NAMES = {"__builtin__": "builtins", "copy_reg": "copyreg"}


def pickled_modules(data: bytes) -> set[str] | None:
    """The modules the pickles of `data` name (GLOBAL, and STACK_GLOBAL's module string, pushed
    as a literal or fetched from the memo), read opcode by opcode without building any object;
    None when `data` is not one or more complete pickles (numba's index holds two)."""
    stream = io.BytesIO(data)
    modules: set[str] = set()
    try:
        while stream.tell() < len(data):
            memo: dict[int, object] = {}
            pushed: list[object] = [None, None]  # the last two values pushed (a string, or None)
            for opcode, arg, _ in pickletools.genops(stream):
                name = opcode.name
                if name == "GLOBAL":
                    modules.add(str(arg).split(" ")[0])
                    pushed = [pushed[-1], None]
                elif name == "STACK_GLOBAL":
                    if isinstance(pushed[-2], str):
                        modules.add(pushed[-2])
                    pushed = [None, None]
                elif name in _MEMO_PUT_OPS:
                    memo[len(memo) if name == "MEMOIZE" else arg] = pushed[-1]
                elif name in _MEMO_GET_OPS:
                    pushed = [pushed[-1], memo.get(arg)]
                elif name not in ("FRAME", "PROTO"):
                    pushed = [pushed[-1], arg if name in _STRING_OPS else None]
    except Exception:  # noqa: BLE001 - any way the bytes fail to read as pickles
        return None
    return modules if len(data) > 0 else None


def _importable(module: str, known: dict[str, bool]) -> bool:
    """Whether this process can import `module` (without importing it), memoised in `known`."""
    if module not in known:
        try:
            # protocols 0-2 name Python 2's modules, which the unpickler maps to these
            known[module] = importlib.util.find_spec(_PYTHON2_NAMES.get(module, module)) is not None
        except (ImportError, ValueError):  # a parent package that is not there
            known[module] = False
    return known[module]


def _loadable(data: bytes, known: dict[str, bool]) -> bool:
    """Whole pickles whose every module this process can import: numba loads a file that names
    one it cannot (a contact law registered from a module not on the path now, a test's toy law)
    with ModuleNotFoundError, which stops every run that reads that kernel's index."""
    modules = pickled_modules(data)
    return modules is not None and all(_importable(m, known) for m in modules)


def check_cache(cache: Path, remove: bool = True) -> list[str]:
    """Read the cache files of `cache` changed since their last check; remove the damaged ones
    (with `remove`) and return a note naming them (none when all are whole)."""
    stamp_path = cache / CHECKED_FILE
    try:
        stamps = json.loads(stamp_path.read_text(encoding="utf-8"))
        stamps = stamps if isinstance(stamps, dict) else {}
    except (OSError, ValueError):
        stamps = {}
    try:
        files = [p for p in cache.rglob("*") if p.suffix in CACHE_SUFFIXES and p.is_file() and not p.is_symlink()]
    except OSError:
        return []
    damaged, seen, known = [], {}, {}
    for path in files:
        name = path.relative_to(cache).as_posix()
        try:
            info = path.stat()
            stamp = [info.st_size, info.st_mtime_ns]
            if stamps.get(name) != stamp and not _loadable(path.read_bytes(), known):
                damaged.append(path)
                continue
        except OSError:
            continue  # replaced meanwhile by numba (an atomic rename): checked next time
        seen[name] = stamp
    if damaged and remove:
        for path in damaged:
            path.unlink(missing_ok=True)
        for marker in cache.glob(".compiled-*"):  # what they held compiles again, under the lock
            marker.unlink(missing_ok=True)
    if seen != stamps:
        try:
            tmp = stamp_path.with_name(f".{stamp_path.name}.{os.getpid()}.tmp")
            tmp.write_text(json.dumps(seen), encoding="utf-8")
            os.replace(tmp, stamp_path)
        except OSError:
            pass  # a read-only cache: checked again next time
    if not damaged:
        return []
    names = ", ".join(p.relative_to(cache).as_posix() for p in damaged[:3]) + (
        f" and {len(damaged) - 3} more" if len(damaged) > 3 else "")
    if remove:
        return [f"the kernel cache {cache} held {len(damaged)} file(s) numba cannot load here ({names}; a full disk, "
                f"a killed copy or a contact law from a module not importable now leaves them): removed, the kernels "
                f"they held compile again (about a minute)"]
    return [f"the kernel cache {cache} (NUMBA_CACHE_DIR) holds {len(damaged)} damaged file(s) ({names}): numba "
            f"cannot load them; delete them (or the folder) and the kernels compile again"]


def forget_checks(cache: Path) -> None:
    """Make the next start read every file of `cache` again (after numba failed on one)."""
    Path(cache, CHECKED_FILE).unlink(missing_ok=True)
    _checked.discard(str(cache))


def from_kernel_cache(exc: BaseException) -> bool:
    """True when `exc` was raised while numba read its cache (its traceback runs through
    numba.core.caching)."""
    seen = set()
    while exc is not None and id(exc) not in seen:
        seen.add(id(exc))
        tb = exc.__traceback__
        while tb is not None:
            if tb.tb_frame.f_code.co_filename.replace("\\", "/").endswith("numba/core/caching.py"):
                return True
            tb = tb.tb_next
        exc = exc.__cause__ or exc.__context__
    return False


def _prune(base: Path, keep: str, max_age_s: float = 86400.0) -> None:
    """Drop caches of other source versions untouched for a day (never the current one)."""
    import shutil
    import time

    try:
        for d in base.iterdir():
            if str(d) != keep and d.is_dir() and time.time() - d.stat().st_mtime > max_age_s:
                shutil.rmtree(d, ignore_errors=True)
    except OSError:
        pass
