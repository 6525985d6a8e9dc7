"""Where numba keeps compiled kernels: a directory keyed by a hash of the dynamics sources.

Called by the command line (and the test harness) before any kernel is imported; importing
`bearingsim.dynamics` itself changes no process state.

numba's own cache (next to each source file) is invalidated only when the *defining* file
changes, not when a kernel it calls from another file changes — an edited contact law could
silently run with its old compiled caller. Keying the whole cache by the sources makes any
edit start a fresh cache. A user's own NUMBA_CACHE_DIR is respected.
"""

from __future__ import annotations

import hashlib
import importlib.util
import os
import sys
from pathlib import Path


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
    unless the user set NUMBA_CACHE_DIR."""
    if "NUMBA_CACHE_DIR" in os.environ:
        return
    base = Path(os.environ.get("XDG_CACHE_HOME", Path.home() / ".cache")) / "bearingsim" / "numba"
    os.environ["NUMBA_CACHE_DIR"] = str(base / source_fingerprint(_dynamics_sources()))
    _prune(base, keep=os.environ["NUMBA_CACHE_DIR"])
    if "numba" in sys.modules:  # numba read its configuration already: make it read again
        from numba.core import config

        config.reload_config()


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
