"""Figure: the crush margin over tolerance stacks and what drives it (docs/model.md §10.2)."""

from __future__ import annotations

from pathlib import Path

REGIME_COLOURS = {"free": "#4c9a2a", "pressed": "#e0a800", "crushed": "#c0392b"}


def plot_crush_probability(data: dict, path: Path, title: str = "") -> None:
    """Left: histogram of the crush margin, coloured by regime, with its 5th percentile and the
    crush threshold (margin 0). Right: the drivers' shares of the margin's variance."""
    from . import new_figure, save_png

    margin, regime = data["margin"], data["regime"]
    summary = data["summary"]
    fig = new_figure(figsize=(10.5, 4.4))
    ax, axd = fig.subplots(1, 2, width_ratios=(1.4, 1.0))
    lo, hi = min(margin), max(margin)
    span = hi - lo or 1.0
    bins = [lo + span * i / 50 for i in range(51)]
    for code, name in enumerate(("free", "pressed", "crushed")):
        part = [m for m, r in zip(margin, regime) if r == code]
        if part:
            p = summary["regime_probability"][name]["probability"]
            ax.hist(part, bins=bins, color=REGIME_COLOURS[name], label=f"{name}: P = {100 * p:.4g} %")  # 99.95, not a rounded 100
    ax.axvline(0.0, color="k", lw=1.0, label="crush threshold (margin 0)")
    p5 = summary["margin_percentiles"]["p5"]
    ax.axvline(p5, color="k", ls="--", lw=0.8, label=f"5th percentile {p5:.2f}")
    ax.set_xlabel("crush margin (C − e_req)/C at operating temperature [-]")
    ax.set_ylabel(f"stacks (of {summary['samples']})")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    rows = summary["drivers"][:8][::-1]
    axd.barh([r["quantity"].replace("_", " ") for r in rows], [100 * r["variance_share"] for r in rows],
             color=["#c0392b" if r["src"] < 0 else "#2e86c1" for r in rows])
    axd.set_xlabel("share of the margin's variance [%]\n(red: a larger value lowers the margin)")
    axd.grid(alpha=0.3, axis="x")
    fig.suptitle(f"Crush probability over tolerances — {title}" if title else "Crush probability over tolerances")
    save_png(fig, Path(path), dpi=110)
