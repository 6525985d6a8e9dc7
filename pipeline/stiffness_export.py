"""Stiffness export for rotordynamics codes: the bearing's 5x5 quasi-static stiffness over a
list of inner-ring speeds, and the hinge's, as CSV (one row per speed) and JSON.

Bearing: `K` of docs/model.md (M.106), the condensed tangent of the quasi-static solve
(`QuasiStaticResult.stiffness`), at the scene's loads and outer-ring speed, each speed a fresh
solve of `pipeline.stages.quasistatic.solve` (so the scene's own speed reproduces
`quasistatic.json` exactly). Order (x, y, z, rx, ry): rows are the forces Fx, Fy, Fz and
moments Mx, My on the inner race, columns the displacements and tilts; units N/m
(force/displacement), N/rad (force/tilt), N.m/m (moment/displacement), N.m/rad. Slightly
unsymmetric (k_h depends on the contact angle). No damping: the quasi-static model has none.

Hinge: H_u (3x3) [N/m] and H_psi (2) [N.m/rad] of docs/model.md §5, from the scene
(`hinge.source = "given"`) or the FE identification (`identify/hinge.toml`); the same at
every speed. In bearingsim's model it acts in parallel with the bearing between the inner
race and ground (the inner race sees K + diag(H_u, H_psi)).

Damping: the hinge's G = c_G H (docs/model.md (M.18)) is exported with it. The bearing's is
not: the quasi-static model has none, and the dynamic model's only bearing damping is the
contact damping of (M.62), a numerical choice (a fraction of each ball's critical damping on its
Hertz stiffness, no published source) acting on the balls' own contact modes; condensed onto
the inner race it is not a constant coefficient, so it is not given as one (BEARING_DAMPING_NOTE).

ROSS (`ross.BearingElement(n, kxx, cxx, kyy=, kxy=, kyx=, kzz=, frequency=)`, ROSS 2.x):
`stiffness.json` holds its keyword arguments as numbers (`ross.bearing_element`, and
`ross.hinge_element` for the hinge), so `rs.BearingElement(n=0, **doc["ross"]["bearing_element"])`
needs nothing of bearingsim; it has no tilt terms (docs/outputs.md "ROSS"; docs/stiffness.md).
"""

from __future__ import annotations

import io
import math
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path

import numpy as np

DOFS = ("x", "y", "z", "rx", "ry")
STIFFNESS_DIR = "stiffness"
MAX_SPEEDS = 1000  # speeds of one `stiffness` call: each is a quasi-static solve
CSV_FILE, JSON_FILE = "stiffness.csv", "stiffness.json"
ROSS_TERMS = ("kxx", "kxy", "kyx", "kyy", "kzz")  # ROSS BearingElement's stiffness arguments
ROSS_DAMPING = ("cxx", "cxy", "cyx", "cyy", "czz")
BEARING_DAMPING_NOTE = (
    "The bearing's damping is not exported (cxx = cxy = cyx = cyy = czz = 0 in ross.bearing_element): "
    "the quasi-static model has none, and the dynamic model's contact damping (docs/model.md (M.62)) is a "
    "numerical choice, not a measured or published bearing damping; condensed onto the inner race it would "
    "depend on frequency through the balls' own modes. With it at zero every logarithmic decrement ROSS "
    "computes comes from the rest of the rotor model (and the hinge's G = c_G H, ross.hinge_element).")
SPEED_RANGE_NOTE = ("ROSS interpolates the coefficients in `frequency` and extrapolates outside it (with a "
                    "warning): export speeds that cover the whole Campbell range, e.g. `bearingsim stiffness "
                    "SCENE --speeds 0:6000:13`.")


def term_name(i: int, j: int) -> str:
    """Name of K[i, j]: kxy (force x per displacement y), kx_ry, krx_y, krx_rx, ..."""
    r, c = DOFS[i], DOFS[j]
    return f"k{r}{c}" if len(r) == 1 and len(c) == 1 else f"k{r}_{c}"


