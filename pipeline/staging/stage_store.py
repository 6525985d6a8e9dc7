"""The stage store shared by run directories (pipeline.staging.runner): what makes a folder one.

A store holds `<stage>/<key>/` result folders, their locks and temporaries; bearingsim writes
only into a store that is new, empty, or one it marked (`.bearingsim-store`; a store of an older
version holds nothing but such stage folders), never into a folder of the user's.
"""

from __future__ import annotations

import os
import re
from pathlib import Path

from .artefacts import is_temporary, mark_directory
from .no_follow import OutputRefused

STORE_MARKER = ".bearingsim-store"
# what a stage folder of a store holds: results by the sha256 of their inputs, their locks, temporaries
_STORE_ENTRY = re.compile(r"^\.?[0-9a-f]{64}(\.lock|\..+\.tmp|\.old-\d+)?$")


def _is_store_stage_folder(path: Path) -> bool:
    try:
        return path.is_dir() and not path.is_symlink() and all(_STORE_ENTRY.match(p.name) for p in path.iterdir())
    except OSError:
        return False


def claim_store_directory(store: Path) -> None:
    """Make sure the stage store `store` is bearingsim's to write, and mark it: a new or empty
    folder, one it marked, or a store of an older version (only stage folders of results by key);
    OutputRefused otherwise (`--store /` would fill the root with stage folders)."""
    store = Path(store)
    if (store / STORE_MARKER).is_file():
        return
    if store.is_symlink() and not store.exists():
        raise OutputRefused(f"{store}: is a link to {os.readlink(store)}, which does not exist; give the stage "
                            "store a folder of its own")
    if store.exists():
        if not store.is_dir():
            raise OutputRefused(f"{store}: exists and is not a folder; give the stage store a folder of its own")
        # a concurrent run may write the marker between the test above and this listing
        foreign = [p.name for p in store.iterdir()
                   if p.name != STORE_MARKER and not is_temporary(p.name) and not _is_store_stage_folder(p)]
        if foreign:
            raise OutputRefused(f"{store}: holds {', '.join(sorted(foreign)[:3])}{' and more' if len(foreign) > 3 else ''}, "
                                "which are not a bearingsim stage store's; bearingsim never writes into a folder of "
                                f"yours: give the stage store a new or empty folder, e.g. {store / 'bearingsim-stages'}")
    store.mkdir(parents=True, exist_ok=True)
    mark_directory(store, STORE_MARKER, "bearingsim stage store: stage results shared by run directories, "
                                        "by the hash of their inputs; delete it to reclaim the space")
