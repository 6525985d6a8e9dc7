"""Figures and tables of docs/validation.md from the study's JSON files.

    python -m benchmarks.cage_verdict.figures STUDY_DIR [--out benchmarks/cage_verdict/data]
        [--figures docs/validation]

STUDY_DIR holds the `<plan>.json` files of `runs.py` and its `runs/` directories. The figures
docs/validation.md shows go to --figures; each plan's JSON file, its table and the other figures
go to --out, the study's data folder (where screen.py's crush screen is kept too).
"""

from __future__ import annotations

import argparse
import json
import math
import shutil
from pathlib import Path

import numpy as np

from . import DATA

METRICS = (  # (key in the settled window, label, unit)
    ("eps_mean", "mean eccentricity ratio", "-"),
    ("metal_fraction", "metal-contact fraction", "-"),
    ("land_force_mean", "mean land force", "N"),
    ("offset_azimuth_deg", "offset direction", "deg"),
    ("offset_spread_rad", "offset spread", "rad"),
    ("whirl_ratio", "whirl ratio", "-"),
    ("impact_p95", "impact p95", "N"),
    ("min_film_um", "min land film", "um"),
)


# the figures docs/validation.md embeds; the others are data
SHOWN = ("operating_sweep.png", "pocket_m430.png", "tornado_a_whirl_ratio.png", "tornado_b_eps_mean.png")


def _load(study: Path, plan: str) -> dict:
    p = study / f"{plan}.json"
    return json.loads(p.read_text()) if p.is_file() else {}


def _plt():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def moment_sweep_figure(study: Path, out: Path, screen: dict | None) -> Path:
    plt = _plt()
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.4))
    for plan, style, label, colour in (("moment_sweep", "o-", "default: dynamic film, 2 lands", "C0"),
                                       ("moment_sweep_static", "s--", "paper's law: static film, 1 journal", "C1")):
        d = _load(study, plan)
        rows = sorted((float(v["overrides"][0].split("=")[1]), v["settled"]) for v in d.values() if "settled" in v)
        if not rows:
            continue
        m = np.array([r[0] for r in rows])
        axes[0].plot(m, [r[1]["eps_mean"] for r in rows], style, color=colour, label=label + " (mean)")
        axes[0].plot(m, [r[1]["eps_max"] for r in rows], style, color=colour, alpha=0.35, label=label + " (max)")
        axes[1].plot(m, [r[1]["metal_fraction"] for r in rows], style, color=colour, label=label)
        axes[2].plot(m, [r[1]["land_force_mean"] for r in rows], style, color=colour, label=label)
    axes[0].axhline(1.0, color="k", lw=0.8)
    axes[0].text(5, 1.005, "metal contact (eps > 1)", fontsize=8, va="bottom")
    axes[0].set_ylabel("cage eccentricity e / C [-]")
    _label_sweep_axes(axes)
    if screen:
        ms = np.array(sorted(float(k) for k in screen))
        for ax in axes:
            for mm in ms:
                reg = screen[str(int(mm))]["regime"]
                ax.axvspan(mm - 12, mm + 12, color={"free": "#e8f4e8", "pressed": "#fff3d6", "crushed": "#f9dcdc"}[reg], lw=0)
    for ax in axes:
        ax.axvline(100, color="g", lw=1, ls=":")
        ax.axvline(430, color="r", lw=1, ls=":")
    axes[1].legend(fontsize=8, loc="upper left")
    axes[0].legend(fontsize=7, loc="lower right")
    fig.suptitle("Reference bearing, 3060 rev/min, settled window 0.1–0.4 s. Dotted: case a (the paper's healthy case, "
                 "green), case b (failed on the rig, red). Shading: crush screen (green free, yellow pressed, red crushed)",
                 fontsize=9)
    return _save(plt, fig, out / "moment_sweep.png")


def _label_sweep_axes(axes) -> None:
    """Labels and grid of the three panels of a moment sweep: eccentricity, metal, land force."""
    axes[1].set_ylabel("metal-contact fraction, settled window [-]")
    axes[2].set_ylabel("mean land force [N]")
    axes[2].set_yscale("symlog", linthresh=1.0)
    for ax in axes:
        ax.set_xlabel("moment [N m]")
        ax.grid(alpha=0.3)