def term_unit(i: int, j: int) -> str:
    return {(False, False): "N/m", (False, True): "N/rad",
            (True, False): "N m/m", (True, True): "N m/rad"}[(i >= 3, j >= 3)]  # UDUNITS (docs/outputs.md)


TERMS = {term_name(i, j): (i, j) for i in range(5) for j in range(5)}
# CSV order: ROSS's five first, then the rest of K row by row
CSV_TERMS = ROSS_TERMS + tuple(n for n in TERMS if n not in ROSS_TERMS)


@dataclass(frozen=True)
class StiffnessTable:
    """Bearing stiffness (n, 5, 5) at `speeds_rpm` (n), plus the hinge (None without one)."""

    scene: str
    speeds_rpm: np.ndarray
    bearing: np.ndarray  # (n, 5, 5) in DOFS order
    converged: np.ndarray  # (n,) bool: the quasi-static solve converged at that speed
    cage_speed: np.ndarray  # (n,) [rad/s]
    warnings: tuple[tuple[str, ...], ...]
    operating_point: dict  # loads [N, N.m] and outer-ring speed [rev/min]
    hinge: dict | None  # {"source", "translational" (3, 3) [N/m], "bending" (2,) [N.m/rad], "damping_time" [s]}

    @property
    def speeds_rad_s(self) -> np.ndarray:
        return self.speeds_rpm * (2.0 * math.pi / 60.0)

    def at(self, speed_rpm: float) -> np.ndarray:
        """The bearing's 5x5 at a tabulated speed [rev/min]."""
        hits = np.flatnonzero(self.speeds_rpm == float(speed_rpm))
        if not len(hits):
            raise KeyError(f"{speed_rpm} rev/min is not in the table ({self.speeds_rpm.tolist()})")
        return self.bearing[hits[0]]

    def term(self, name: str) -> np.ndarray:
        """One coefficient over the speeds, e.g. term("kxy") or term("krx_rx")."""
        i, j = TERMS[name]
        return self.bearing[:, i, j]

    def ross_coefficients(self) -> dict[str, np.ndarray]:
        """Keyword arguments of `ross.BearingElement` (add `n=`): stiffness from the bearing's
        translational rows, damping zero, frequency = inner-ring speed [rad/s]."""
        zeros = np.zeros(len(self.speeds_rpm))  # no bearing damping: BEARING_DAMPING_NOTE
        return {**{t: self.term(t) for t in ROSS_TERMS}, **{c: zeros for c in ROSS_DAMPING},
                "frequency": self.speeds_rad_s}

    def ross_element_arguments(self) -> dict[str, list[float]]:
        """`ross_coefficients()` as plain lists of floats (what stiffness.json holds)."""
        ross = self.ross_coefficients()
        return {k: [float(v) for v in ross[k]] for k in (*ROSS_TERMS, *ROSS_DAMPING, "frequency")}

    def ross_hinge_arguments(self) -> dict[str, list[float]] | None:
        """Keyword arguments of a second `ross.BearingElement` for the hinge: H_u's x, y, z
        terms and their damping G_u = c_G H_u (docs/model.md (M.18)), the same at every
        speed. None without a hinge."""
        if self.hinge is None:
            return None
        H_u = np.asarray(self.hinge["translational"], float)
        c_G = float(self.hinge.get("damping_time", 0.0))
        n = len(self.speeds_rpm)
        index = {"xx": (0, 0), "xy": (0, 1), "yx": (1, 0), "yy": (1, 1), "zz": (2, 2)}
        out = {f"k{a}": [float(H_u[ij])] * n for a, ij in index.items()}
        out.update({f"c{a}": [float(c_G * H_u[ij])] * n for a, ij in index.items()})
        out["frequency"] = [float(v) for v in self.speeds_rad_s]
        return out

    def csv_text(self) -> str:
        """One row per speed; units in the header; floats in round-trip precision."""
        hinge = hinge_columns(self.hinge)
        header = ["speed [rev/min]", "speed [rad/s]", "converged [1]"]
        header += [f"{t} [{term_unit(*TERMS[t])}]" for t in CSV_TERMS]
        header += [f"{name} [{unit}]" for name, unit, _ in hinge]
        out = io.StringIO()
        out.write(",".join(header) + "\n")
        for n, rpm in enumerate(self.speeds_rpm):
            row = [repr(float(rpm)), repr(float(self.speeds_rad_s[n])), str(int(bool(self.converged[n])))]
            row += [repr(float(self.bearing[n][TERMS[t]])) for t in CSV_TERMS]
            row += [repr(float(v)) for _, _, v in hinge]
            out.write(",".join(row) + "\n")
        return out.getvalue()

    def markdown(self) -> str:
        """The main terms per speed as a markdown table (what `bearingsim stiffness` prints)."""
        terms = ("kxx", "kxy", "kyy", "kzz", "kx_ry", "krx_rx", "kry_ry")
        lines = ["| speed [rev/min] | " + " | ".join(f"{t} [{term_unit(*TERMS[t])}]" for t in terms)
                 + " | converged |", "|" + " --- |" * (len(terms) + 2)]
        for n, rpm in enumerate(self.speeds_rpm):
            values = " | ".join(f"{self.bearing[n][TERMS[t]]:.4g}" for t in terms)
            lines.append(f"| {rpm:g} | {values} | {'yes' if self.converged[n] else 'NO'} |")
        return "\n".join(lines)

    def to_json_dict(self) -> dict:
        h = self.hinge
        return {
            "scene": self.scene,
            "operating_point": self.operating_point,
            "order": list(DOFS),
            "units": {"stiffness": "rows Fx, Fy, Fz [N], Mx, My [N m]; columns x, y, z [m], rx, ry [rad]: "
                                   "N/m, N/rad, N m/m, N m/rad", "speed": "rev/min",
                      "cage_speed": "rad/s", "hinge.translational": "N/m", "hinge.bending": "N m/rad"},
            "damping": None,
            "damping_note": BEARING_DAMPING_NOTE,
            "rows": [{"speed_rpm": float(rpm), "speed_rad_s": float(self.speeds_rad_s[n]),
                      "converged": bool(self.converged[n]), "cage_speed": float(self.cage_speed[n]),
                      "stiffness": self.bearing[n].tolist(), "warnings": list(self.warnings[n])}
                     for n, rpm in enumerate(self.speeds_rpm)],
            "hinge": None if h is None else _hinge_json(h),
            "ross": {
                "bearing_element": self.ross_element_arguments(),
                "hinge_element": self.ross_hinge_arguments(),
                "units": {"k..": "N/m", "c..": "N s/m", "frequency": "rad/s (inner-ring speed)"},
                "usage": "rs.BearingElement(n=NODE, **doc['ross']['bearing_element']); the hinge (mounting "
                         "stiffness and its damping G = c_G H) as a second element, unless the rotor model has "
                         "its own shaft and housing: rs.BearingElement(n=NODE, **doc['ross']['hinge_element'])",
                "damping_note": BEARING_DAMPING_NOTE,
                "speed_range_rpm": [float(self.speeds_rpm.min()), float(self.speeds_rpm.max())],
                "speed_range_note": SPEED_RANGE_NOTE,
                "not_representable": "tilt rows/columns (rx, ry) and the x-z, y-z couplings",
            },
        }


