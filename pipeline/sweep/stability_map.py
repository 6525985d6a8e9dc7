"""The cage-stability map: two varied keys (default moment × speed), each point coloured
by its cage-motion class, with contours of the metal-contact fraction.

With more than two varied keys there is one panel per combination of the others.
matplotlib is imported inside the functions only (docs/contributing.md rule 6); no pyplot.
"""

from __future__ import annotations

import itertools
import math
from pathlib import Path
from typing import Any

CLASS_COLOURS = {
    "centred": "#4daf4a", "whirling": "#377eb8", "pressed": "#ff7f00", "crushed": "#e41a1c", "chaotic": "#984ea3",
    "no cage": "#999999", "failed": "#222222", "pending": "#dddddd",
}
CLASS_LABELS = {"centred": "stable (centred)", "pressed": "pressed onto one sector", "crushed": "crushed against the land"}
CONTOUR_LEVELS = (0.05, 0.25, 0.5, 0.75)  # metal-contact fraction; 0.05 and 0.5 are class limits
MAX_PANELS = 12


def map_axes(varied: list[str], map_x: str | None = None, map_y: str | None = None) -> tuple[str, str | None]:
    """The keys on the map's x and y axes: as asked, else moment and speed when varied,
    else the first varied keys."""
    for key in (map_x, map_y):
        if key is not None and key not in varied:
            raise ValueError(f"map axis {key!r} is not varied by this sweep; varied keys: {', '.join(varied)}")
    rest = [k for k in varied if k not in (map_x, map_y)]
    preferred = [k for k in ("load.moment", "speed.inner_rpm") if k in rest] + \
                [k for k in rest if k not in ("load.moment", "speed.inner_rpm")]
    x = map_x or preferred.pop(0)
    y = map_y or next((k for k in preferred if k != x), None)
    return x, y


def axis_label(key: str) -> str:
    from ..scene import sections
    from ..scene.schema import field_unit

    owners = {"load": sections.Load, "speed": sections.Speed, "hinge": sections.Hinge,
              "solver": sections.SolverSettings, "physics": sections.Physics}
    table, _, name = key.partition(".")
    unit = field_unit(owners[table], name) if table in owners and "." not in name else ""
    return f"{key} [{unit}]" if unit and unit != "-" else key


def _positions(values: list[Any]) -> tuple[list[float], list[float] | None, list[str] | None]:
    """Numeric values as they are; anything else as categories 0, 1, 2 ... with labels."""
    if all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in values):
        return [float(v) for v in values], None, None
    labels = list(dict.fromkeys(str(v) for v in values))
    return [float(labels.index(str(v))) for v in values], list(range(len(labels))), labels


def plot_stability_map(rows: list[dict], varied: list[str], out: Path, *, map_x: str | None = None,
                       map_y: str | None = None, title: str = "") -> Path:
    """Draw the map of `rows` (results-table rows) into `out` (PNG) and return it."""
    from ..figures import save_png

    save_png(stability_map_figure(rows, varied, map_x=map_x, map_y=map_y, title=title), Path(out), dpi=120)
    return Path(out)


