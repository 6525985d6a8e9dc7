"""The pipeline's stages, in order. Each module defines one `STAGE`."""

from __future__ import annotations

from ..staging.runner import Stage
from .identify import STAGE as IDENTIFY
from .quasistatic import STAGE as QUASISTATIC
from .report import STAGE as REPORT
from .simulate import STAGE as SIMULATE

STAGES: list[Stage] = [IDENTIFY, QUASISTATIC, SIMULATE, REPORT]
STAGE_NAMES = [s.name for s in STAGES]