def _hinge_json(h: dict) -> dict:
    """The hinge block of stiffness.json: H_u, H_psi, c_G and the damping G = c_G H."""
    c_G = float(h.get("damping_time", 0.0))
    H_u, H_psi = np.asarray(h["translational"], float), np.asarray(h["bending"], float)
    return {"source": h["source"], "translational": H_u.tolist(), "bending": H_psi.tolist(),
            "damping_time": c_G, "damping_translational": (c_G * H_u).tolist(),
            "damping_bending": (c_G * H_psi).tolist(),
            "units": {"damping_time": "s", "damping_translational": "N s/m", "damping_bending": "N m s/rad"},
            "relation": "parallel to the bearing between inner race and ground (docs/model.md §5); "
                        "damping G = c_G H (docs/model.md (M.18))"}


def hinge_columns(hinge: dict | None) -> list[tuple[str, str, float]]:
    """(name, unit, value) of the hinge's CSV columns: H_u row by row, then H_psi."""
    if hinge is None:
        return []
    H_u, H_psi = np.asarray(hinge["translational"], float), np.asarray(hinge["bending"], float)
    cols = [(f"hinge_k{DOFS[i]}{DOFS[j]}", "N/m", H_u[i, j]) for i in range(3) for j in range(3)]
    return cols + [("hinge_krx_rx", "N m/rad", H_psi[0]), ("hinge_kry_ry", "N m/rad", H_psi[1])]


