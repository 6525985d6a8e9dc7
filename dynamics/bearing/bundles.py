"""The named bundles the bearing kernels take instead of long positional argument lists.

numba accepts NamedTuples of arrays and floats as arguments and builds them inside kernels;
attribute access compiles to a field load, and a bundle of borrowed arrays needs no
reference counting, so the kernels compiled without it (dynamics/_speed/compile_policy.py) take
them too. A call passes the same arrays as before, now under their names; the hot per-contact
kernels get only the small bundles they read (a body, a race table, the traction rule).

Built once outside the time loop (`BearingModelParams`, `BearingModel`), except `Ball`,
`Body` and `Bodies`, which the residual kernel makes per evaluation from views of (q, v).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from ..traction.fast import TractionRule


class Ball(NamedTuple):
    """One ball: centre x [m], velocity v [m/s], angular velocity w [rad/s] (views of q, v)."""

    x: np.ndarray
    v: np.ndarray
    w: np.ndarray


class Body(NamedTuple):
    """A race or the cage, global frame: centre x [m], rotation R (body -> global), velocity
    v [m/s], spatial angular velocity w [rad/s]."""

    x: np.ndarray
    R: np.ndarray
    v: np.ndarray
    w: np.ndarray


class Bodies(NamedTuple):
    """The bodies a ball touches, in one state; `cage` is read only when there is a cage."""

    inner: Body
    outer: Body
    cage: Body


class RaceTables(NamedTuple):
    """Contact tables of the two races (race_table.race_contact_table)."""

    inner: np.ndarray
    outer: np.ndarray


class HingeArrays(NamedTuple):
    """Viscoelastic hinge of the inner race (docs/model.md §5): stiffnesses H_u (3x3) [N/m],
    H_psi (2) [N m/rad], dampings G = c_G H, and the static frame A (x_A [m], R_A)."""

    H_u: np.ndarray
    H_psi: np.ndarray
    G_u: np.ndarray
    G_psi: np.ndarray
    x_A: np.ndarray
    R_A: np.ndarray


class CageArrays(NamedTuple):
    """Ball–pocket parameters (`contact.pocket.PocketParams`), cage–land parameters
    (`journal.short_bearing.JournalParams`), each with its law's bundle, the impact speeds v_0 [m/s] the hysteresis law remembers per pocket (state of the
    model, updated after every accepted step), and cos psi, sin psi of the pocket azimuths
    (`model.cage_arrays` computes them once)."""

    pocket: tuple
    journal: tuple
    impact_speeds: np.ndarray
    cos_psi: np.ndarray
    sin_psi: np.ndarray


class BorderLoads(NamedTuple):
    """Sums of the contact wrenches on the inner race and the cage, spatial, about their
    centres [N, N m]; filled ball by ball."""

    F_inner: np.ndarray
    M_inner: np.ndarray
    F_cage: np.ndarray
    M_cage: np.ndarray


class ContactScratch(NamedTuple):
    """Work rows of the ball–race contacts (`race_forces.contact_scratch`): per contact its
    geometry (contact/race.py, N_CONTACT_SCRATCH) and what its two phases pass on
    (race_forces.N_CARRY); one traction result (12: T, dT/ds); the film batch's inputs
    (F, R_x, u_s and the five NVM terms, rows of length n), its result and its scratch."""

    contact: np.ndarray
    traction: np.ndarray
    carry: np.ndarray
    film_in: np.ndarray
    film_h: np.ndarray
    film_work: np.ndarray
    film_iwork: np.ndarray


class ResidualWork(NamedTuple):
    """The residual kernel's scratch, allocated once per model instead of in every call:
    contact rows (2Z, N_RC) and pocket rows (Z, N_POCKET_OUT), the contacts' scratch, the
    border load sums, the outer race (x = 0, R = I, v = 0; the kernel sets w = (0, 0, omega_o)
    from the parameters), the rotation (3x3) and spatial angular velocity (3) of the inner race
    and the cage, the external loads, three material moments (3), the cage–land result row, its film's scratch and
    the land reaction on a fixed outer race. Like
    the traction rule's workspace it belongs to one model: one evaluation at a time."""

    rows: np.ndarray
    pocket_rows: np.ndarray
    scratch: ContactScratch
    loads: BorderLoads
    outer: Body
    R_inner: np.ndarray
    w_inner: np.ndarray
    R_cage: np.ndarray
    w_cage: np.ndarray
    ext_f: np.ndarray  # external force on the inner race (3) [N]
    ext_m: np.ndarray  # external moment (3) [N m]
    moment_contact: np.ndarray  # contact moment sum on the inner race, material (3) [N m]
    moment_load: np.ndarray  # external moment on the inner race, material (3) [N m]
    moment_cage: np.ndarray  # contact moment sum on the cage, material (3) [N m]
    journal_row: np.ndarray  # the cage–land result row (journal/short_bearing.py, N_JOURNAL_OUT)
    journal_squeeze: np.ndarray  # the dynamic cage film's scratch (journal/squeeze_film.py, N_SQUEEZE_OUT)
    fixed_reaction: np.ndarray  # (2, 3): the land's reaction force and moment on the fixed outer race (unused)


class ModelArrays(NamedTuple):
    """Everything the residual kernel reads besides the state: the float and integer
    parameter vectors (params.FP_*, IP_*), the diagonal mass, the bundles above, the laws' and the
    residual's scratch (`ResidualWork`)."""

    fp: np.ndarray
    ip: np.ndarray
    mass: np.ndarray
    races: RaceTables
    traction: TractionRule
    film: tuple  # the film law's bundle (`lubrication.film_laws`)
    cage: CageArrays
    hinge: HingeArrays
    work: ResidualWork


class BearingData(NamedTuple):
    """What the force kernel (`assembly.evaluate_bearing`) takes besides the state: the model's
    arrays and its tangent kernel (`assembly.bearing_tangents`) as a numba first-class function
    value (`multibody.compiled.KernelFunction`), so that the two compile as separate libraries."""

    arrays: ModelArrays
    tangents: object
