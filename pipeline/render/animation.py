"""An animation of the cage with the balls in their pockets, from the saved time series.

Two panels per frame: on the left the bearing seen along its axis at true scale (pitch
circle, the cage's pockets turning with the cage angle, each ball drawn at its pocket's
azimuth plus its lead or lag in the pocket, magnified so that a clearance of a millimetre is
seen on a ring of 160 mm); on the right the cage centre's orbit [µm] inside the guide clearance,
its trail up to the frame. The frames cover the last cage revolutions of the run (the settled
motion), evenly in time. GIF through Pillow (matplotlib's PillowWriter, no ffmpeg needed);
MP4 when ffmpeg is installed.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

ANIMATION_DIR = "animation"  # <run>/animation/, apart from the report stage's folder
LEAD_GAIN = 10.0  # a ball's lead or lag in its pocket, drawn this many times its size
REVOLUTIONS = 2.0  # cage revolutions the animation covers, at the end of the run


def _frame_indices(t: np.ndarray, angle: np.ndarray, frames: int) -> np.ndarray:
    """`frames` sample indices, evenly in time over the last REVOLUTIONS cage revolutions."""
    turned = np.abs(angle - angle[-1])
    inside = np.nonzero(turned <= REVOLUTIONS * 2 * math.pi)[0]
    first = int(inside[0]) if inside.size else 0
    times = np.linspace(t[first], t[-1], frames)
    return np.unique(np.clip(np.searchsorted(t, times), 0, t.size - 1))


def _cage_angle(t: np.ndarray, speed: np.ndarray) -> np.ndarray:
    """The cage's angle [rad] from its speed (trapezoidal), 0 at the start."""
    steps = 0.5 * (speed[1:] + speed[:-1]) * np.diff(t)
    return np.r_[0.0, np.cumsum(steps)]


