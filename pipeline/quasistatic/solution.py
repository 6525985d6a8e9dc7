"""The quasi-static solution of a scene and the crush screen on it (docs/model.md §10, §10.1):
what the quasi-static stage writes, and what the tolerance analysis and the bench reuse."""

from __future__ import annotations

import numpy as np

from ..scene.load import Scene


def operating_point(scene: Scene):
    """The loads on the inner race and the race speeds of `scene` (`[load]`, `[speed]`)."""
    from ...dynamics.operating_point import OperatingPoint

    return OperatingPoint(axial=scene.load.axial, radial=scene.load.radial, moment=scene.load.moment,
                          inner_speed=scene.speed.inner, outer_speed=scene.speed.outer)


def solve(scene: Scene):
    """Solve the quasi-static equilibrium of `scene` (no files)."""
    from ...dynamics.quasistatic.options import QuasiStaticOptions
    from ...dynamics.quasistatic.solver import solve_quasistatic

    return solve_quasistatic(
        scene.operating.bearing, scene.operating.materials.ball, scene.operating.materials.race, operating_point(scene),
        QuasiStaticOptions(centrifugal=scene.physics.centrifugal, gyroscopic=scene.physics.gyroscopic),
    )


def land_shift(scene: Scene, result) -> np.ndarray:
    """(2, 2) [m]: the guiding land's centre minus the non-guiding land's, in x and y, at the
    cage's two ends (z = -+w_c/2 from the inner ring's centre), from the inner ring's
    displacement and tilt (M.124)."""
    from ...dynamics.quasistatic.result import tilt_rotation_matrix

    axis = tilt_rotation_matrix(np.asarray(result.inner_tilt, float))[:, 2]
    half = 0.5 * scene.operating.cage.width
    centres = np.array([result.inner_displacement[:2] + axis[:2] * z / axis[2] for z in (-half, half)])
    return -centres if scene.cage.guidance == "outer" else centres


def cage_screen(scene: Scene, result, parts=None):
    """The crush screen (docs/model.md §10.1) of a scene with a cage, else None; `parts`
    (default: the operating parts) gives the clearances."""
    if scene.cage is None:
        return None
    from ...dynamics.quasistatic.crush_screen import crush_screen, excursion_of

    from ..scene.clearances import cage_clearances, land_film

    parts = parts or scene.operating
    excursion = excursion_of(result.azimuth, result.ball_orbital_speed, 0.5 * scene.operating.cage.mean_diameter)
    return crush_screen(excursion, result.cage_speed, cage_clearances(parts), land_film(scene),
                        land_shift(scene, result))


def screen_payload(scene: Scene, result) -> dict | None:
    """`cage_screen` of quasistatic.json: the screen at operating clearances, the margin the
    drawing's (reference-temperature) clearances would give with the same ball excursion, and
    the clearance table."""
    screen = cage_screen(scene, result)
    if screen is None:
        return None
    from ..scene.clearances import clearance_table

    payload = screen.to_json_dict()
    cold = cage_screen(scene, result, parts=scene.nominal)
    payload["crush_margin_at_reference_temperature"] = cold.crush_margin
    payload["regime_at_reference_temperature"] = cold.regime
    payload["clearances"] = clearance_table(scene)
    return payload
