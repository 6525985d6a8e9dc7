"""Run a test's script in a fresh Python process with a numba cache of its own, so that what
the script compiles, and what it finds in the cache, depends on that test alone."""

import os
import subprocess
import sys
from pathlib import Path


def run_script(tmp_path: Path, script: str, *args: str, name: str = "run.py") -> subprocess.CompletedProcess:
    """Write `script` to tmp_path/name and run it from tmp_path, with numba's cache in
    tmp_path/numba; returns the finished process (its output as text)."""
    path = tmp_path / name
    path.write_text(script)
    return subprocess.run([sys.executable, str(path), *args], cwd=tmp_path, capture_output=True, text=True,
                          env=dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path / "numba")))