def hinge_of(scene, identify_dir: Path | None) -> dict | None:
    """The hinge the dynamic stage uses (`stages.simulate.hinge_matrices`), or None."""
    from .scene.schema import SceneError
    from .stages.identify import HINGE_FILE
    from .stages.simulate import hinge_matrices

    if scene.hinge.source == "fe" and (identify_dir is None or not (Path(identify_dir) / HINGE_FILE).is_file()):
        raise SceneError("hinge.source", f"'fe' needs the identified hinge ({identify_dir}/{HINGE_FILE}); run "
                                         "the identify stage first (export_stiffness(scene, run_dir) does)")
    matrices = hinge_matrices(scene, Path(identify_dir) if identify_dir is not None else None)
    if matrices is None:
        return None
    H_u, H_psi, c_G = matrices
    return {"source": scene.hinge.source, "translational": np.asarray(H_u, float), "bending": np.asarray(H_psi, float),
            "damping_time": float(c_G)}


def check_speeds(speeds_rpm: Iterable[float] | float | None, scene) -> np.ndarray:
    from .scene.schema import SceneError

    if speeds_rpm is None:
        return np.array([scene.speed.inner_rpm], dtype=float)
    values = [speeds_rpm] if np.isscalar(speeds_rpm) else list(speeds_rpm)
    try:
        speeds = np.array(values, dtype=float)
    except (TypeError, ValueError):
        raise SceneError("speeds", f"expected inner-ring speeds in rev/min, got {values!r}") from None
    if speeds.ndim != 1 or not len(speeds) or not np.all(np.isfinite(speeds)):
        raise SceneError("speeds", f"expected one or more finite inner-ring speeds [rev/min], got {values!r}")
    return speeds


def stiffness_table(scene, speeds_rpm: Iterable[float] | float | None = None, *,
                    identify_dir: Path | None = None) -> StiffnessTable:
    """Solve the quasi-static equilibrium of `scene` at each inner-ring speed [rev/min]
    [default: the scene's `speed.inner_rpm`] and tabulate the bearing's 5x5 stiffness with
    the hinge. `identify_dir`: the finished identify stage (needed for hinge.source = "fe")."""
    from .scene.load import apply_overrides, resolve
    from .stages.quasistatic import solve

    speeds = check_speeds(speeds_rpm, scene)
    hinge = hinge_of(scene, identify_dir)
    results, notes = [], []
    for rpm in speeds:
        at_speed = scene if rpm == scene.speed.inner_rpm else \
            resolve(apply_overrides(scene.raw, [f"speed.inner_rpm={float(rpm)!r}"]), f"the scene at {rpm:g} rev/min")
        try:
            result = solve(at_speed)
        except RuntimeError as exc:  # QuasiStaticError: say at which speed of the list
            raise type(exc)(f"at {rpm:g} rev/min (speed.inner_rpm): {exc}") from exc
        results.append(result)
        notes.append(tuple(result.warnings) + _validity_warnings(at_speed, result, rpm))
    load = scene.load
    return StiffnessTable(
        scene=scene.name, speeds_rpm=speeds,
        bearing=np.array([np.asarray(r.stiffness, dtype=float) for r in results]).reshape(-1, 5, 5),
        converged=np.array([bool(r.converged) for r in results]),
        cage_speed=np.array([float(r.cage_speed) for r in results]),
        warnings=tuple(notes),
        operating_point={"axial_N": load.axial, "radial_N": load.radial, "moment_Nm": load.moment,
                         "outer_rpm": scene.speed.outer_rpm},
        hinge=hinge)


