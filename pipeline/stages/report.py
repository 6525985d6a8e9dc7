"""Stage `report`: renders and the run report, from saved results only (never re-solves)."""

from __future__ import annotations

from ..runner import Stage, StageContext, StageNotAvailable


def compute(ctx: StageContext) -> dict:
    raise StageNotAvailable(
        "the report stage (renders and run report, issue 8) is not implemented yet"
    )


STAGE = Stage(
    name="report",
    depends=("identify", "quasistatic", "simulate"),
    needed=lambda scene: True,
    inputs=lambda scene: {},
    compute=compute,
    summary="burn-zone and FE renders, HTML report",
)
