"""The ball–pocket impact log the dynamic run writes (docs/model.md §7, `impacts.csv`):
`model.track_impacts` against a hand-made sequence of accepted steps, whose events are worked
out by hand below from the rule: a contact episode starts at the first accepted step with the
ball touching its pocket, its impact speed is the approach speed of that step, its peak is the
largest pocket force (with its time and orbital position), and it is logged, with its duration,
at the first accepted step after it in which the pocket is open again. While a pocket is open
the model remembers its approach speed (floored at 0) as v_0 of the hysteresis law."""

from __future__ import annotations

import numpy as np
import pytest

from bearingsim.dynamics.bearing import channels
from bearingsim.dynamics.bearing.model import IMPACT_FIELDS, track_impacts

Z = 3


def diag_of(pockets: dict) -> np.ndarray:
    """One state's diagnostics with the pocket channels of `pockets` {ball: (force [N],
    touching, approach speed [m/s], orbital position [rad])}; other balls open and at rest."""
    diag = np.zeros(channels.diag_size(Z))
    for k, values in pockets.items():
        for name, value in zip(("pocket/force", "pocket/in_contact", "pocket/approach_speed",
                                "pocket/orbital_position"), values):
            channels.read(diag, Z, name)[k] = value
    return diag


# (time [s], {ball: (force, touching, approach, orbital)})
SEQUENCE = [
    (0.0, {0: (0.0, 0.0, 0.3, 0.90), 1: (0.0, 0.0, 0.1, 1.9)}),
    (1.0, {0: (0.0, 0.0, 0.5, 0.95), 1: (5.0, 1.0, 0.2, 2.0)}),
    (2.0, {0: (10.0, 1.0, 0.45, 1.0), 1: (3.0, 1.0, -0.1, 2.1)}),
    (3.0, {0: (40.0, 1.0, 0.1, 1.1), 1: (0.0, 0.0, 0.0, 2.2), 2: (8.0, 1.0, 0.6, 3.0)}),
    (4.0, {0: (25.0, 1.0, -0.3, 1.2), 1: (7.0, 1.0, 0.05, 2.5), 2: (9.0, 1.0, 0.1, 3.1)}),
    (5.0, {0: (0.0, 0.0, -0.2, 1.3), 1: (0.0, 0.0, -0.4, 2.6), 2: (9.5, 1.0, 0.0, 3.2)}),
]
# worked out by hand from SEQUENCE: (step index where logged, event row in IMPACT_FIELDS order)
EXPECTED = [
    (3, (1.0, 1, 2.0, 5.0, 0.2, 2.0)),    # ball 1: touches at t = 1 (approach 0.2), peak 5 N at t = 1, open at t = 3
    (5, (3.0, 0, 1.1, 40.0, 0.45, 3.0)),  # ball 0: touches at t = 2 (approach 0.45), peak 40 N at t = 3, open at t = 5
    (5, (4.0, 1, 2.5, 7.0, 0.05, 1.0)),   # ball 1 again: t = 4 to t = 5
]                                          # ball 2 is still touching at the end: not logged
# v_0 after each step: the approach speed while open (floored at 0), held while touching
EXPECTED_SPEEDS = [(0.3, 0.1, 0.0), (0.5, 0.1, 0.0), (0.5, 0.1, 0.0), (0.5, 0.0, 0.0),
                   (0.5, 0.0, 0.0), (0.0, 0.0, 0.0)]


@pytest.mark.parametrize("compiled", [True, False])
def test_impacts_of_a_hand_made_sequence(compiled):
    kernel = track_impacts if compiled else track_impacts.py_func
    state = np.zeros((Z, 6))
    events = np.full((Z, len(IMPACT_FIELDS)), np.nan)
    speeds = np.full(Z, 9.0)
    logged = []
    for step, (t, pockets) in enumerate(SEQUENCE):
        n = kernel(t, diag_of(pockets), Z, state, events, speeds)
        logged += [(step, tuple(row)) for row in events[:n]]
        np.testing.assert_allclose(speeds, EXPECTED_SPEEDS[step], rtol=0, atol=0, err_msg=f"step {step}")
    assert [s for s, _ in logged] == [s for s, _ in EXPECTED]
    for (_, got), (_, want) in zip(logged, EXPECTED):
        np.testing.assert_allclose(got, want, rtol=1e-15, atol=0)
    assert state[2, 0] == 1.0 and state[2, 1] == 9.5  # the open episode: in contact, peak so far


def test_a_contact_of_one_step_is_logged_with_its_only_sample():
    state, events, speeds = np.zeros((Z, 6)), np.zeros((Z, len(IMPACT_FIELDS))), np.zeros(Z)
    track_impacts(0.0, diag_of({0: (0.0, 0.0, 0.7, 0.0)}), Z, state, events, speeds)
    assert track_impacts(1e-6, diag_of({0: (120.0, 1.0, 0.65, 0.5)}), Z, state, events, speeds) == 0
    assert track_impacts(2e-6, diag_of({0: (0.0, 0.0, -0.5, 0.6)}), Z, state, events, speeds) == 1
    np.testing.assert_allclose(events[0], (1e-6, 0, 0.5, 120.0, 0.65, 1e-6), rtol=1e-15)
