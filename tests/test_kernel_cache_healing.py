"""numba's kernel cache heals itself (docs/reliability.md): a truncated data file (.nbc) or a
garbage index (.nbi) is found before numba reads it, removed, and its kernel compiles again,
with a note naming the cache; in a NUMBA_CACHE_DIR of the user's own nothing is removed and the
note names the damaged files; a damaged file the check misses gives a message naming the cache,
not "a defect of bearingsim"; XDG_CACHE_HOME naming a file moves the cache, with a note."""

from __future__ import annotations

import json
import os
import pickle
import subprocess
import sys
import textwrap

import pytest

from bearingsim.pipeline.machine.numba_cache import CHECKED_FILE, check_cache, pickled_modules

KERNEL = textwrap.dedent("""
    import numba

    @numba.njit(cache=True)
    def twice(x):
        return 2.0 * x
""")
# a fresh process: configure the cache (which checks it), then call the cached kernel
CALL = textwrap.dedent("""
    import sys
    sys.path.insert(0, sys.argv[1])
    from bearingsim.pipeline.machine.numba_cache import cache_notes, configure_numba_cache, from_kernel_cache
    configure_numba_cache()
    for note in cache_notes():
        print("NOTE", note)
    import kernel_mod
    try:
        print("RESULT", kernel_mod.twice(21.0))
    except Exception as exc:
        print("FAILED", type(exc).__name__, "from the kernel cache" if from_kernel_cache(exc) else "elsewhere")
""")


