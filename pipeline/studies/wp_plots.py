"""Figures of the bench studies (matplotlib imported inside each function, docs/contributing.md rule 6)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..figures import new_figure, save_png
from . import wp_metrics as wm


def plot_work_precision(study: dict, path: Path) -> Path:
    """Error against wall time, log–log, one panel per quantity, one curve per method."""
    fig = new_figure(figsize=(10, 7.5), layout="tight")
    axes = fig.subplots(2, 2)
    curves = list(dict.fromkeys(r["curve"] for r in study["rows"]))
    markers = "os^vD<>ph*"
    from matplotlib import colormaps

    colours = colormaps["tab20"].colors  # one colour per curve (the default cycle has 10)
    for ax, q in zip(axes.ravel(), wm.QUANTITIES):
        for i, curve in enumerate(curves):
            rows = [r for r in study["rows"] if r["curve"] == curve and not r["error_text"]
                    and np.isfinite(r[q]) and r[q] > 0]
            if rows:
                ax.loglog([r["wall"] for r in rows], [r[q] * wm.DISPLAY_SCALE[q] for r in rows],
                          marker=markers[i % len(markers)], color=colours[(2 * i) % 20 + (2 * i) // 20],
                          ls="--" if curve.startswith("solve_ivp") else "-", label=curve, ms=5, lw=1.2)
        ax.set_xlabel("wall time [s]")
        ax.set_ylabel(wm.LABELS[q])
        ax.grid(True, which="both", alpha=0.3)
    axes[0, 0].legend(fontsize=7)
    c = study["config"]
    fig.suptitle(f"Work-precision over {c['window'] * 1e3:g} ms (reference: HHT fixed h = "
                 f"{c['reference_step']:g} s; load average {study['load_average']:.1f})", fontsize=10)
    save_png(fig, path, dpi=80)
    return path


def plot_stability(results: list[dict], path: Path) -> Path:
    """Step size and Newton work per accepted step against time, one line per case."""
    fig = new_figure(figsize=(10, 7), layout="tight")
    axes = fig.subplots(2, 1, sharex=True)
    for r in results:
        hist = np.asarray(r.get("history", np.zeros((0, 4))))
        if hist.shape[0] < 2:
            continue
        t = hist[:, 0] * 1e3
        ls = "-" if r["status"] == "pass" else ":"
        axes[0].semilogy(t, hist[:, 1], ls, lw=0.8, label=r["case"])
        # evaluations per accepted step (rejections included), smoothed over 25 steps
        k = min(25, hist.shape[0])
        axes[1].plot(t, np.convolve(hist[:, 2], np.ones(k) / k, mode="same"), ls, lw=0.8)
    axes[0].set_ylabel("step h [s]")
    axes[1].set_ylabel("residual evaluations / step")
    axes[1].set_xlabel("time [ms]")
    axes[0].legend(fontsize=6, ncol=3)
    for ax in axes:
        ax.grid(True, which="both", alpha=0.3)
    save_png(fig, path, dpi=80)
    return path
