"""Stage `identify`: FE identification of the inner-race hinge stiffness (docs/model.md §3).

Only scenes with `hinge.source = "fe"` need it; its key hashes the `[fe]` table and the
ring dimensions the FE geometry is built from, nothing else. With `fe.model = "mesh"` the key
holds the mesh file's content (its SHA-256), not its path. A mesh that cannot be used as the
scene says is a SceneError naming the key and the region, raised before anything is solved.
"""

from __future__ import annotations

import dataclasses

from ..staging.runner import Stage, StageContext
from ..scene.load import Scene
from ..scene.schema import SceneError

HINGE_FILE = "hinge.toml"
RING_KEYS = ("inner_bore_diameter", "inner_shoulder_diameter", "outer_outside_diameter", "width")


def ring_seat(scene: Scene):
    """The bearing dimensions the FE geometry needs, as fe_model's plain-number type: the
    drawing dimensions (the housing's own thermal growth is not modelled, so neither is the
    rings')."""
    from ...fe_model import RingSeat

    b = scene.bearing  # as drawn
    missing = [k for k in RING_KEYS if getattr(b, k) is None]
    if missing:
        raise SceneError(f"bearing.{missing[0]}",
                         f"required by the FE identification stage (hinge.source = 'fe') [m]; "
                         f"give {', '.join('bearing.' + m for m in missing)} or set hinge.source = 'given'")
    return RingSeat(
        inner_bore_diameter=b.inner_bore_diameter,
        # the ring's outside diameter in the axisymmetric FE model: the mean of its two shoulders
        inner_outer_diameter=b.mean_shoulder_diameter("inner"),
        outer_outside_diameter=b.outer_outside_diameter,
        width=b.width,
    )


def identify_inputs(scene: Scene) -> dict:
    b = scene.bearing
    fe = dataclasses.asdict(scene.fe) if scene.fe is not None else None
    if fe is not None and scene.fe.model == "mesh":
        from ..scene.mesh_files import mesh_identity

        fe["mesh_file"] = mesh_identity(scene.fe.mesh_file)
    return {"fe": fe,
            "ring": {k: getattr(b, k) for k in RING_KEYS},
            "pitch_diameter": b.pitch_diameter}


def compute(ctx: StageContext) -> dict:
    from ...fe_model import identify_hinge

    from ..machine.system_libraries import require_libraries

    from ...fe_model.mesh_checks import MeshInputError

    fe = ctx.scene.fe
    if fe.model != "mesh":
        require_libraries("gmsh")
    ring = ring_seat(ctx.scene)
    try:
        fe.validate(ring)
    except ValueError as exc:
        raise SceneError("fe", str(exc)) from exc
    if fe.model == "mesh":
        from ..scene.mesh_files import ensure_example

        if ensure_example(fe.mesh_file):  # a built-in scene's example: written once, then cached
            ctx.progress("wrote the example mesh", 0.0)
    try:
        result = identify_hinge(fe, ring, ctx.out_dir, progress=ctx.progress)
    except MeshInputError as exc:
        raise SceneError(exc.key, str(exc)) from None
    return {
        "H_u_N_per_m": result.H_u.tolist(), "H_psi_Nm_per_rad": result.H_psi.tolist(),
        "fit_relative_residual": float(result.residual),
        "condition_number": float(result.condition_number),
        "mesh": {k: (float(v) if isinstance(v, float) else v) for k, v in result.mesh_stats.items()},
        "timings_s": {k: float(v) for k, v in result.timings.items()},
        "warnings": result.mesh_stats.get("warnings", []),
    }


STAGE = Stage(
    name="identify",
    depends=(),
    needed=lambda scene: scene.hinge.source == "fe",
    inputs=identify_inputs,
    compute=compute,
    summary="FE hinge identification (gmsh + scikit-fem + least squares)",
)
