"""Physical validity: say plainly when a scene or a result is outside what the model covers.

Three moments, one kind of answer (`Finding`, an error or a warning naming the scene
key, the value, what is allowed and the unit):

- **before anything runs** — `scene_findings` (geometry that cannot be built as the
  model assumes: clearance beyond the curvature-centre limit, a land outside its groove, a
  cage that does not fit between the rings; the resources a dynamic run would need;
  values that look like the wrong unit) and `run_findings` (what the stages about to
  run cannot do, e.g. an inner-guided cage in the dynamics);
- **after a stage** — `stage_findings` (in pipeline.staging.result_checks) reads the stage's
  own result file (`quasistatic.json`, `summary.json`) and checks it against the limits of
  the model (contact angle past the groove, ellipse truncation, contact pressure beyond the
  steel's limit, a displacement as large as the ball).

An *error* means the result would be meaningless: the run stops with exit code 2 and no
result is kept. A *warning* means the result is doubtful: it is printed, logged to
run.log and stored with the result (`validity` list of the JSON and of `stage.json`).

The limits are this project's choices, with their reasons next to each constant.
"""

from __future__ import annotations

import dataclasses

import math
import os
from dataclasses import dataclass

from ...dynamics.geometry import SIDE_NAMES, SIDES, contact_side

from .schema import SceneError

# ISO 76:2006 "Rolling bearings — Static load ratings", §5.1 / §6.1: the basic static load
# rating of radial ball bearings (self-aligning excepted) corresponds to a calculated contact
# stress of 4200 MPa at the centre of the most heavily loaded contact; at that stress the
# permanent deformation of ball and raceway is about 0.0001 of the ball diameter. Beyond it
# the elastic (Hertz) contact model the solver uses is increasingly wrong: a warning.
STATIC_CAPACITY_PRESSURE = 4.2e9  # Pa
# Fully plastic indentation: the mean pressure reaches about 3 Y (Tabor 1951; Johnson,
# "Contact Mechanics" 1985, §6.5). With Y ≈ 2.3 GPa for through-hardened bearing steel
# (AISI 52100 at 60-64 HRC) that is p_m ≈ 7 GPa, i.e. a Hertz peak p_0 = 1.5 p_m ≈ 10 GPa.
# Above it no elastic contact exists: an error.
PLASTIC_LIMIT_PRESSURE = 10.0e9  # Pa
# The time averages of summary.json use the last half of the run: at least 10 samples there.
MIN_SAMPLES = 20
# Beyond this many steps (at max_step) a run takes days.
MAX_STEPS = 1e9
STEP_WALL_TIME_PER_BALL = 90e-6 / 22  # s per step and ball, measured for helicopter-b
# Doubles kept per time sample by the recorder (time, q, v, diagnostics, kinetic energy):
# 2 + 2 (6 Z + 12) + 16 + 15 Z (dynamics/bearing/layout.py, assembly.diag_size), and the
# output writer holds about two more copies while it writes timeseries.h5.
SAMPLE_COPIES = 3
# a value this large in a result is a sentinel or an overflow, not a physical quantity
ABSURD = 1e100


@dataclass(frozen=True)
class Finding:
    level: str  # "error" | "warning"
    key: str  # dotted scene key ("" when none applies)
    message: str

    @property
    def text(self) -> str:
        return f"{self.key}: {self.message}" if self.key else self.message

    def to_json(self) -> dict:
        return {"level": self.level, "key": self.key, "message": self.message}


class ValidityError(SceneError):
    """A scene or a result outside the model's validity (exit code 2)."""

    def __init__(self, findings: list[Finding]):
        errors = [f for f in findings if f.level == "error"]
        self.findings = errors
        first = errors[0]
        more = "".join(f"\n  also {f.text}" for f in errors[1:4])
        if len(errors) > 4:
            more += f"\n  (and {len(errors) - 4} more)"
        super().__init__(first.key, first.message + more)


def error(key: str, message: str) -> Finding:
    return Finding("error", key, message)


def warning(key: str, message: str) -> Finding:
    return Finding("warning", key, message)


def raise_errors(findings: list[Finding]) -> list[Finding]:
    """Raise ValidityError when `findings` holds an error; else return the warnings."""
    if any(f.level == "error" for f in findings):
        raise ValidityError(findings)
    return [f for f in findings if f.level == "warning"]


def _g(x: float) -> str:
    return f"{x:.4g}"


