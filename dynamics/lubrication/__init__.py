"""The lubricant: its rheology (`rheology`), the parameter sets shipped in `data/`
(`lubricant`) and the EHD central film thickness (`film`); docs/model.md §6.3–6.4."""