def _run(tmp_path, cache):
    (tmp_path / "kernel_mod.py").write_text(KERNEL)
    (tmp_path / "call.py").write_text(CALL)
    env = dict(os.environ, NUMBA_CACHE_DIR=str(cache))
    done = subprocess.run([sys.executable, str(tmp_path / "call.py"), str(tmp_path)], capture_output=True,
                          text=True, env=env, cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    return done.stdout


def _cache_files(cache, suffix):
    return sorted(p for p in cache.rglob(f"*{suffix}"))


@pytest.fixture()
def own_cache(tmp_path):
    """A cache where bearingsim puts its own (.../bearingsim/numba/<fingerprint>), compiled once."""
    cache = tmp_path / "xdg" / "bearingsim" / "numba" / "0123456789abcdef"
    assert "RESULT 42.0" in _run(tmp_path, cache)
    assert _cache_files(cache, ".nbi") and _cache_files(cache, ".nbc")
    return cache


def _truncate(path):
    path.write_bytes(path.read_bytes()[: path.stat().st_size // 2])


def _garbage(path):
    path.write_bytes(b"\x37\x00garbage that is no pickle")


@pytest.mark.parametrize("damage, suffix", [(_truncate, ".nbc"), (_garbage, ".nbi"), (_truncate, ".nbi")])
def test_a_damaged_cache_file_is_removed_and_recompiled(damage, suffix, own_cache, tmp_path):
    (own_cache / ".compiled-abc").touch()
    damage(_cache_files(own_cache, suffix)[0])
    out = _run(tmp_path, own_cache)
    assert "RESULT 42.0" in out, out
    assert f"NOTE the kernel cache {own_cache} held 1 file(s) numba cannot load here" in out and "removed" in out
    assert not (own_cache / ".compiled-abc").exists()  # compiled again under the compile lock
    assert "NOTE" not in _run(tmp_path, own_cache)  # healed: the next start finds nothing


def test_without_the_check_numba_fails_on_the_damaged_file(own_cache, tmp_path):
    """What the check prevents: numba reads a garbage index and raises (the issue's repro). A
    check stamp that claims the file whole keeps the check from reading it; the failure is then
    recognised as the kernel cache's."""
    index = _cache_files(own_cache, ".nbi")[0]
    _garbage(index)
    stamps = {index.relative_to(own_cache).as_posix(): [index.stat().st_size, index.stat().st_mtime_ns]}
    (own_cache / CHECKED_FILE).write_text(json.dumps(stamps))
    out = _run(tmp_path, own_cache)
    assert "FAILED UnpicklingError from the kernel cache" in out, out


def test_a_users_own_numba_cache_dir_is_not_touched(tmp_path):
    cache = tmp_path / "my-numba-cache"
    assert "RESULT 42.0" in _run(tmp_path, cache)
    data = _cache_files(cache, ".nbc")[0]
    _truncate(data)
    notes = check_cache(cache, remove=False)
    assert data.exists() and len(notes) == 1
    assert f"{cache} (NUMBA_CACHE_DIR)" in notes[0] and data.name in notes[0] and "delete" in notes[0]


def test_pickled_modules_reads_numba_s_index_layout():
    """Whole pickles give their modules (a set), anything else None."""
    index = pickle.dumps("0.68") + pickle.dumps(("stamp", {"key": "name"}))  # numba: version, then data
    assert pickled_modules(index) is not None and pickled_modules(pickle.dumps(list(range(1000)))) is not None
    assert pickled_modules(index[:-3]) is None and pickled_modules(b"") is None
    assert pickled_modules(b"\x37garbage") is None


def test_the_cli_names_the_cache_when_numba_fails_on_it(monkeypatch, tmp_path):
    """A failure raised inside numba's caching is the cache's (exit 1, the cache named, and the
    next start reads every file again), not 'internal error ... a defect of bearingsim'."""
    from bearingsim.pipeline.cli import commands

    cache = tmp_path / "bearingsim" / "numba" / "fedcba9876543210"
    cache.mkdir(parents=True)
    (cache / CHECKED_FILE).write_text("{}")
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(cache))
    from numba.core import caching

    def unreadable(*args, **kwargs):
        raise EOFError("Ran out of input")

    file = caching.IndexDataCacheFile.__new__(caching.IndexDataCacheFile)
    monkeypatch.setattr(caching.IndexDataCacheFile, "_load_index", lambda self: unreadable())
    try:
        caching.IndexDataCacheFile.load(file, "key")
    except EOFError as exc:
        message = commands._kernel_cache_failure(exc)
    assert message is not None and str(cache) in message and "EOFError" in message
    assert "run the command again" in message and not (cache / CHECKED_FILE).exists()
    assert commands._kernel_cache_failure(EOFError("elsewhere")) is None


def test_xdg_cache_home_naming_a_file_moves_the_cache(tmp_path):
    afile = tmp_path / "afile"
    afile.write_text("mine\n")
    script = ("from bearingsim.pipeline.machine.numba_cache import cache_notes, configure_numba_cache\n"
              "import os; configure_numba_cache(); print(os.environ['NUMBA_CACHE_DIR']); print(cache_notes())")
    env = {k: v for k, v in os.environ.items() if k != "NUMBA_CACHE_DIR"} | {"XDG_CACHE_HOME": str(afile)}
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, env=env)
    assert done.returncode == 0, done.stderr
    where, notes = done.stdout.splitlines()[:2]
    assert not where.startswith(str(afile)) and f"XDG_CACHE_HOME={afile}" in notes
    assert afile.read_text() == "mine\n"


def test_an_index_naming_a_module_this_process_cannot_import_is_removed(tmp_path):
    """A kernel specialised for a law registered from a module not importable now (here, as after
    the test suite's toy laws, a class of a module `tests_gone`) makes numba's index load fail with
    ModuleNotFoundError on every run: the check removes it, and says why; the same layout naming
    an importable module is kept."""
    cache = tmp_path / "cache"
    cache.mkdir()
    gone = cache / "gone.nbi"
    # pickle protocol 4's STACK_GLOBAL and protocol 0's GLOBAL, the module names of both
    gone.write_bytes(pickle.dumps(1, protocol=4) + b"\x80\x04\x95\x1d\x00\x00\x00\x00\x00\x00\x00\x8c\ntests_gone"
                     b"\x94\x8c\x03Law\x94\x93\x94.")
    kept = cache / "kept.nbi"
    kept.write_bytes(pickle.dumps(1, protocol=4) + pickle.dumps(json.JSONDecoder, protocol=4))
    import numba  # a numba type's pickle at every protocol names importable modules only
    for protocol in range(pickle.HIGHEST_PROTOCOL + 1):
        (cache / f"numba-{protocol}.nbc").write_bytes(pickle.dumps((numba.float64, {"k": json.JSONDecoder}),
                                                                   protocol=protocol))
    old = cache / "old.nbc"
    old.write_bytes(b"cgone_module\nThing\np0\n.")
    notes = check_cache(cache)
    assert not gone.exists() and not old.exists() and kept.exists()
    assert len(list(cache.glob("numba-*.nbc"))) == pickle.HIGHEST_PROTOCOL + 1
    assert len(notes) == 1 and "numba cannot load here" in notes[0] and "not importable" in notes[0]