def _validity_warnings(scene, result, rpm: float) -> tuple[str, ...]:
    """The quasistatic stage's own result checks (pipeline.scene.validity): an error (e.g. a contact
    angle past the land at this speed) raises, naming the speed; warnings are returned."""
    from .scene.schema import SceneError
    from .staging.result_checks import quasistatic_findings

    findings = quasistatic_findings(scene, result.to_json_dict())
    errors = [f for f in findings if f.level == "error"]
    if errors:
        raise SceneError("speeds", f"at {rpm:g} rev/min the quasi-static result is outside the model's "
                                   f"validity: {errors[0].text}")
    return tuple(f.text for f in findings)


def write_stiffness_table(table: StiffnessTable, out_dir: Path, inputs: dict | None = None) -> dict[str, Path]:
    """`stiffness.csv` and `stiffness.json` into `out_dir`, replaced together atomically, with
    a `stage.json` manifest like a stage's (so bearingsim may replace the folder later)."""
    import time

    from .staging.artefacts import (MANIFEST, atomic_write_json, atomic_write_text, input_key, stage_files,
                            staged_directory)
    from .staging.provenance import package_version

    out_dir = Path(out_dir)
    inputs = inputs if inputs is not None else {"scene": table.scene}
    with staged_directory(out_dir) as tmp:
        atomic_write_text(tmp / CSV_FILE, table.csv_text())
        atomic_write_json(tmp / JSON_FILE, table.to_json_dict())
        atomic_write_json(tmp / MANIFEST, {
            "stage": STIFFNESS_DIR, "status": "done", "key": input_key(STIFFNESS_DIR, inputs, package_version()),
            "inputs": inputs, "finished": time.strftime("%Y-%m-%dT%H:%M:%S%z"), "files": stage_files(tmp)})
    return {"csv": out_dir / CSV_FILE, "json": out_dir / JSON_FILE}


def table_inputs(scene, table: StiffnessTable) -> dict:
    """What the table depends on: the quasi-static stage's inputs, the speeds, the hinge."""
    from .stages.quasistatic import quasistatic_inputs

    h = table.hinge
    return {"quasistatic": quasistatic_inputs(scene), "speeds_rpm": table.speeds_rpm.tolist(),
            "hinge": None if h is None else {"source": h["source"], "translational": np.asarray(h["translational"]).tolist(),
                                             "bending": np.asarray(h["bending"]).tolist()}}


def parse_speeds(text: str) -> list[float]:
    """Command-line speeds: `1000,3060,6000` or `start:stop:count` (as `--vary`) [rev/min]."""
    from .scene.schema import SceneError
    from .scene.sweep_section import parse_values

    values = parse_values("speeds", text, "--speeds")
    if len(values) > MAX_SPEEDS:
        raise SceneError("--speeds", f"{len(values)} speeds; at most {MAX_SPEEDS} per call (each is a "
                                     f"quasi-static solve): give fewer, e.g. 0:20000:41 [rev/min]")
    try:
        return [float(v) for v in values]
    except (TypeError, ValueError):
        raise SceneError("--speeds", f"expected numbers [rev/min] (a,b,c or start:stop:count), got {text!r}") from None
