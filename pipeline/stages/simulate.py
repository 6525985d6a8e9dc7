"""Stage `simulate`: the HHT-alpha multibody run of the bearing (MODEL.md §4–§9)."""

from __future__ import annotations

import dataclasses

from ..runner import Stage, StageContext, StageNotAvailable
from ..scene import Scene


def simulate_inputs(scene: Scene) -> dict:
    """Everything physical and numerical; the FE inputs reach it through identify's key."""
    raw = {k: v for k, v in scene.raw.items() if k not in ("name", "description", "fe")}
    return {"scene": raw, "hinge": dataclasses.asdict(scene.hinge)}


def compute(ctx: StageContext) -> dict:
    raise StageNotAvailable(
        "the simulate stage (bearing dynamic model, issue 7) is not implemented yet; "
        "`bearingsim quasistatic SCENE` and `bearingsim identify SCENE` work today"
    )


STAGE = Stage(
    name="simulate",
    depends=("identify", "quasistatic"),
    needed=lambda scene: True,
    inputs=simulate_inputs,
    compute=compute,
    summary="dynamic run: cage orbit, speed, impacts, contact forces",
)
