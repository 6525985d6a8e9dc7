"""Scenes: the schema, the sections, loading and overrides, physical validity, clearances."""
