"""Where the start-up transient of a dynamic run ends: the *settled window* of the summary.

A dynamic run starts from the quasi-static equilibrium, with the cage centred in its guide
clearance at the epicyclic speed. The cage then falls onto its land, often with a start-up
crash (metal contact, impacts), and settles into a regime: pressed on one sector, whirling,
floating. Statistics of the whole run, or of a fixed fraction of it, mix the two; a burn zone
accumulated over the whole run can be nothing but the start-up crash. The rule below finds
the end of the start-up from the saved series alone, so the same run always gives the same
window.

Rule (`detect_settled_window`):

1. **Blocks.** The run is cut into consecutive blocks of length
   ``tau = min(block_revolutions * T_c, duration / min_blocks)``, ``T_c = 2 pi / |mean cage
   speed over the last half|`` the cage revolution period (default half a revolution, i.e.
   Z/2 ball passes: every block averages the ball-pass excitation, the fastest forcing of
   the cage, yet a run of 10-20 cage revolutions still has 20-40 blocks; a run too short
   for 12 such blocks gets 12 shorter ones, and a warning below).
2. **Block statistics.** Per block (time-weighted): mean and standard deviation of the
   eccentricity ratio eps, the largest eps, and the mean cage centre (x, y) / C. The mean eps
   and the centre say *where* the cage runs, the spread of eps *how violently*: a start-up
   crash shows as a large spread even where its mean happens to match the regime. The largest
   eps says *how close* the cage came to its land. The verdict's extremes (thinnest film,
   metal contact) read it, and a single late touch of the land hardly moves a block's mean or
   spread. Case b with a 9 x 18/22/28 traction rule had one at t = 0.074 s (eps 1.001, 14 µm
   of film, metal contact) in blocks whose mean and spread lay in the band of a slowly
   drifting regime. A window that started at one revolution reported that touch as the
   settled regime's thinnest film.
3. **Reference.** The blocks of the last half of the run are the regime. Each statistic of
   a block must lie within ``band_sigmas`` (3) standard deviations of the reference blocks'
   values around their mean (the centre: within 3 RMS distances of the mean centre), or
   within an absolute tolerance (0.02 in eps, 0.02 C for the centre) when the reference is
   steadier than that. Three standard deviations: a block of the regime falls outside with
   a probability of a few per mille for normal scatter, so a block outside is evidence of
   transient, while the band stays generous when only 6-20 reference blocks estimate it;
   the tolerances keep a perfectly steady end (zero scatter) from rejecting round-off.
4. **End of the start-up** = the start of the first block after which every block of the
   first half lies within the bands ("the block means stay within the spread of the final
   blocks"), with a floor of ``min_startup_revolutions`` (1) cage revolution — the cage
   starts centred and needs at least one revolution, every pocket passing the loaded zone
   once, before a statistic describes anything but its fall onto the land — and a cap at
   half the run, so that the statistics always use at least half of it.

Warnings (strings for `summary.json` `warnings`): a settled window shorter than
``min_settled_revolutions`` (10) cage revolutions (too short to settle: its statistics
describe a transient, not a regime); a start-up that never ended in the first half (the
window is the last half by the cap, and may still hold transient); a cage that does not
rotate (blocks then split the run in 12, without revolutions).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np


def time_weights(t: np.ndarray) -> np.ndarray:
    """Trapezoidal quadrature weights of samples at times `t` (sum = t[-1] - t[0])."""
    t = np.asarray(t, dtype=float)
    if t.size < 2:
        return np.ones_like(t)
    w = np.zeros_like(t)
    dt = np.diff(t)
    w[:-1] += 0.5 * dt
    w[1:] += 0.5 * dt
    return w


BLOCK_REVOLUTIONS = 0.5  # block length [cage revolutions]
MIN_BLOCKS = 12  # at least this many blocks in a run (6 reference blocks)
BAND_SIGMAS = 3.0  # half-width of the reference band [standard deviations]
EPS_TOLERANCE = 0.02  # smallest half-width of the eps bands [-]
CENTRE_TOLERANCE = 0.02  # smallest radius of the centre band [C]
MIN_STARTUP_REVOLUTIONS = 1.0  # floor of the start-up [cage revolutions]
MIN_SETTLED_REVOLUTIONS = 10.0  # shorter settled windows are flagged [cage revolutions]


@dataclass(frozen=True)
class SettledWindow:
    """The settled part [start, end] of a run [s] and how it was found."""

    start: float  # end of the start-up transient [s]
    end: float  # end of the run [s]
    block: float  # block length [s]
    revolution: float  # cage revolution period T_c [s] (inf: the cage does not rotate)
    limited_by: tuple[str, ...]  # what set `start`: statistics out of band, "floor", "cap"
    warnings: tuple[str, ...] = ()

    @property
    def revolutions(self) -> float:
        """Cage revolutions in the settled window."""
        return (self.end - self.start) / self.revolution if math.isfinite(self.revolution) else 0.0

    def mask(self, t: np.ndarray) -> np.ndarray:
        return np.asarray(t, dtype=float) >= self.start


def _block_means(k: np.ndarray, w: np.ndarray, values: np.ndarray, n: int) -> np.ndarray:
    total = np.bincount(k, weights=w, minlength=n)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.bincount(k, weights=w * values, minlength=n) / total


def _band_violations(stat: np.ndarray, ref: np.ndarray, tolerance: float, sigmas: float) -> np.ndarray:
    """True where a block's statistic lies outside mean(ref) ± max(sigmas sd(ref), tolerance)."""
    ref = ref[np.isfinite(ref)]
    if ref.size == 0:
        return np.zeros(stat.shape, dtype=bool)
    sd = float(np.std(ref, ddof=1)) if ref.size > 1 else 0.0
    half = max(sigmas * sd, tolerance)
    return np.isfinite(stat) & (np.abs(stat - float(np.mean(ref))) > half)


