"""bearingsim: internal dynamics of ball bearings under high moment load.

This file is the top of the installed namespace (`pyproject.toml` maps the package
`bearingsim` here, and `bearingsim.pipeline`, `.dynamics`, `.fe_model`, `.meshes` to the
repository's top-level folders of those names). See docs/model.md for the model.
"""

__version__ = "0.1.0"