def stability_map_figure(rows: list[dict], varied: list[str], *, map_x: str | None = None,
                         map_y: str | None = None, title: str = ""):
    """The map as a Figure: a line plot over the one varied key, else the class map of two
    keys (one panel per combination of the others)."""
    if len(varied) == 1:
        return line_figure(rows, varied[0], title)
    from matplotlib.patches import Patch

    from ..figures import new_figure

    x_key, y_key = map_axes(varied, map_x, map_y)
    others = [k for k in varied if k not in (x_key, y_key)]
    groups = list(dict.fromkeys(tuple(_freeze(r.get(k)) for k in others) for r in rows))[:MAX_PANELS]
    cols = min(3, len(groups))
    nrows = math.ceil(len(groups) / cols)
    fig = new_figure(figsize=(5.2 * cols, 4.4 * nrows), layout=None)
    axes = fig.subplots(nrows, cols, squeeze=False)
    for ax, group in itertools.zip_longest(axes.flat, groups):
        if group is None:
            ax.set_visible(False)
            continue
        members = [r for r in rows if tuple(_freeze(r.get(k)) for k in others) == group]
        _panel(ax, members, x_key, y_key)
        ax.set_title(", ".join(f"{k}={v}" for k, v in zip(others, group)), fontsize=9)
    present = list(dict.fromkeys(r["cage_class"] for r in rows))
    handles = [Patch(color=CLASS_COLOURS.get(c, "#000000"), label=CLASS_LABELS.get(c, c)) for c in present]
    ncol = min(len(handles), 2 * cols)
    legend_rows = math.ceil(len(handles) / ncol)
    fig.legend(handles=handles, loc="lower center", ncol=ncol, frameon=False, fontsize=8)
    fig.suptitle(title or "cage stability map\n(contours: metal-contact fraction)", fontsize=10)
    fig.tight_layout(rect=(0, 0.045 * legend_rows / nrows + 0.02, 1, 0.95))
    return fig


def line_figure(rows: list[dict], key: str, title: str = ""):
    """A sweep of one key: the metal-contact fraction and the mean eccentricity ratio against
    it, each point's marker coloured by its cage class; a point too short to settle is drawn
    hollow and says so."""
    from matplotlib.lines import Line2D

    from ..figures import new_figure

    xs, xticks, xlabels = _positions([r.get(key) for r in rows])
    fig = new_figure(figsize=(7.5, 4.4))
    ax = fig.subplots()
    eps_ax = ax.twinx()
    order = sorted(range(len(rows)), key=xs.__getitem__)
    for axis, column, style, label in ((ax, "cage_metal_contact_fraction", "-", "metal-contact fraction"),
                                       (eps_ax, "cage_eps_mean", ":", "mean eccentricity ratio ε")):
        points = [(xs[i], rows[i].get(column)) for i in order if rows[i].get(column) is not None]
        if points:
            axis.plot(*zip(*points), style, color="0.35", lw=1, zorder=1)
        for i in order:
            value, short = rows[i].get(column), rows[i].get("too_short_to_settle") in (True, "True")
            if value is None:
                continue
            colour = CLASS_COLOURS.get(rows[i]["cage_class"], "#000000")
            axis.plot(xs[i], value, "o" if column == "cage_metal_contact_fraction" else "s", ms=8,
                      mfc="white" if short else colour, mec=colour, mew=1.5, zorder=2)
        axis.set_ylabel(label)
    ax.set_ylim(-0.05, 1.05)
    eps_ax.set_ylim(0.0, max([1.2, *(float(r["cage_eps_mean"]) * 1.1 for r in rows if r.get("cage_eps_mean") is not None)]))
    ax.set_xlabel(axis_label(key))
    if xticks is not None:
        ax.set_xticks(xticks, xlabels)
    ax.grid(alpha=0.3)
    present = list(dict.fromkeys(r["cage_class"] for r in rows))
    handles = [Line2D([], [], ls="", marker="o", color=CLASS_COLOURS.get(c, "#000000"), label=CLASS_LABELS.get(c, c))
               for c in present]
    handles += [Line2D([], [], color="0.35", ls="-", label="metal-contact fraction (circles)"),
                Line2D([], [], color="0.35", ls=":", label="mean ε (squares)")]
    if any(r.get("too_short_to_settle") in (True, "True") for r in rows):
        handles.append(Line2D([], [], ls="", marker="o", mfc="white", mec="k", label="too short to settle"))
    ax.legend(handles=handles, fontsize=7, loc="upper left")
    ax.set_title(title or f"cage over {key}", fontsize=10)
    return fig


def _freeze(value: Any) -> Any:
    return tuple(value) if isinstance(value, list) else value