# --- before anything runs ----------------------------------------------------------------
def scene_findings(scene) -> list[Finding]:
    """Checks of a resolved scene that need no solve: geometry, resources, units. Geometry is
    checked as the scene gives it (the drawing): messages quote the user's own values; the
    operating parts are checked where they are grown (pipeline.scene.load.operating_parts)."""
    drawn = _as_drawn(scene)
    out: list[Finding] = []
    out += _clearance(drawn)
    out += _lands(drawn)
    out += _cage_fit(drawn)
    out += _resources(scene)
    out += _plausibility(drawn)
    from .named_materials import overheated_materials

    out += [warning(key, message) for key, message in overheated_materials(scene)]
    return out


def geometry_findings(scene) -> list[Finding]:
    """The geometry checks of `scene_findings` on the parts as the scene holds them (clearance,
    lands, cage fit): what a tolerance stack must pass (pipeline.scene.tolerance_stacks)."""
    return _clearance(scene) + _lands(scene) + _cage_fit(scene)


def _as_drawn(scene):
    """The scene: its bearing, cage and materials are as drawn (`operating` holds them grown)."""
    return scene


def _form2(scene) -> bool:
    table = scene.raw.get("bearing", {})
    return isinstance(table, dict) and "pitch_diameter" in table


def _land_angle(b, ring: str, side: int) -> float | None:
    """Angle from the radial plane at which `ring`'s groove meets its land on `side` [rad]
    (None: no land given); the formula of dynamics/quasistatic/solver.py (_shoulder_angle)."""
    land = b.shoulder(ring, side)
    if land is None:
        return None
    if ring == "inner":
        depth, r = 0.5 * b.inner_groove_center_diameter - 0.5 * land, b.inner_groove_radius
    else:
        depth, r = 0.5 * land - 0.5 * b.outer_groove_center_diameter, b.outer_groove_radius
    return math.acos(max(-1.0, min(1.0, depth / r)))


def _side_text(b, ring: str, side: int) -> str:
    """'' for a ring with one shoulder diameter, else ', its side toward +z' (or -z)."""
    pair = b.shoulders(ring)
    if pair is None or pair[0] == pair[1]:
        return ""
    return f", {SIDE_NAMES[0 if side > 0 else 1]}"


def _loaded_sides(scene, ring: str) -> tuple[int, ...]:
    """The sides of `ring`'s groove the axial load presses the balls onto (both without one)."""
    axial = scene.load.axial if getattr(scene, "load", None) is not None else 0.0
    if axial == 0.0:
        return SIDES
    return (contact_side(ring, 1.0 if axial > 0.0 else -1.0),)


def _clearance(scene) -> list[Finding]:
    """cos alpha_0 = 1 - P_d / (2 A) (docs/model.md §2): P_d = 2A puts the free contact at
    90° (the ball no longer held radially); the lands, when given, come earlier: for each ring,
    the land on the side the axial load presses the balls onto (the more permissive side
    without an axial load)."""
    b = scene.bearing
    A, play = b.curvature_center_distance, b.diametral_clearance
    limit_angle, why = math.pi / 2, "90° (the groove no longer holds the ball radially)"
    for ring in ("inner", "outer"):
        angles = [(theta, side) for side in _loaded_sides(scene, ring)
                  if (theta := _land_angle(b, ring, side)) is not None]
        if not angles:
            continue
        theta, side = max(angles)
        if theta < limit_angle:
            limit_angle = theta
            why = (f"the {ring} land at {math.degrees(theta):.1f}° (bearing.{ring}_shoulder_diameter"
                   f"{_side_text(b, ring, side)})")
    limit = 2.0 * A * (1.0 - math.cos(limit_angle))
    if play < limit:
        return []
    angle = math.degrees(b.free_contact_angle)
    if _form2(scene):
        key, value = "bearing.diametral_clearance", f"{_g(play)} m"
    else:
        key = "bearing.outer_groove_center_diameter"
        value = (f"{_g(b.outer_groove_center_diameter)} m with inner_groove_center_diameter = "
                 f"{_g(b.inner_groove_center_diameter)} m gives a diametral clearance of {_g(play)} m")
    return [error(key, f"{value}: the free contact angle acos(1 - P_d / 2A) would be {angle:.1f}°, beyond "
                       f"{why}, with A = r_i + r_o - D = {_g(A)} m; allowed: diametral clearance "
                       f"< {_g(limit)} m [m]")]


