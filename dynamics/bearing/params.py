"""Pack a physical bearing into the arrays and bundles the force kernel takes (once, outside
the time loop). Everything here is SI; nothing here runs per step."""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from ..geometry import BearingGeometry, CageGeometry, Material, effective_modulus
from ..operating_point import OperatingPoint
from ..traction.fast import TractionRule, dry_traction_rule
from ..lubrication.film_laws import LAWS as FILM_LAWS
from ..lubrication.film_laws.nvm import NVM
from ..traction.laws import LAWS

from . import layout
from .bundles import HingeArrays, RaceTables
from .options import ModelOptions
from .race_table import race_contact_table

# --- float parameter vector fp -----------------------------------------------------------
FP_D, FP_DM, FP_DI, FP_DO, FP_RI, FP_RO = 0, 1, 2, 3, 4, 5
FP_MB, FP_JB = 6, 7                        # ball mass [kg], inertia [kg m^2]
FP_MI, FP_JIX, FP_JIZ = 8, 9, 10          # inner race mass, diametral and polar inertia
FP_MC, FP_JCX, FP_JCZ = 11, 12, 13        # cage
FP_OMEGA_I, FP_OMEGA_O = 14, 15           # race speeds about +z [rad/s]
FP_FX, FP_FZ, FP_MY = 16, 17, 18          # loads on the inner race: radial (x), axial (z), moment (y)
FP_E_EFF = 19                              # ball-race E' [Pa]
FP_ETA0, FP_ALPHA_P = 20, 21               # lubricant at its temperature: eta0 [Pa s], alpha* [1/Pa]
FP_MIN_FILM, FP_ZETA = 22, 23
FP_T_LOAD_STEP, FP_MY_STEP = 24, 25        # from t >= FP_T_LOAD_STEP [s] the moment is FP_MY_STEP [N m]
FP_LOAD_EXPONENT = 26                      # |T| ~ F_n^e at fixed slip: the traction law's load exponent
N_FP = 27

# --- integer switches ip ------------------------------------------------------------------
IP_Z, IP_TRACTION, IP_FILM, IP_CAGE, IP_JOURNAL, IP_HINGE, IP_GYRO = 0, 1, 2, 3, 4, 5, 6
N_IP = 7
# ip[IP_TRACTION]: 1 = the traction law of `BearingModelParams.traction` acts, 0 = switched off
# ip[IP_FILM]: no film; the NVM law for all contacts at once (`lubrication.film`); the film law of
# `BearingModelParams.film`, contact by contact (`film_laws.operations.central_film`)
FILM_NONE, FILM_NVM, FILM_CONTACT = 0, 1, 2
# the parts of the model a study may switch off (`BearingModelParams.without`)
SWITCHES = {"traction": IP_TRACTION, "film": IP_FILM, "cage": IP_CAGE, "journal": IP_JOURNAL,
            "hinge": IP_HINGE, "gyroscopic": IP_GYRO}


@dataclass(frozen=True)
class BearingModelParams:
    """Everything the force kernel needs, as contiguous arrays and bundles (see FP_*, IP_*)."""

    fp: np.ndarray
    ip: np.ndarray
    races: RaceTables
    traction: TractionRule    # the traction law's bundle and, for a film law, the fast engine's rule
    film: tuple               # the EHD film law's bundle (`lubrication.film_laws`)
    pocket: tuple             # ball-pocket parameters and law (contact/pocket.py `PocketParams`)
    journal: tuple            # cage-land parameters and law (journal/short_bearing.py `JournalParams`)
    pocket_psi: np.ndarray    # pocket azimuths [rad]
    hinge: HingeArrays
    has_cage: bool
    guide_clearance: float = float("nan")
    cage_guidance: str = "outer"  # what centres the cage: "outer" | "inner" | "ball" (geometry.CageGeometry)
    meta: dict = field(default_factory=dict)

    @property
    def ball_count(self) -> int:
        return int(self.ip[IP_Z])

    @property
    def n_dof(self) -> int:
        return layout.n_dof(self.ball_count, self.has_cage)

    @property
    def ball_diameter(self) -> float:
        """D [m]."""
        return float(self.fp[FP_D])

    @property
    def pitch_diameter(self) -> float:
        """d_m [m]."""
        return float(self.fp[FP_DM])

    @property
    def ball_mass(self) -> float:
        """m_b [kg]."""
        return float(self.fp[FP_MB])

    def with_float32_residual(self, on: bool = True) -> "BearingModelParams":
        """A copy whose residual-only traction runs through the float32 passes (`on`) or not
        (dynamics/traction/fast.py): ~15 % off a time step, for callers whose tangent is the
        model's own; the default float64 residual is the one to difference."""
        return replace(self, traction=self.traction.with_float32_residual(on))

    def without(self, *parts: str) -> "BearingModelParams":
        """A copy with `parts` switched off (keys of SWITCHES: traction, film, cage, journal,
        hinge, gyroscopic), for studies that time or compare the model piece by piece."""
        unknown = sorted(set(parts) - set(SWITCHES))
        if unknown:
            raise ValueError(f"unknown model part(s) {unknown}; choose from {sorted(SWITCHES)}")
        ip = self.ip.copy()
        for part in parts:
            ip[SWITCHES[part]] = 0
        return replace(self, ip=ip)


