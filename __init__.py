"""bearingsim: internal dynamics of ball bearings under high moment load.

The repository root is the package: this file is its face, and the top-level folders
`pipeline/`, `dynamics/`, `fe_model/`, `meshes/` are `bearingsim.pipeline` and so on (`pyproject.toml`).
Inside the package every import is relative, so a type checker or an editor reading the clone
resolves it as an install would. See docs/model.md for the model.

The Python API (README "Python API"; `bearingsim.pipeline.api`)::

    import bearingsim
    scene = bearingsim.load_scene("helicopter-b-given-hinge", {"load.moment": 300})
    run = bearingsim.run(scene, "runs/demo", stages=["simulate"])
    run.summary["cage_speed_mean"], run.timeseries()["cage/position"].values
    run.plot.orbit()  # a matplotlib Figure; the report draws the same
    table = bearingsim.sweep(scene, vary={"load.moment": [200, 430, 600]})

Its names load on first use: `import bearingsim` imports no numba, matplotlib or gmsh.
"""

from typing import TYPE_CHECKING

__version__ = "0.1.0"

if TYPE_CHECKING:  # what static tools see; at run time each name loads on first use (_API)
    from .pipeline.api import Run, RunPlots, export_stiffness, load_scene, open_run, run, stage_names
    from .pipeline.results.named_arrays import NamedArray, TimeSeries
    from .pipeline.scene.load import Scene
    from .pipeline.scene.schema import SceneError
    from .pipeline.staging.artefacts import OutputRefused, RunDirectoryBusy
    from .pipeline.staging.runner import StageNotAvailable
    from .pipeline.stiffness_export import StiffnessTable, stiffness_table
    from .pipeline.sweep.api import SweepResult, sweep

_API = {
    "load_scene": "bearingsim.pipeline.api",
    "run": "bearingsim.pipeline.api",
    "sweep": "bearingsim.pipeline.sweep.api",
    "SweepResult": "bearingsim.pipeline.sweep.api",
    "open_run": "bearingsim.pipeline.api",
    "stage_names": "bearingsim.pipeline.api",
    "Run": "bearingsim.pipeline.api",
    "RunPlots": "bearingsim.pipeline.api",
    "NamedArray": "bearingsim.pipeline.results.named_arrays",
    "TimeSeries": "bearingsim.pipeline.results.named_arrays",
    "export_stiffness": "bearingsim.pipeline.api",
    "stiffness_table": "bearingsim.pipeline.stiffness_export",
    "StiffnessTable": "bearingsim.pipeline.stiffness_export",
    "Scene": "bearingsim.pipeline.scene.load",
    "SceneError": "bearingsim.pipeline.scene.schema",
    "StageNotAvailable": "bearingsim.pipeline.staging.runner",
    "RunDirectoryBusy": "bearingsim.pipeline.staging.artefacts",
    "OutputRefused": "bearingsim.pipeline.staging.artefacts",
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
