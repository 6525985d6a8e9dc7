"""The cage-verdict study of docs/validation.md: sensitivity, ablations and the moment sweep
of the reference bearing, run through the `bearingsim` command line (not installed).

`data/` holds what the study measured: the plans' JSON files and their tables, the crush screen,
the tolerance sets with their analyses, and the figures docs/validation.md does not show."""

from pathlib import Path

DATA = Path(__file__).resolve().parent / "data"
