"""Test harness: numba's cache keyed by the dynamics sources, as the command line does it
(numba's own per-file cache misses an edit to a kernel's callee in another file)."""

from bearingsim.pipeline.machine.numba_cache import configure_numba_cache

configure_numba_cache()


import pytest  # noqa: E402


@pytest.fixture(autouse=True)
def _private_stage_store(tmp_path_factory, monkeypatch):
    """Each test gets its own empty shared stage store (the CLI shares the FE identification
    between run directories through it), so no test sees another's results or the user's."""
    monkeypatch.setenv("BEARINGSIM_STAGE_STORE", str(tmp_path_factory.mktemp("stage-store")))
