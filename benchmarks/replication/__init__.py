"""docs/replication.md: the reference paper's modelling choices against bearingsim's defaults,
re-measured on both reference cases (`python -m benchmarks.replication`)."""