def _lands(scene) -> list[Finding]:
    """A land must lie between its groove's bottom and the pitch circle, on either side."""
    b, out = scene.bearing, []
    ranges = {"inner": (b.inner_groove_bottom_diameter, b.pitch_diameter, "the inner groove bottom",
                        "the pitch diameter"),
              "outer": (b.pitch_diameter, b.outer_groove_bottom_diameter, "the pitch diameter",
                        "the outer groove bottom")}
    for ring, (lo, hi, lo_name, hi_name) in ranges.items():
        pair = b.shoulders(ring)
        if pair is None:
            continue
        for side, d in zip(SIDES, pair):
            if not lo < d < hi:
                out.append(error(f"bearing.{ring}_shoulder_diameter",
                                 f"{_g(d)} m{_side_text(b, ring, side)} is not on the {ring} ring's land: allowed "
                                 f"between {lo_name} {_g(lo)} m and {hi_name} {_g(hi)} m [m]"))
                break
    return out


def _cage_fit(scene) -> list[Finding]:
    """The cage sits between the rings' lands and its pockets hold the balls on the pitch
    circle: inner land < bore < d_m < outside < outer land."""
    c, b = scene.cage, scene.bearing
    if c is None:
        return []
    out = []
    ring = c.guide_ring
    if ring is not None and b.shoulders(ring) is None:
        out.append(error(f"bearing.{ring}_shoulder_diameter",
                         f"required with a cage guided by the {ring} ring (cage.guidance = {ring!r}): the "
                         f"diameter of the land the cage runs on [m]"))
    inner, outer = b.shoulders("inner"), b.shoulders("outer")
    inner_land = max(inner) if inner is not None else b.inner_groove_bottom_diameter
    outer_land = min(outer) if outer is not None else b.outer_groove_bottom_diameter
    d_m, t = b.pitch_diameter, c.radial_thickness
    lo, hi = max(d_m - t, inner_land + t), min(d_m + t, outer_land - t)
    fits = c.bore_diameter > inner_land and c.outside_diameter < outer_land and abs(c.mean_diameter - d_m) < t
    if not fits:
        where = ("outside the bearing" if c.outside_diameter >= outer_land or c.bore_diameter <= inner_land
                 else "off the pitch circle")
        allowed = (f"{_g(lo)} m < mean_diameter < {_g(hi)} m with radial_thickness = {_g(t)} m"
                   if lo < hi else f"none with radial_thickness = {_g(t)} m: reduce cage.radial_thickness")
        out.append(error("cage.mean_diameter",
                         f"{_g(c.mean_diameter)} m puts the cage {where}: its bore {_g(c.bore_diameter)} m and "
                         f"outside {_g(c.outside_diameter)} m must lie between the inner land {_g(inner_land)} m "
                         f"and the outer land {_g(outer_land)} m, with the pitch circle d_m = {_g(d_m)} m through "
                         f"the pockets; allowed: {allowed} [m]"))
    if b.width is not None and c.width > b.width:
        out.append(warning("cage.width", f"{_g(c.width)} m is wider than the rings (bearing.width = "
                                         f"{_g(b.width)} m) [m]"))
    return out


def sample_count(scene) -> int:
    """Samples the dynamic run allocates: floor(duration / sample_interval) + 2."""
    ratio = scene.solver.duration / scene.output.sample_interval
    return int(min(ratio, 1e18)) + 2


def sample_bytes(scene) -> float:
    Z = scene.bearing.ball_count
    n_dof = 6 * Z + 6 + (6 if scene.cage is not None else 0)
    doubles = 2 + 2 * n_dof + 16 + 15 * Z
    return 8.0 * doubles * SAMPLE_COPIES


def memory_limit() -> float:
    """What the dynamic run may allocate [bytes]: half the machine's physical memory (8 GiB
    where it cannot be read), and no more than the process's address-space limit (ulimit -v,
    RLIMIT_AS) leaves beyond what the process maps already."""
    try:
        limit = 0.5 * os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")
    except (ValueError, OSError, AttributeError):
        limit = 8.0 * 2**30
    address_space = _address_space_left()
    return limit if address_space is None else min(limit, address_space)


