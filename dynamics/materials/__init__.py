"""Named materials: the built-in sets of `data/` (cage alloys and polymers, bearing steels,
silicon nitride), each number with its source (docs/model.md §2.2)."""
