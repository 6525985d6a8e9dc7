"""Parameter sweeps on Dask and cage-stability maps (`bearingsim sweep`).

- `.spec` — what to vary (`--vary`, the scene's `[sweep]` table)
- `.points` — expansion into points, stable ids, per-point scene tables
- `.point_runner` — one point = one pipeline run with a shared stage store
- `.driver` — plan, run on a Dask client, resume, gather
- `.classify` — cage-motion class from summary metrics (documented thresholds)
- `.table`, `.stability_map`, `.console` — results table, map, progress

Light on import: dask and matplotlib are imported by the functions that use them.
"""