def inner_race_inertia(bearing: BearingGeometry, race: Material) -> tuple[float, float, float]:
    """(mass [kg], J_diametral, J_polar [kg m^2]) of the inner ring as two plain annuli, one a
    side of the groove plane, each between the bore and its side's shoulder diameter (the
    groove is neglected); equal shoulders make it one annulus."""
    missing = [k for k in ("inner_bore_diameter", "inner_shoulder_diameter", "width")
               if getattr(bearing, k) is None]
    if missing:
        raise ValueError(
            f"the dynamic model needs the inner-ring mass: give bearing.{missing[0]} [m] "
            f"(missing: {', '.join('bearing.' + m for m in missing)})")
    ri, w = 0.5 * bearing.inner_bore_diameter, bearing.width
    m = jz = jx = 0.0
    for d in bearing.shoulders("inner"):
        ro = 0.5 * d
        m_half = race.density * math.pi * (ro * ro - ri * ri) * 0.5 * w
        m += m_half
        jz += 0.5 * m_half * (ro * ro + ri * ri)
        # each half about its own centre (w/4 off the groove plane), moved there by Steiner
        jx += m_half * (3.0 * (ro * ro + ri * ri) + (0.5 * w) ** 2) / 12.0 + m_half * (0.25 * w) ** 2
    return m, jx, jz