def detect_settled_window(
    t: np.ndarray,
    eccentricity_ratio: np.ndarray,
    cage_xy: np.ndarray,
    cage_speed: np.ndarray,
    guide_clearance: float | None = None,
    *,
    block_revolutions: float = BLOCK_REVOLUTIONS,
    min_blocks: int = MIN_BLOCKS,
    band_sigmas: float = BAND_SIGMAS,
    eps_tolerance: float = EPS_TOLERANCE,
    centre_tolerance: float = CENTRE_TOLERANCE,
    min_startup_revolutions: float = MIN_STARTUP_REVOLUTIONS,
    min_settled_revolutions: float = MIN_SETTLED_REVOLUTIONS,
) -> SettledWindow:
    """The settled window of a run from its cage series (rule in the module docstring).

    `t` [s], `eccentricity_ratio` eps [-], `cage_xy` (n, 2) cage centre [m], `cage_speed`
    [rad/s]; `guide_clearance` C [m] scales the centre (None: C = median |xy| / eps, which
    is the definition of eps).
    """
    t = np.asarray(t, dtype=float)
    eps = np.asarray(eccentricity_ratio, dtype=float)
    xy = np.asarray(cage_xy, dtype=float)[:, :2]
    t0, t1 = float(t[0]), float(t[-1])
    span = t1 - t0
    if t.size < 2 or span <= 0.0:
        return SettledWindow(t0, t1, 0.0, math.inf, (), ("run too short to settle: fewer than two samples",))
    half_time = t0 + 0.5 * span
    late = t >= half_time
    speed = float(np.sum(time_weights(t[late]) * np.asarray(cage_speed, dtype=float)[late])
                  / max(t[late][-1] - t[late][0], 1e-300)) if late.sum() > 1 else float(np.mean(cage_speed))
    revolution = 2.0 * math.pi / abs(speed) if math.isfinite(speed) and abs(speed) > 1e-9 else math.inf
    warnings = []
    if not math.isfinite(revolution):
        warnings.append("the cage does not rotate: the start-up is found without cage revolutions")
    block = min(block_revolutions * revolution, span / min_blocks)
    n = max(1, int(span / block + 1e-9))
    k = np.minimum(((t - t0) / block).astype(int), n - 1)
    w = time_weights(t)
    if guide_clearance is None or not guide_clearance > 0.0:
        radius = np.hypot(xy[:, 0], xy[:, 1])
        ok = eps > 1e-3
        guide_clearance = float(np.median(radius[ok] / eps[ok])) if ok.any() else 1.0
    eps_mean = _block_means(k, w, eps, n)
    eps_sd = np.sqrt(np.maximum(_block_means(k, w, eps * eps, n) - eps_mean**2, 0.0))
    cx = _block_means(k, w, xy[:, 0] / guide_clearance, n)
    cy = _block_means(k, w, xy[:, 1] / guide_clearance, n)
    starts = t0 + np.arange(n) * block
    ref = starts >= half_time - 1e-9 * span
    if ref.sum() < 2:  # cannot happen with min_blocks >= 4; keep the rule total
        ref[-2:] = True
    eps_max = np.full(n, -np.inf)
    np.maximum.at(eps_max, k, eps)
    eps_max[~np.isfinite(eps_max)] = np.nan  # a block without samples has no statistic
    out = {
        "eps mean": _band_violations(eps_mean, eps_mean[ref], eps_tolerance, band_sigmas),
        "eps spread": _band_violations(eps_sd, eps_sd[ref], eps_tolerance, band_sigmas),
        "eps max": _band_violations(eps_max, eps_max[ref], eps_tolerance, band_sigmas),
    }
    cref = np.column_stack([cx[ref], cy[ref]])
    cref = cref[np.all(np.isfinite(cref), axis=1)]
    if cref.size:
        centre = cref.mean(axis=0)
        rms = float(np.sqrt(np.mean(np.sum((cref - centre) ** 2, axis=1))))
        distance = np.hypot(cx - centre[0], cy - centre[1])
        out["cage centre"] = np.isfinite(distance) & (distance > max(band_sigmas * rms, centre_tolerance))
    bad = np.zeros(n, dtype=bool)
    for flags in out.values():
        bad |= flags
    bad &= ~ref  # the reference blocks define the regime
    limited_by: tuple[str, ...] = ()
    start = t0
    if bad.any():
        last = int(np.nonzero(bad)[0].max())
        start = float(starts[last] + block)
        limited_by = tuple(name for name, flags in out.items() if flags[last])
        if last == int(np.nonzero(~ref)[0].max()):
            warnings.append("the start-up did not end in the first half of the run: its last block before "
                            "the reference still differs from the regime, so the settled window (the last "
                            "half) may hold transient")
    floor = t0 + min_startup_revolutions * revolution if math.isfinite(revolution) else t0
    if floor > start:
        start, limited_by = floor, ("floor",)
    if start > half_time:
        start, limited_by = half_time, limited_by + ("cap",)
    window = SettledWindow(start, t1, block, revolution, limited_by)
    if math.isfinite(revolution) and window.revolutions < min_settled_revolutions:
        warnings.append(f"run too short to settle: the settled window (t >= {start:.4g} s) holds "
                        f"{window.revolutions:.1f} cage revolutions (< {min_settled_revolutions:g}); "
                        "its statistics describe a transient, not a regime")
    return SettledWindow(start, t1, block, revolution, limited_by, tuple(warnings))