def _save(plt, fig, path: Path) -> Path:
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def operating_sweep_figure(study: Path, out: Path, screen: dict | None) -> Path:
    """The moment sweep at operating temperatures against the same sweep with the clearances as
    drawn (docs/validation.md §9), the crush screen of each as a step curve of its margin."""
    plt = _plt()
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.4))
    for plan, style, label, colour, state in (("moment_sweep", "o-", "parts at 100 °C (default)", "C3", "operating"),
                                              ("moment_sweep_cold", "s--", "clearances as drawn (20 °C)", "C0", "cold")):
        d = _load(study, plan)
        rows = sorted((float(v["overrides"][0].split("=")[1]), v["settled"]) for v in d.values() if "settled" in v)
        if not rows:
            continue
        m = np.array([r[0] for r in rows])
        axes[0].plot(m, [r[1]["eps_mean"] for r in rows], style, color=colour, label=label)
        axes[1].plot(m, [r[1]["metal_fraction"] for r in rows], style, color=colour, label=label)
        axes[2].plot(m, [r[1]["land_force_mean"] for r in rows], style, color=colour, label=label)
        if screen and state in screen:
            ms = sorted(float(k) for k in screen[state] if k.isdigit())
            axes[0].plot(ms, [1.0 - screen[state][str(int(x))]["crush_margin"] for x in ms], ":", color=colour,
                         label=f"screen, {label}: required offset e_req/C")
            thr = screen[state].get("crush_threshold_moment")
            if thr:
                for ax in axes:
                    ax.axvline(thr, color=colour, lw=0.8, ls="-.")
    axes[0].axhline(1.0, color="k", lw=0.8)
    axes[0].set_ylim(0, 1.6)
    axes[0].set_ylabel("cage eccentricity e / C [-] (dynamics: settled mean)")
    _label_sweep_axes(axes)
    axes[2].set_ylim(bottom=0.0)
    for ax in axes:
        ax.axvline(430, color="k", lw=1, ls=":")
    axes[0].legend(fontsize=7, loc="upper left")
    axes[1].legend(fontsize=8, loc="upper left")
    fig.suptitle("Reference bearing, 3060 rev/min, settled window 0.1–0.4 s; dotted vertical: case b (430 N m); "
                 "dash-dot: the screen's crush threshold of each state", fontsize=9)
    return _save(plt, fig, out / "operating_sweep.png")


