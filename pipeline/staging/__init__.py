"""The staged runner: cache keys, atomic stage folders, run-directory ownership, provenance."""