def _address_space_left() -> float | None:
    """RLIMIT_AS minus the process's mapped size (VmSize) [bytes]; None without a limit."""
    try:
        import resource

        soft = resource.getrlimit(resource.RLIMIT_AS)[0]
    except (ImportError, OSError, ValueError, AttributeError):  # not POSIX
        return None
    if soft == resource.RLIM_INFINITY or soft <= 0:
        return None
    mapped = 0.0
    try:
        with open("/proc/self/status", encoding="ascii") as fh:
            for line in fh:
                if line.startswith("VmSize:"):
                    mapped = float(line.split()[1]) * 1024.0
    except (OSError, ValueError):
        pass
    return max(float(soft) - mapped, 0.0)


def _resources(scene) -> list[Finding]:
    """What the dynamic run would allocate and how long it would step, before it starts."""
    s, o, out = scene.solver, scene.output, []
    ratio = s.duration / o.sample_interval
    if ratio < MIN_SAMPLES:
        out.append(error("output.sample_interval",
                         f"{_g(o.sample_interval)} s gives {int(ratio)} samples in solver.duration = "
                         f"{_g(s.duration)} s; the time averages of summary.json (last half of the run) need "
                         f"at least {MIN_SAMPLES // 2} samples there; allowed <= duration / {MIN_SAMPLES} = "
                         f"{_g(s.duration / MIN_SAMPLES)} [s]"))
    steps = s.duration / s.max_step
    if steps > MAX_STEPS:
        out.append(error("solver.duration",
                         f"{_g(s.duration)} s needs at least {_g(steps)} steps of solver.max_step = {_g(s.max_step)} s "
                         f"(days of computing); allowed <= {_g(MAX_STEPS * s.max_step)} s at this max_step [s]"))
    else:
        hours = steps * STEP_WALL_TIME_PER_BALL * scene.bearing.ball_count / 3600.0
        if hours > 1.0:
            out.append(warning("solver.duration",
                               f"{_g(s.duration)} s is at least {_g(steps)} steps: expect {hours:.3g} h or more "
                               f"of computing for the dynamic run [s]"))
    need = sample_bytes(scene) * min(ratio, 1e30)
    limit = memory_limit()
    if need > limit:
        per = sample_bytes(scene)
        out.append(error("output.sample_interval",
                         f"{_g(o.sample_interval)} s over solver.duration = {_g(s.duration)} s is {_g(ratio)} samples "
                         f"of the time series, about {need / 2**30:.3g} GiB of memory (this process may use "
                         f"{limit / 2**30:.3g} GiB: half the machine's memory, or what its address-space limit, "
                         f"ulimit -v, leaves); allowed >= {_g(s.duration * per / limit)} [s], or a shorter "
                         f"solver.duration"))
    return out


def _plausibility(scene) -> list[Finding]:
    """Values that look like the wrong unit (scene files are SI: m, N, N.m, Pa, kg/m^3)."""
    b, out = scene.bearing, []
    if b.ball_diameter >= 0.2:  # the largest rolling-bearing balls are about 0.1 m; 0.5 in is 0.0127 m
        out.append(warning("bearing.ball_diameter",
                           f"{_g(b.ball_diameter)} m is a ball of {b.ball_diameter:.3g} metres (mass "
                           f"{_g(b.ball_mass(scene.materials.ball))} kg): scene lengths are in metres; did you "
                           f"write millimetres or inches? (12.7 mm = 0.5 in is 0.0127) [m]"))
    elif b.ball_diameter < 1e-4:
        out.append(warning("bearing.ball_diameter",
                           f"{_g(b.ball_diameter)} m is a ball of {b.ball_diameter * 1e6:.3g} µm: scene lengths "
                           f"are in metres [m]"))
    if scene.load.axial < 0.0:
        out.append(warning("load.axial", f"{_g(scene.load.axial)} N is a thrust along -z: the model's rings are "
                                         "symmetric about their mid-plane, so the other flanks of the grooves "
                                         "carry it and the result is the mirror image of +z; a one-sided "
                                         "angular-contact bearing carries thrust one way only: check the sign [N]"))
    if scene.cage is not None and scene.cage.mean_diameter > 5.0:
        out.append(warning("cage.mean_diameter", f"{_g(scene.cage.mean_diameter)} m: scene lengths are in metres [m]"))
    for name in ("ball", "race", "cage"):
        m = getattr(scene.materials, name)
        if m is None:
            continue
        out += _unit_slips(f"materials.{name}", m, (
            ("youngs_modulus", 1e9, 1.5e12, "Pa", "steel: 2.08e11 Pa", "Pa, not GPa or MPa"),
            ("density", 10.0, 25000.0, "kg/m^3", "steel: 7850", "kg/m^3, not g/cm^3")))
    out += _load_plausibility(scene)
    out += _sub_nanometre(scene)
    ndm = max(abs(scene.speed.inner_rpm), abs(scene.speed.outer_rpm)) * b.pitch_diameter * 1e3
    if ndm > 4e6:
        out.append(warning("speed.inner_rpm" if abs(scene.speed.inner_rpm) >= abs(scene.speed.outer_rpm)
                           else "speed.outer_rpm",
                           f"speed x pitch diameter n d_m = {_g(ndm)} mm/min is beyond the ~3e6 of the fastest "
                           f"ball bearings; the unit is rev/min [rev/min]"))
    lub = scene.lubricant
    if lub is not None and getattr(lub, "temperature_degC", None) is not None and lub.temperature_degC > 250.0:
        out.append(warning("lubricant.temperature_degC",
                           f"{_g(lub.temperature_degC)} degC is hotter than any bearing oil survives; the unit is "
                           f"degC, not K [degC]"))
    out += _lubricant_plausibility(scene)
    return out