def _panel(ax, rows: list[dict], x_key: str, y_key: str | None) -> None:
    xs, xticks, xlabels = _positions([r.get(x_key) for r in rows])
    ys, yticks, ylabels = _positions([r.get(y_key) for r in rows]) if y_key else ([0.0] * len(rows), [0], [""])
    colours = [CLASS_COLOURS.get(r["cage_class"], "#000000") for r in rows]
    if not _grid_cells(ax, xs, ys, colours):
        ax.scatter(xs, ys, c=colours, s=260, marker="s", edgecolors="k", linewidths=0.5, zorder=2)
    metal = [r.get("cage_metal_contact_fraction") for r in rows]
    if len(rows) <= 100:
        # each point's own value: a dot and a boxed label inside the range (the contour labels
        # have no box), so that the two are not confused and no label leaves the axes
        ax.plot(xs, ys, "k.", ms=3, zorder=3)
        for x, y, f in zip(xs, ys, metal):
            right, top = x >= max(xs) and x > min(xs), y >= max(ys) and y > min(ys)
            ax.annotate("—" if f is None else f"{f:.2f}", (x, y), textcoords="offset points",
                        xytext=(-4 if right else 4, -4 if top else 4), ha="right" if right else "left",
                        va="top" if top else "bottom", fontsize=7, zorder=4,
                        bbox={"boxstyle": "round,pad=0.15", "fc": "white", "ec": "none", "alpha": 0.8})
    _contours(ax, xs, ys, metal)
    ax.set_xlabel(axis_label(x_key))
    ax.set_ylabel(axis_label(y_key) if y_key else "")
    if xticks is not None:
        ax.set_xticks(xticks, xlabels)
    if yticks is not None:
        ax.set_yticks(yticks, ylabels)
    ax.margins(0.05)


def _grid_cells(ax, xs: list[float], ys: list[float], colours: list[str]) -> bool:
    """A full factorial grid as filled cells meeting half-way between values and ending at the
    outermost values (nothing is painted beyond the swept range; the axes leave a margin
    there); False when the points are not a complete grid (then they are drawn as markers)."""
    import numpy as np
    from matplotlib.colors import to_rgb

    ux, uy = sorted(set(xs)), sorted(set(ys))
    if len(ux) < 2 or len(uy) < 2 or len(xs) != len(ux) * len(uy):
        return False
    image = np.ones((len(uy), len(ux), 3))
    for x, y, c in zip(xs, ys, colours):
        image[uy.index(y), ux.index(x)] = to_rgb(c)

    def edges(u):
        u = np.asarray(u, float)
        return np.concatenate([[u[0]], 0.5 * (u[1:] + u[:-1]), [u[-1]]])

    ax.pcolormesh(edges(ux), edges(uy), image, edgecolors="w", linewidth=0.5, zorder=1)
    for u, set_lim in ((ux, ax.set_xlim), (uy, ax.set_ylim)):
        pad = 0.05 * (u[-1] - u[0])
        set_lim(u[0] - pad, u[-1] + pad)
    return True


def _contours(ax, xs: list[float], ys: list[float], metal: list) -> None:
    """Metal-contact contours by linear interpolation on a Delaunay triangulation built in
    axis-normalised coordinates (moment and speed differ by orders of magnitude)."""
    import matplotlib.tri as mtri
    import numpy as np

    keep = [i for i, f in enumerate(metal) if f is not None]
    if len(keep) < 3:
        return
    x, y, f = (np.array([v[i] for i in keep], float) for v in (xs, ys, metal))
    span = lambda a: (a - a.min()) / (np.ptp(a) or 1.0)  # noqa: E731
    try:
        triangles = mtri.Triangulation(span(x), span(y)).triangles
    except (ValueError, RuntimeError):  # collinear points: no area to contour
        return
    levels = [lv for lv in CONTOUR_LEVELS if f.min() < lv < f.max()]
    if not levels:
        return
    cs = ax.tricontour(mtri.Triangulation(x, y, triangles), f, levels=levels, colors="k",
                       linewidths=0.8, zorder=3)
    ax.clabel(cs, fmt="%.2f", fontsize=7)
