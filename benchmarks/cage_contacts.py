"""Time the cage contact kernels: 22 ball–pocket contacts + 1 cage–race journal call.

Run: python -m benchmarks.cage_contacts [--repeats N]

Reference scene of docs/model.md §2 (bronze cage, steel balls and races), a state near the
paper's operating point: cage at 0.44 of the inner-race speed, every other ball touching
its pocket, cage pressed into the land at eps = 1.02 (inside the hybrid blend, the most
expensive branch: film terms plus the Lundberg Newton solve).
"""

from __future__ import annotations

import argparse
import math

import numba
import numpy as np

from bearingsim.dynamics.geometry import BearingGeometry, CageGeometry, Material
from bearingsim.dynamics.journal.short_bearing import cage_race_journal, journal_parameters_for_cage
from bearingsim.dynamics.contact.pocket import pocket_azimuths, pocket_contact, pocket_contacts, pocket_parameters_for_cage
from benchmarks import best_time


def reference_state():
    bearing = BearingGeometry(0.01905, 22, 0.1584, 0.1573, 0.009753, 0.009906, outer_shoulder_diameter=0.166)
    cage = CageGeometry(0.158, 0.02023, 0.00742, 0.0254, "outer")
    steel, bronze = Material(208e9, 0.3, 7850.0), Material(110e9, 0.34, 8800.0)
    pocket_p = pocket_parameters_for_cage(bearing, cage, steel, bronze, restitution=0.7, friction_coefficient=0.1)
    journal_p = journal_parameters_for_cage(bearing, cage, bronze, steel, viscosity=4.9e-3, friction_coefficient=0.1)
    omega_cage = 0.44 * 3060.0 * 2 * math.pi / 60
    psi = pocket_azimuths(22)
    clearance = 0.5 * (cage.pocket_diameter - bearing.ball_diameter)
    # balls at their pocket centres, every other one pushed 2 µm into the wall round the cage
    tangent = np.stack([-np.sin(psi), np.cos(psi), np.zeros(22)], axis=1)
    radial = np.stack([np.cos(psi), np.sin(psi), np.zeros(22)], axis=1)
    push = np.where(np.arange(22) % 2 == 0, clearance + 2e-6, 0.0)[:, None]
    x_balls = 0.079 * radial + push * tangent
    v_balls = omega_cage * 0.079 * tangent + 0.01
    w_balls = np.tile([0.0, 0.0, -900.0], (22, 1))
    cage_state = (np.zeros(3), np.eye(3), np.zeros(3), np.array([0.0, 0.0, omega_cage]))
    journal_state = (np.array([1.02 * journal_p[2], 0.0]), np.array([0.0, 0.05]), omega_cage, 0.0)
    return x_balls, v_balls, w_balls, cage_state, psi, pocket_p, journal_state, journal_p


def time_call(fn, repeats, rounds=5):
    """Best of `rounds` mean times per call [s] (the machine is shared: take the quietest)."""
    fn()  # compile / load from cache
    return best_time(fn, repeat=rounds, number=repeats)


@numba.njit
def _compiled_loop(n, pocket_args, journal_args):
    """What an njit residual pays: n x (22 pockets + 1 journal), no Python dispatch; the
    arguments of `pocket_contacts` and of `cage_race_journal` as two tuples."""
    total = 0.0
    for _ in range(n):
        total += pocket_contacts(*pocket_args)[0, 3]
        total += cage_race_journal(*journal_args)[0]
    return total


def main(repeats: int = 20000) -> None:
    x_b, v_b, w_b, (x_c, rot, v_c, w_c), psi, pocket_p, (off, vel, wc, wr), journal_p = reference_state()
    speeds = np.full(22, 0.1)
    pockets = lambda: pocket_contacts(x_b, v_b, w_b, x_c, rot, v_c, w_c, psi, speeds, pocket_p)
    one_pocket = lambda: pocket_contact(x_b[0], v_b[0], w_b[0], x_c, rot, v_c, w_c, psi[0], 0.1, pocket_p)
    journal = lambda: cage_race_journal(off, vel, wc, wr, journal_p)

    def both():
        pockets()
        journal()

    loop_args = ((x_b, v_b, w_b, x_c, rot, v_c, w_c, psi, speeds, pocket_p), (off, vel, wc, wr, journal_p))
    compiled = time_call(lambda: _compiled_loop(1000, *loop_args), max(1, repeats // 1000)) / 1000
    rows = [
        ("1 pocket contact (in contact)", time_call(one_pocket, repeats)),
        ("22 pocket contacts (batched kernel)", time_call(pockets, repeats)),
        ("1 journal call (hybrid blend, eps=1.02)", time_call(journal, repeats)),
        ("22 pockets + 1 journal", time_call(both, repeats)),
        ("22 pockets + 1 journal, inside njit code", compiled),
    ]
    in_contact = int(pockets()[:, 2].sum())
    print(f"cage contact kernels, {repeats} calls each (Python call overhead included)")
    print(f"{'kernel':<42}{'time per call':>16}")
    for name, seconds in rows:
        print(f"{name:<42}{seconds * 1e6:>13.2f} µs")
    print(f"pockets in contact: {in_contact}/22; journal eps = {journal()[4]:.3f}")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=20000)
    main(parser.parse_args().repeats)