# A length of a solid part below this is smaller than a few atoms (steel's lattice spacing is
# 0.29 nm): no width, diameter, radius or roughness of a bearing, most likely a unit slip.
SMALLEST_PART_LENGTH = 1e-9  # m


def _sub_nanometre(scene) -> list[Finding]:
    """Warnings for [bearing] and [cage] lengths (the positive ones: sizes, not clearances or
    run-outs) below SMALLEST_PART_LENGTH."""
    out = []
    for section, obj in (("bearing", scene.bearing), ("cage", scene.cage)):
        if obj is None:
            continue
        for f in dataclasses.fields(obj):
            value = getattr(obj, f.name)
            if (f.metadata.get("unit") == "m" and "gt" in f.metadata and isinstance(value, float)
                    and 0.0 < value < SMALLEST_PART_LENGTH):
                out.append(warning(f"{section}.{f.name}", f"{_g(value)} m is smaller than a few atoms (below "
                                                          f"{SMALLEST_PART_LENGTH:g} m): scene lengths are in metres [m]"))
    return out


def _lubricant_plausibility(scene) -> list[Finding]:
    """Film and lubricant values a unit slip puts decades away (m for µm, Pa for MPa, kg/m^3
    for g/cm^3, Pa s for mPa s): the verdict moves with them and nothing else would say so."""
    out = []
    floor = scene.physics.min_film
    if not 1e-10 <= floor <= 1e-6:  # EHD films of bearings run 0.05-1 µm; the floor stands below them
        out.append(warning("physics.min_film",
                           f"{_g(floor)} m is a film floor of {floor * 1e6:.3g} µm, outside 1e-10 .. 1e-6 m: "
                           f"traction uses no thinner film than this, and bearing films are 0.05-1 µm; the "
                           f"unit is m, not µm [m]"))
    lub = scene.lubricant
    if lub is None:
        return out
    return out + _unit_slips("lubricant", lub, (
        ("eyring_stress", 1e5, 1e8, "Pa", "esters: 2e6 .. 1e7 Pa", "Pa, not MPa"),
        ("density", 500.0, 2000.0, "kg/m^3", "oils: 800 .. 1100 kg/m^3", "kg/m^3, not g/cm^3"),
        ("ambient_viscosity", 1e-4, 10.0, "Pa s", "oils at 40 degC: 0.005 .. 0.5 Pa s", "Pa s, not mPa s or cP"),
        ("pressure_viscosity_coefficient", 1e-10, 1e-7, "1/Pa", "oils: 1e-8 .. 3e-8 1/Pa", "1/Pa, not 1/GPa"),
        ("elastic_shear_modulus", 1e7, 1e11, "Pa", "oils at 1-2 GPa: measured 0.1 .. 1 GPa", "Pa, not GPa")))


def _unit_slips(section: str, values, checks) -> list[Finding]:
    """A warning for each (name, low, high, unit, typical, slip) of `checks` whose value in
    `values` is given and lies outside [low, high]: most likely typed in another unit."""
    def bound(x: float) -> str:  # 1e9, 1.5e12, 25000: as a person writes them
        return f"{x:g}".replace("e+0", "e").replace("e+", "e").replace("e-0", "e-")

    out = []
    for name, low, high, unit, typical, slip in checks:
        value = getattr(values, name, None)
        if value is not None and not low <= value <= high:
            out.append(warning(f"{section}.{name}", f"{_g(value)} {unit} is outside {bound(low)} .. {bound(high)} "
                                                    f"{unit} ({typical}); the unit is {slip} [{unit}]"))
    return out