def tornado_figure(study: Path, out: Path, case: str, metric: str, label: str) -> Path:
    plt = _plt()
    d = _load(study, f"sensitivity_{case}")
    base = d.get(f"{case}-base", {}).get("settled", {}).get(metric)
    if base is None:
        raise SystemExit(f"no base run for case {case}")
    groups: dict[str, list[tuple[str, float]]] = {}
    for name, v in d.items():
        if name == f"{case}-base" or "settled" not in v:
            continue
        key = name[len(case) + 1:]
        group = key.rsplit("-", 1)[0] if key.endswith(("-lo", "-hi", "-on")) else key
        groups.setdefault(group, []).append((v["overrides"][-1], v["settled"][metric] - base))
    order = sorted(groups, key=lambda g: max(abs(x[1]) for x in groups[g]))
    fig, ax = plt.subplots(figsize=(9, 0.42 * len(order) + 1.6))
    labels = []
    for i, g in enumerate(order):
        values = []
        for setting, delta in groups[g]:
            ax.barh(i, delta, height=0.6, color="#c0504d" if delta > 0 else "#4f81bd", alpha=0.75)
            values.append(setting.split("=", 1)[1])
        labels.append(f"{g}: " + " / ".join(values))
    ax.set_yticks(range(len(order)))
    ax.set_yticklabels(labels, fontsize=8)
    ax.axvline(0, color="k", lw=0.8)
    ax.set_xlabel(f"change of {label} from the default ({base:.3g})")
    ax.set_title(f"Case {case}: sensitivity of {label} (settled window 0.1–0.4 s)", fontsize=10)
    ax.grid(axis="x", alpha=0.3)
    fig.tight_layout()
    path = out / f"tornado_{case}_{metric}.png"
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def orbits_figure(study: Path, out: Path, runs: list[tuple[str, str]], name: str, settle: float = 0.1) -> Path:
    import h5py

    plt = _plt()
    fig, axes = plt.subplots(1, len(runs), figsize=(4.6 * len(runs), 4.6))
    for ax, (run, title) in zip(np.atleast_1d(axes), runs):
        with h5py.File(study / "runs" / run / "simulate" / "timeseries.h5") as f:
            t, c = f["time"][:], f["cage/position"][:]
            C = float(f.attrs["guide_clearance_m"])
        m = t >= settle
        th = np.linspace(0, 2 * math.pi, 200)
        ax.plot(np.cos(th), np.sin(th), "k--", lw=0.8)
        ax.plot(c[~m, 0] / C, c[~m, 1] / C, color="0.75", lw=0.6, label="start-up")
        ax.plot(c[m, 0] / C, c[m, 1] / C, lw=0.7, label="settled")
        ax.set_aspect("equal")
        ax.set_xlim(-1.15, 1.15)
        ax.set_ylim(-1.15, 1.15)
        ax.set_title(title, fontsize=9)
        ax.set_xlabel("x / C")
        ax.grid(alpha=0.3)
    np.atleast_1d(axes)[0].set_ylabel("y / C")
    np.atleast_1d(axes)[0].legend(fontsize=8, loc="lower left")
    fig.tight_layout()
    path = out / f"{name}.png"
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def pocket_figure(study: Path, out: Path, run: str, screen_excursion: tuple | None, settle: float = 0.1) -> Path:
    """Ball position in its pocket (along the orbit) against orbital position, dynamic run vs
    the screen's excursion relative to a cage at its required offset."""
    import h5py

    plt = _plt()
    with h5py.File(study / "runs" / run / "simulate" / "timeseries.h5") as f:
        t, pos, cx, cs = f["time"][:], f["balls/position"][:], f["cage/position"][:], f["cage/speed"][:]
    Z = pos.shape[1]
    rp = float(np.mean(np.hypot(pos[0, :, 0], pos[0, :, 1])))
    phi = np.concatenate([[0.0], np.cumsum(0.5 * (cs[1:] + cs[:-1]) * np.diff(t))])
    ang = 2 * math.pi * np.arange(Z)[None, :] / Z + phi[:, None]
    pk = cx[:, None, :2] + rp * np.stack([np.cos(ang), np.sin(ang)], -1)
    et = np.stack([-np.sin(ang), np.cos(ang)], -1)
    off = np.sum((pos[:, :, :2] - pk) * et, -1)
    theta = np.degrees(np.mod(np.arctan2(pos[:, :, 1], pos[:, :, 0]), 2 * math.pi))
    m = t >= settle
    fig, ax = plt.subplots(figsize=(8, 4))
    ax.plot(theta[m].ravel()[::7], 1e3 * off[m].ravel()[::7], ",", alpha=0.3, label="dynamic run (each ball)")
    if screen_excursion is not None:
        grid, s = screen_excursion
        ax.plot(np.degrees(grid), 1e3 * s, "k-", lw=1.2, label="screen: excursion against a centred cage")
    return _finish_pocket(fig, ax, out, run)


def _finish_pocket(fig, ax, out, run):
    half = 0.59
    ax.axhline(half, color="r", lw=0.8)
    ax.axhline(-half, color="r", lw=0.8)
    ax.text(2, half + 0.02, "front wall (ball leads, pushes the cage)", fontsize=7, color="r")
    ax.text(2, -half - 0.08, "rear wall (cage drives the ball)", fontsize=7, color="r")
    ax.set_xlabel("orbital position [deg]")
    ax.set_ylabel("ball ahead of its pocket centre [mm]")
    ax.set_xlim(0, 360)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="lower right")
    fig.tight_layout()
    path = out / f"pocket_{run}.png"
    fig.savefig(path, dpi=110)
    plt = _plt()
    plt.close(fig)
    return path