def build_model_params(
    bearing: BearingGeometry, cage: CageGeometry | None, ball: Material, race: Material,
    cage_material: Material | None, lubricant, loads: OperatingPoint, *, hinge: tuple | None,
    static_frame: tuple, options: ModelOptions = ModelOptions(), load_step: tuple[float, float] | None = None,
) -> BearingModelParams:
    """Pack a bearing under `loads` (loads on the inner race and race speeds). `hinge` =
    (H_u 3x3 [N/m], H_psi (2) [N m/rad], c_G [s]) or None (inner race free); `static_frame` =
    (x_A [m], R_A) is the hinge's static frame A (docs/model.md §5). `load_step` =
    (t_step [s], moment after it [N m]): a sudden change of the moment."""
    if not options.centrifugal:
        raise ValueError("physics.centrifugal = false acts only on the quasi-static solve: the dynamic "
                         "model's inertia always carries the balls' centrifugal force")
    Z = bearing.ball_count
    fp = np.zeros(N_FP)
    fp[[FP_D, FP_DM, FP_DI, FP_DO, FP_RI, FP_RO]] = (
        bearing.ball_diameter, bearing.pitch_diameter, bearing.inner_groove_center_diameter,
        bearing.outer_groove_center_diameter, bearing.inner_groove_radius, bearing.outer_groove_radius)
    fp[FP_MB], fp[FP_JB] = bearing.ball_mass(ball), bearing.ball_inertia(ball)
    fp[FP_MI], fp[FP_JIX], fp[FP_JIZ] = inner_race_inertia(bearing, race)
    fp[FP_OMEGA_I], fp[FP_OMEGA_O] = loads.inner_speed, loads.outer_speed
    fp[FP_FX], fp[FP_FZ], fp[FP_MY] = loads.radial, loads.axial, loads.moment
    fp[FP_T_LOAD_STEP], fp[FP_MY_STEP] = load_step if load_step is not None else (math.inf, loads.moment)
    e_eff = effective_modulus(ball, race)
    fp[FP_E_EFF] = e_eff
    fp[FP_MIN_FILM], fp[FP_ZETA] = options.min_film, options.contact_damping_ratio
    ip = np.zeros(N_IP, dtype=np.int64)
    ip[IP_Z] = Z
    ip[IP_GYRO] = int(options.gyroscopic)
    law = LAWS[options.traction]
    ip[IP_TRACTION] = 1
    film = NVM()  # the bundle's type when there is no film (ip[IP_FILM] = FILM_NONE)
    fp[FP_LOAD_EXPONENT] = law.flags["load_exponent"]
    if lubricant is not None:
        fp[FP_ETA0], fp[FP_ALPHA_P] = lubricant.eta0, lubricant.alpha_star
        if options.ehd_film:
            film = FILM_LAWS.pack(options.film_formula, options, lubricant)
            # the batch and the tabulated terms are the NVM law's own: any other law, contact by contact
            ip[IP_FILM] = FILM_NVM if isinstance(film, NVM) else FILM_CONTACT
        elif law.film:
            raise ValueError(f"{options.traction} traction needs the EHD film (ehd_film = True)")
    elif law.film:
        raise ValueError(f"{options.traction} traction needs a lubricant; use traction 'coulomb' for dry contacts")
    bundle = LAWS.pack(options.traction, options, lubricant)
    if law.film:
        from ..traction.fast import FastTraction

        traction = FastTraction.build(lubricant).with_law(bundle).traction_rule()
    else:
        traction = dry_traction_rule(bundle)
    from ..contact.pocket import no_pockets
    from ..journal.short_bearing import no_journal

    pocket, journal, psi, clearance = no_pockets(), no_journal(), np.zeros(Z), float("nan")
    if cage is not None:
        pocket, journal, clearance = _cage_params(bearing, cage, ball, race, cage_material, lubricant, options, fp, ip)
        from ..contact.pocket import pocket_azimuths

        psi = pocket_azimuths(Z, cage.pocket_index_errors, 0.5 * cage.mean_diameter)
    if hinge is not None:
        H_u, H_psi, c_G = np.asarray(hinge[0], float), np.asarray(hinge[1], float), float(hinge[2])
        ip[IP_HINGE] = 1
    else:
        H_u, H_psi, c_G = np.zeros((3, 3)), np.zeros(2), 0.0
    static_x, static_R = static_frame
    contiguous = np.ascontiguousarray
    return BearingModelParams(
        fp=fp, ip=ip,
        races=RaceTables(inner=race_contact_table(bearing, e_eff, outer=False),
                         outer=race_contact_table(bearing, e_eff, outer=True)),
        traction=traction, film=film, pocket=pocket, journal=journal, pocket_psi=contiguous(psi),
        hinge=HingeArrays(H_u=contiguous(H_u), H_psi=contiguous(H_psi), G_u=contiguous(c_G * H_u),
                          G_psi=contiguous(c_G * H_psi), x_A=contiguous(static_x, dtype=float),
                          R_A=contiguous(static_R, dtype=float)),
        has_cage=cage is not None, guide_clearance=clearance, meta={"effective_modulus": e_eff},
        cage_guidance=cage.guidance if cage is not None else "outer",
    )


def _cage_params(bearing, cage, ball, race, cage_material, lubricant, options, fp, ip):
    from ..contact.pocket import pocket_parameters_for_cage
    from ..journal.land_laws import LAWS as LAND_LAWS
    from ..journal.short_bearing import journal_parameters_for_cage, no_journal

    if cage_material is None:
        raise ValueError("a bearing with a cage needs the cage material (materials.cage)")
    m_c = cage.mass(cage_material, bearing)
    jz, jx = cage.inertia(cage_material, bearing)
    fp[FP_MC], fp[FP_JCX], fp[FP_JCZ] = m_c, jx, jz
    ip[IP_CAGE] = 1
    pocket = pocket_parameters_for_cage(bearing, cage, ball, cage_material,
                                        restitution=options.pocket_restitution,
                                        friction_coefficient=options.pocket_friction,
                                        law=options.pocket_law)
    journal = no_journal()
    if options.cage_race != "none" and cage.guide_ring is not None:  # a ball-guided cage runs on no land
        viscosity = lubricant.eta0 if lubricant is not None else 0.0
        if LAND_LAWS[options.cage_race].film and viscosity <= 0.0:
            raise ValueError(f"cage_race = {options.cage_race!r} needs a lubricant viscosity")
        journal = journal_parameters_for_cage(
            bearing, cage, cage_material, race, viscosity=viscosity,
            friction_coefficient=options.cage_race_friction, eps0=options.cage_race_boundary,
            mode=options.cage_race, film=options.cage_race_film,
            # one guiding land (a high shoulder beside a low one) is one journal
            lands=options.cage_race_lands if cage.guide_land_count(bearing) == 2 else 1)
        ip[IP_JOURNAL] = 1
    return pocket, journal, cage.guide_clearance(bearing)
