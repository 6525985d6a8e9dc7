"""Dry contact mechanics: Hertz point contact (`hertz`), the ball–race torus–sphere contact
(`race`) and the ball in its cylindrical cage pocket (`pocket`); docs/model.md §6.1–6.2, §7."""