def static_capacity(scene) -> float:
    """ISO 76 basic static load rating C_0r = f_0 Z D^2 cos(alpha) [N] with f_0 = 14.7 N/mm^2
    (ISO 76:2006 Table 2 range 12-17 for radial ball bearings; a mid value): only a scale
    for the unit-plausibility check, never a result."""
    b = scene.bearing
    return 14.7e6 * b.ball_count * b.ball_diameter**2 * max(math.cos(b.free_contact_angle), 0.2)


def _load_plausibility(scene) -> list[Finding]:
    c0, out = static_capacity(scene), []
    arm = 0.5 * scene.bearing.pitch_diameter
    for key, value, unit, force in (("load.radial", scene.load.radial, "N", abs(scene.load.radial)),
                                    ("load.axial", scene.load.axial, "N", abs(scene.load.axial)),
                                    ("load.moment", scene.load.moment, "N.m", abs(scene.load.moment) / arm)):
        if force > 10.0 * c0:
            out.append(warning(key, f"{_g(value)} {unit} is more than 10 times the bearing's static load rating "
                                    f"(ISO 76, about {_g(c0)} N{' at the pitch radius' if unit == 'N.m' else ''}): "
                                    f"loads are in N and N.m, not N.mm [{unit}]"))
    return out


def run_findings(scene, stages: set[str]) -> list[Finding]:
    """What the stages about to run cannot do with this scene (checked before any runs)."""
    out: list[Finding] = []
    if "simulate" in stages:
        out += _dynamics_findings(scene)
    return out


def _dynamics_findings(scene) -> list[Finding]:
    b, out = scene.bearing, []
    missing = [f"bearing.{k}" for k in ("inner_bore_diameter", "inner_shoulder_diameter", "width")
               if getattr(b, k) is None]
    if missing:
        also = f" (as are {', '.join(missing[1:])})" if len(missing) > 1 else ""
        out.append(error(missing[0], f"required by the dynamic stage for the inner ring's mass and inertia{also} "
                                     f"[m]; give it in [bearing], or run only the quasi-static stage, which "
                                     f"needs none of them (bearingsim quasistatic; stages=['quasistatic'] in Python)"))
    out += _land_overlap(scene)
    if scene.physics.ehd_film and scene.lubricant is None:  # refused by stages.simulate.check_dynamic_physics
        out.append(error("physics.ehd_film", "true needs a [lubricant] table (the film's viscosity); give one, or "
                                             "remove the key (without a lubricant the film is off)"))
    if not scene.physics.centrifugal:
        out.append(error("physics.centrifugal",
                         "false acts only on the quasi-static solve: the dynamic model's inertia always carries "
                         "the balls' centrifugal force; remove the key (or set it true) to run the dynamics"))
    return out


def _land_overlap(scene) -> list[Finding]:
    """The cage-land journal needs a length: the cage must be wider than the guiding groove
    where it meets the land, as drawn and at the operating temperatures."""
    if (scene.cage is None or scene.cage.guide_ring is None or scene.cage.land_length is not None
            or scene.physics.cage_race == "none"):
        return []
    drawn = _as_drawn(scene)
    ring = drawn.cage.guide_ring
    key = f"bearing.{ring}_shoulder_diameter"
    for parts, when in ((drawn, ""), (scene.operating, " at the operating temperatures ([thermal])")):
        c, b = parts.cage, parts.bearing
        if b.shoulders(ring) is None:
            return []  # the land itself is missing: _cage_fit says so
        if c.guide_land_length(b) > 0.0:
            continue
        side = c.guide_sides(b)[0]
        opening = c.groove_opening_at_land(b, side)
        return [error("cage.width", f"{_g(drawn.cage.width)} m does not reach the {ring} ring's guiding land"
                                    f"{when}: the groove is {_g(opening)} m wide where it meets the land "
                                    f"({key}{_side_text(b, ring, side)}) and the cage {_g(c.width)} m, so the "
                                    f"cage-land journal would have no length; allowed: wider than the groove "
                                    f"there, or give cage.land_length [m]")]
    return []


__all__ = ["Finding", "ValidityError", "raise_errors", "scene_findings", "run_findings"]
