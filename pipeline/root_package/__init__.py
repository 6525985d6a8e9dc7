"""bearingsim: internal dynamics of ball bearings under high moment load.

This file is the top of the installed namespace (`pyproject.toml` maps the package
`bearingsim` here, and `bearingsim.pipeline`, `.dynamics`, `.fe_model`, `.meshes` to the
repository's top-level folders of those names). See docs/model.md for the model.

The Python API (README "Python API"; `bearingsim.pipeline.api`)::

    import bearingsim
    scene = bearingsim.load_scene("helicopter-b-given-hinge", {"load.moment": 300})
    run = bearingsim.run(scene, "runs/demo", stages=["simulate"])
    run.summary["cage_speed_mean"], run.timeseries()["cage/position"].values
    table = bearingsim.sweep(scene, vary={"load.moment": [200, 430, 600]})

Its names load on first use: `import bearingsim` imports no numba, matplotlib or gmsh.
"""

__version__ = "0.1.0"

_API = {
    "load_scene": "bearingsim.pipeline.api",
    "run": "bearingsim.pipeline.api",
    "sweep": "bearingsim.pipeline.sweep.api",
    "SweepResult": "bearingsim.pipeline.sweep.api",
    "open_run": "bearingsim.pipeline.api",
    "stage_names": "bearingsim.pipeline.api",
    "Run": "bearingsim.pipeline.api",
    "NamedArray": "bearingsim.pipeline.results.named_arrays",
    "TimeSeries": "bearingsim.pipeline.results.named_arrays",
    "export_stiffness": "bearingsim.pipeline.api",
    "stiffness_table": "bearingsim.pipeline.stiffness_export",
    "StiffnessTable": "bearingsim.pipeline.stiffness_export",
    "Scene": "bearingsim.pipeline.scene",
    "SceneError": "bearingsim.pipeline.schema",
    "StageNotAvailable": "bearingsim.pipeline.runner",
    "RunDirectoryBusy": "bearingsim.pipeline.artefacts",
    "OutputRefused": "bearingsim.pipeline.artefacts",
}

__all__ = ["__version__", *sorted(_API)]


def __getattr__(name: str):
    if name in _API:
        import importlib

        value = getattr(importlib.import_module(_API[name]), name)
        globals()[name] = value  # later look-ups skip this function
        return value
    raise AttributeError(f"module 'bearingsim' has no attribute {name!r}")


def __dir__() -> list[str]:
    """The public names only (what `__all__` lists), as tab completion should offer them."""
    return list(__all__)