def _screen_curve(moment: float):
    """(psi grid, s) of the crush screen (M.115) for the reference bearing at `moment`."""
    from bearingsim.dynamics.quasistatic.crush_screen import orbital_excursion
    from bearingsim.pipeline.scene.load import load_scene
    from bearingsim.pipeline.stages.quasistatic import solve

    scene = load_scene("helicopter-b-given-hinge", [f"load.moment={moment}"])
    r = solve(scene)
    _, grid, s = orbital_excursion(r.azimuth, r.ball_orbital_speed, 0.5 * scene.cage.mean_diameter)
    return grid, s


def markdown_table(study: Path, plan: str, names: dict[str, str] | None = None) -> str:
    d = _load(study, plan)
    head = "| run | " + " | ".join(f"{lab} [{u}]" for _, lab, u in METRICS) + " |"
    rows = [head, "|" + " --- |" * (len(METRICS) + 1)]
    for k, v in d.items():
        if "settled" not in v:
            rows.append(f"| {k} | failed | " + " | " * (len(METRICS) - 1))
            continue
        s = v["settled"]
        cells = []
        for key, _, _ in METRICS:
            x = s.get(key)
            cells.append("—" if x is None else (f"{x:.0f}" if key in ("offset_azimuth_deg", "impact_p95") else f"{x:.3g}"))
        label = (names or {}).get(k, k + (" (" + ", ".join(o for o in v["overrides"] if not o.startswith("load.")) + ")" if len(v["overrides"]) > 1 else ""))
        rows.append(f"| {label} | " + " | ".join(cells) + " |")
    return "\n".join(rows)


def _publish(study: Path, out: Path, plan: str) -> None:
    """The plan's table and the JSON file behind it, into the data folder."""
    (out / f"{plan}.md").write_text(markdown_table(study, plan) + "\n")
    source, target = study / f"{plan}.json", out / f"{plan}.json"
    if source.resolve() != target.resolve():
        shutil.copyfile(source, target)


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("study", type=Path)
    ap.add_argument("--out", type=Path, default=DATA, help="the data folder: tables, JSON, figures not shown")
    ap.add_argument("--figures", type=Path, default=Path("docs/validation"),
                    help="the figures docs/validation.md shows")
    ap.add_argument("--screen", type=Path, help="JSON of the crush screen per moment (screen.py)")
    ap.add_argument("--operating", action="store_true",
                    help="only the operating-temperature study: operating_sweep.png and the tables of its plans")
    a = ap.parse_args(argv)
    a.out.mkdir(parents=True, exist_ok=True)
    a.figures.mkdir(parents=True, exist_ok=True)

    def folder(name: str) -> Path:
        return a.figures if name in SHOWN else a.out

    screen = json.loads(a.screen.read_text()) if a.screen else None
    if a.operating:
        print(operating_sweep_figure(a.study, folder("operating_sweep.png"), screen))
        for plan in ("moment_sweep", "moment_sweep_cold", "paper_land", "run_out", "confirm"):
            if _load(a.study, plan):
                _publish(a.study, a.out, plan)
        return
    print(moment_sweep_figure(a.study, folder("moment_sweep.png"), (screen or {}).get("operating", screen)))
    for case in ("a", "b"):
        for metric, label in (("eps_mean", "mean eccentricity ratio"), ("land_force_mean", "mean land force [N]"),
                              ("whirl_ratio", "whirl ratio"), ("metal_fraction", "metal-contact fraction")):
            try:
                print(tornado_figure(a.study, folder(f"tornado_{case}_{metric}.png"), case, metric, label))
            except SystemExit as exc:
                print(exc)
    print(orbits_figure(a.study, folder("orbits.png"), [("m100", "case a, 100 N m (default)"), ("static-m100", "case a, static film, 1 journal"),
                                                        ("m430", "case b, 430 N m (default)"), ("m550", "550 N m (default)")], "orbits"))
    print(pocket_figure(a.study, folder("pocket_m430.png"), "m430", _screen_curve(430.0)))
    for plan in ("moment_sweep", "moment_sweep_static", "sensitivity_a", "sensitivity_b", "ablations", "repeat"):
        if _load(a.study, plan):
            _publish(a.study, a.out, plan)


if __name__ == "__main__":
    main()