def write_cage_animation(scene, simulate_dir: Path, path: Path, frames: int = 120, fps: int = 15) -> Path:
    """Write the animation to `path` (.gif or .mp4) and return it; ValueError for another
    suffix, for an .mp4 without ffmpeg, or a run without a cage."""
    import h5py
    from matplotlib import animation

    from ..figures import new_figure
    from ..staging.artefacts import atomic_write_bytes

    path = Path(path)
    suffix = path.suffix.lower()
    if suffix not in (".gif", ".mp4"):
        raise ValueError(f"{path}: an animation is a .gif or an .mp4 file")
    if suffix == ".mp4" and not animation.writers.is_available("ffmpeg"):
        raise ValueError(f"{path}: an MP4 needs ffmpeg, which is not installed; give a .gif path (Pillow) instead")
    if scene.cage is None:
        raise ValueError("the scene has no [cage]: nothing to animate")
    frames = max(2, int(frames))
    with h5py.File(Path(simulate_dir) / "timeseries.h5", "r") as h5:
        t = h5["time"][()]
        angle = _cage_angle(t, h5["cage/speed"][()])
        index = _frame_indices(t, angle, frames)
        balls = h5["balls/position"][index.tolist()]
        start_balls = h5["balls/position"][0]
        cage_xy = h5["cage/position"][:, :2] * 1e6
        clearance = float(h5.attrs.get("guide_clearance_m", 0.0)) * 1e6
    b, c = scene.operating.bearing, scene.operating.cage
    pitch, ball_r, pocket_r = 0.5e3 * b.pitch_diameter, 0.5e3 * b.ball_diameter, 0.5e3 * c.pocket_diameter
    home = np.arctan2(start_balls[:, 1], start_balls[:, 0])  # each ball's pocket at t = 0

    fig = new_figure(figsize=(9.6, 4.8), layout=None)
    ax_b, ax_o = fig.subplots(1, 2)
    fig.subplots_adjust(left=0.03, right=0.98, bottom=0.1, top=0.86, wspace=0.18)
    ring = np.linspace(0.0, 2 * math.pi, 241)
    for radius, style in ((pitch, "k:"), (0.5e3 * c.mean_diameter + 0.25e3 * c.width, "0.8")):
        ax_b.plot(radius * np.cos(ring), radius * np.sin(ring), style, lw=0.6)
    pockets = [ax_b.add_patch(_circle(pocket_r, "none", "tab:blue")) for _ in home]
    spheres = [ax_b.add_patch(_circle(ball_r, "0.35", "k")) for _ in home]
    lim = 1.25 * (pitch + pocket_r)
    ax_b.set_xlim(-lim, lim)
    ax_b.set_ylim(-lim, lim)
    ax_b.set_aspect("equal")
    ax_b.set_axis_off()
    ax_b.set_title(f"balls in their pockets (lead in the pocket ×{LEAD_GAIN:g})", fontsize=9)
    c_lim = 1.15 * max(clearance, float(np.abs(cage_xy).max(initial=1.0)))
    if clearance:
        ax_o.plot(clearance * np.cos(ring), clearance * np.sin(ring), "k--", lw=0.8, label=f"guide clearance {clearance:.0f} µm")
    trail, = ax_o.plot([], [], color="C0", lw=0.6)
    dot, = ax_o.plot([], [], "o", color="tab:red", ms=6)
    ax_o.set_xlim(-c_lim, c_lim)
    ax_o.set_ylim(-c_lim, c_lim)
    ax_o.set_aspect("equal")
    ax_o.grid(alpha=0.3)
    ax_o.set_xlabel("cage centre x [µm]")
    ax_o.set_ylabel("cage centre y [µm]")
    ax_o.legend(loc="upper right", fontsize=7)
    heading = fig.suptitle("", fontsize=10)

    def draw(n: int):
        i = index[n]
        cage = angle[i]
        for k, (pocket, sphere) in enumerate(zip(pockets, spheres)):
            centre = home[k] + cage
            lead = (math.atan2(balls[n, k, 1], balls[n, k, 0]) - centre + math.pi) % (2 * math.pi) - math.pi
            pocket.center = (pitch * math.cos(centre), pitch * math.sin(centre))
            drawn = centre + LEAD_GAIN * lead
            sphere.center = (pitch * math.cos(drawn), pitch * math.sin(drawn))
        trail.set_data(cage_xy[index[0]:i + 1, 0], cage_xy[index[0]:i + 1, 1])
        dot.set_data([cage_xy[i, 0]], [cage_xy[i, 1]])
        heading.set_text(f"{scene.name}: cage and balls, t = {t[i] * 1e3:.1f} ms")
        return [*pockets, *spheres, trail, dot, heading]

    movie = animation.FuncAnimation(fig, draw, frames=len(index), blit=False)
    writer = animation.PillowWriter(fps=fps) if suffix == ".gif" else animation.FFMpegWriter(fps=fps)
    tmp = path.with_name(f".{path.name}.partial{suffix}")
    path.parent.mkdir(parents=True, exist_ok=True)
    try:
        movie.save(str(tmp), writer=writer, dpi=80)
        atomic_write_bytes(path, tmp.read_bytes())
    finally:
        tmp.unlink(missing_ok=True)
    return path


def _circle(radius: float, face, edge):
    from matplotlib.patches import Circle

    return Circle((0.0, 0.0), radius, facecolor=face, edgecolor=edge, lw=0.6)


def write_cage_animations(scene, simulate_dir: Path, out_dir: Path) -> list[Path]:
    """`bearingsim render --animate`: cage_orbit.gif, and cage_orbit.mp4 when ffmpeg is installed."""
    from matplotlib import animation

    paths = [write_cage_animation(scene, simulate_dir, Path(out_dir) / "cage_orbit.gif")]
    if animation.writers.is_available("ffmpeg"):
        paths.append(write_cage_animation(scene, simulate_dir, Path(out_dir) / "cage_orbit.mp4"))
    return paths
