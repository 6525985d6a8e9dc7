"""Named slots of the bearing model's flat float64 rows: each field is declared once — name,
width, unit, description — and its slot follows from the order of declaration.

Two layouts are declared here, the model's diagnostics of one state (`diag`, filled by every
residual evaluation, docs/model.md §11):

    diag = [ GLOBAL (N_DG) | ball 0 (DB) | ball 1 (DB) | ... | ball Z-1 (DB) ]

A run hands these back by name (`BearingRun.channels()`, `BearingModel.channel()`); the
integer slot constants below exist for the kernels (numba reads module integers as
compile-time constants) and stay inside dynamics/bearing.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np


@dataclass(frozen=True)
class Channel:
    """One named field of a row: `width` consecutive slots from `slot`."""

    name: str
    width: int
    unit: str
    description: str
    saved: bool = True   # handed back with a run's series (False: the model's own bookkeeping)
    cage: bool = False   # exists only in a bearing with a cage
    slot: int = -1       # set by RowLayout

    def view(self, row: np.ndarray) -> np.ndarray:
        """This field of `row` (..., n): shape (...) for one slot, (..., width) otherwise."""
        part = row[..., self.slot:self.slot + self.width]
        return part[..., 0] if self.width == 1 else part


class RowLayout:
    """Fields of a flat row in declaration order; `size` slots in all."""

    def __init__(self, *channels: Channel) -> None:
        self.fields: dict[str, Channel] = {}
        slot = 0
        for c in channels:
            if c.name in self.fields:
                raise ValueError(f"channel {c.name!r} is declared twice")
            self.fields[c.name] = replace(c, slot=slot)
            slot += c.width
        self.size = slot

    def __getitem__(self, name: str) -> Channel:
        try:
            return self.fields[name]
        except KeyError:
            raise KeyError(f"no field {name!r}; declared: {', '.join(self.fields)}") from None

    def __iter__(self):
        return iter(self.fields.values())

    def slot(self, name: str) -> int:
        return self.fields[name].slot


# --- diagnostics of one state -------------------------------------------------------------
GLOBAL = RowLayout(
    Channel("cage_race/eccentricity_ratio", 1, "-", "cage eccentricity / guide clearance", cage=True),
    Channel("cage_race/force", 2, "N", "guide-land force on the cage (x, y)", cage=True),
    Channel("cage_race/torque", 1, "N.m", "guide-land torque on the cage about +z", cage=True),
    Channel("cage_race/metal_force", 1, "N", "metal-to-metal normal force at the land", cage=True),
    Channel("cage_race/friction_power", 1, "W", "metal-contact friction power (burn zone)", cage=True),
    Channel("cage_race/contact_azimuth", 1, "rad", "azimuth of the land point facing the cage offset", cage=True),
    Channel("power/drive_moment", 1, "N.m", "drive moment about the inner-race axis"),
    Channel("power/drive", 1, "W", "power of the drive holding the inner-race speed"),
    Channel("power/external", 1, "W", "power of the applied loads"),
    Channel("power/dissipated", 1, "W", "power dissipated by traction, damping and friction"),
    Channel("energy/hertz", 1, "J", "elastic energy of the ball-race contacts"),
    Channel("energy/hinge", 1, "J", "elastic energy of the hinge"),
    Channel("traction/flagged_contacts", 1, "-",
            "ball-race contacts whose traction flagged its input (dynamics/traction/fast.py FLAG_*)", saved=False),
    Channel("cage_race/film_power", 1, "W", "viscous shear power of the land film (burn zone)", cage=True),
    Channel("cage_race/min_film", 1, "m", "thinnest land film, C(1 + eps0) - e in the hybrid model", cage=True),
)

# inner and outer contact of one ball side by side: the kernel writes slot + j (j = 0 inner, 1 outer)
PER_BALL = RowLayout(
    Channel("contacts/inner_load", 1, "N", "ball-inner race normal load"),
    Channel("contacts/outer_load", 1, "N", "ball-outer race normal load"),
    Channel("contacts/inner_contact_angle", 1, "rad", "inner contact angle (+: carries +z thrust on the inner race)"),
    Channel("contacts/outer_contact_angle", 1, "rad", "outer contact angle"),
    Channel("contacts/inner_film", 1, "m", "inner central film thickness (0: no film)"),
    Channel("contacts/outer_film", 1, "m", "outer central film thickness"),
    Channel("contacts/inner_slide_roll", 1, "-", "inner slide-to-roll ratio"),
    Channel("contacts/outer_slide_roll", 1, "-", "outer slide-to-roll ratio"),
    Channel("contacts/inner_max_pressure", 1, "Pa", "inner maximum Hertz pressure"),
    Channel("contacts/outer_max_pressure", 1, "Pa", "outer maximum Hertz pressure"),
    Channel("pocket/force", 1, "N", "ball-pocket normal force", cage=True),
    Channel("pocket/in_contact", 1, "-", "1 while the ball touches its pocket wall", saved=False, cage=True),
    Channel("pocket/approach_speed", 1, "m/s", "approach speed of ball and pocket wall (+: closing)",
            saved=False, cage=True),
    Channel("pocket/orbital_position", 1, "rad",
            "orbital position of the ball, atan2(y, x), while it touches its pocket (0 otherwise)", saved=False,
            cage=True),
    Channel("pocket/friction_power", 1, "W", "ball-pocket friction power", saved=False, cage=True),
)

N_DG = GLOBAL.size
DB = PER_BALL.size

DG_EPS = GLOBAL.slot("cage_race/eccentricity_ratio")
DG_FX = GLOBAL.slot("cage_race/force")
DG_FY = DG_FX + 1
DG_TORQUE = GLOBAL.slot("cage_race/torque")
DG_METAL = GLOBAL.slot("cage_race/metal_force")
DG_FRICTION_POWER = GLOBAL.slot("cage_race/friction_power")
DG_AZIMUTH = GLOBAL.slot("cage_race/contact_azimuth")
DG_DRIVE = GLOBAL.slot("power/drive_moment")
DG_P_DRIVE = GLOBAL.slot("power/drive")
DG_P_EXT = GLOBAL.slot("power/external")
DG_P_DISS = GLOBAL.slot("power/dissipated")
DG_V_HERTZ = GLOBAL.slot("energy/hertz")
DG_V_HINGE = GLOBAL.slot("energy/hinge")
DG_FLAGS = GLOBAL.slot("traction/flagged_contacts")
DG_FILM_POWER = GLOBAL.slot("cage_race/film_power")
DG_MIN_FILM = GLOBAL.slot("cage_race/min_film")

DB_QI = PER_BALL.slot("contacts/inner_load")
DB_QO = PER_BALL.slot("contacts/outer_load")
DB_AI = PER_BALL.slot("contacts/inner_contact_angle")
DB_AO = PER_BALL.slot("contacts/outer_contact_angle")
DB_HI = PER_BALL.slot("contacts/inner_film")
DB_HO = PER_BALL.slot("contacts/outer_film")
DB_SRRI = PER_BALL.slot("contacts/inner_slide_roll")
DB_SRRO = PER_BALL.slot("contacts/outer_slide_roll")
DB_PMI = PER_BALL.slot("contacts/inner_max_pressure")
DB_PMO = PER_BALL.slot("contacts/outer_max_pressure")
DB_POCKET = PER_BALL.slot("pocket/force")
DB_POCKET_IN_CONTACT = PER_BALL.slot("pocket/in_contact")
DB_POCKET_APPROACH = PER_BALL.slot("pocket/approach_speed")
DB_POCKET_ORBITAL = PER_BALL.slot("pocket/orbital_position")
DB_POCKET_FRICTION_POWER = PER_BALL.slot("pocket/friction_power")
assert all(outer == inner + 1 for inner, outer in (
    (DB_QI, DB_QO), (DB_AI, DB_AO), (DB_HI, DB_HO), (DB_SRRI, DB_SRRO), (DB_PMI, DB_PMO)))


def diag_size(ball_count: int) -> int:
    return N_DG + DB * ball_count


def read(diag: np.ndarray, ball_count: int, name: str) -> np.ndarray:
    """Channel `name` of diagnostics `diag` (..., diag_size(Z)): a global channel has the
    shape (...) or (..., width), a per-ball one (..., Z) or (..., Z, width)."""
    if name in GLOBAL.fields:
        return GLOBAL[name].view(diag[..., :N_DG])
    if name not in PER_BALL.fields:
        raise KeyError(f"no diagnostic channel {name!r}; declared: {', '.join([*GLOBAL.fields, *PER_BALL.fields])}")
    per_ball = diag[..., N_DG:N_DG + DB * ball_count].reshape(diag.shape[:-1] + (ball_count, DB))
    return PER_BALL[name].view(per_ball)


def declared(has_cage: bool, saved_only: bool = True):
    """(channel, per ball?) of every diagnostic a bearing with/without a cage has."""
    for layout, per_ball in ((GLOBAL, False), (PER_BALL, True)):
        for c in layout:
            if (has_cage or not c.cage) and (c.saved or not saved_only):
                yield c, per_ball
