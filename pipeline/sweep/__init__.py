"""Parameter sweeps on Dask and cage-stability maps (`bearingsim sweep`).

- :mod:`.spec` — what to vary (`--vary`, the scene's `[sweep]` table)
- :mod:`.points` — expansion into points, stable ids, per-point scene tables
- :mod:`.point_runner` — one point = one pipeline run with a shared stage store
- :mod:`.driver` — plan, run on a Dask client, resume, gather
- :mod:`.classify` — cage-motion class from summary metrics (documented thresholds)
- :mod:`.table`, :mod:`.stability_map`, :mod:`.console` — results table, map, progress

Light on import: dask and matplotlib are imported by the functions that use them.
"""
