"""The cage-verdict study of docs/validation.md: sensitivity, ablations and the moment sweep
of the reference bearing, run through the `bearingsim` command line (not installed)."""
