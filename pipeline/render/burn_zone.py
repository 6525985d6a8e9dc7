"""Burn-zone renders (docs/model.md §11): the guiding race (the outer ring's bore, or the inner
ring's outside in the frame turning with it) in 3-D and unrolled in 2-D.

Both images show the same two layers (see `burn_zone_data`), over the settled window of the
run: on the cage's land overlap the land heat per sector [J] — metal friction plus film
shear — ("inferno", 0 to the data's maximum), on the raceway the ball contact tracks as
load × time [N·s] ("Blues", 0 to the maximum). The unrolled map's upper panel shows the two
heat layers stacked (film below, metal on top). The parts of the lands the cage does not
cover and the ring's faces are grey. The peak sector is marked by a cyan line with its
azimuth, the arc holding 80 % of the heat (`summary.json` `burn_zone_sector`) by a cyan
outline. Azimuth runs from +x towards +y.

The 3-D image has four fixed views: each panel shows the half of the ring centred on
azimuth 0°, 90°, 180° or 270°, seen from inside the bearing, so every sector faces the
camera in at least one panel and two runs' images compare view for view. The camera sits
on the side of the groove plane opposite the loaded half of the groove (`camera_side`),
where the contact tracks face it.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from .burn_zone_data import BurnZoneMap, RaceProfile
from ..figures import new_figure, save_png
from .offscreen import render_png

BURN_CMAP, TRACK_CMAP = "inferno", "Blues"
MARK_COLOR = "cyan"
VIEW_AZIMUTHS_DEG = (0.0, 90.0, 180.0, 270.0)
OUTSIDE_RADIUS_FACTOR = 1.12  # ring OD drawn when the scene gives none (context only)
DPI = 110


def _clim(values: np.ndarray) -> list[float]:
    top = float(np.max(values, initial=0.0))
    return [0.0, top if top > 0.0 else 1.0]


def _surface_of_revolution(pv, radius: np.ndarray, z: np.ndarray, phi: np.ndarray):
    """Structured surface: profile (radius, z) [m] (P points) swept over azimuths phi
    [rad] (A points); its cells are ordered azimuth-fastest, i.e. cell (k, i) of a
    (P-1, A-1) array is `values.ravel()` with i the azimuth index."""
    R, PHI = np.meshgrid(radius, phi, indexing="ij")
    Zg = np.broadcast_to(np.asarray(z, dtype=float)[:, None], R.shape)
    # StructuredGrid dimensions are (A, P, 1) with the first (azimuth) index fastest
    grid = pv.StructuredGrid((R * np.cos(PHI)).T, (R * np.sin(PHI)).T, np.array(Zg).T)
    return grid


def _azimuth_window(first: float, count: int, total: int) -> np.ndarray:
    """Indices of `count` consecutive bins starting at `first` (mod `total`)."""
    return (first + np.arange(count)) % total


def _race_meshes(pv, bzm: BurnZoneMap, center_deg: float, rim_radius: float) -> list[tuple]:
    """(mesh, kind) of the half ring centred on `center_deg`: land bands, raceway, grey;
    `rim_radius` the ring's other surface (the outer ring's outside, the inner ring's bore)."""
    p = bzm.profile
    S, A = bzm.sectors, bzm.track_density.shape[0]
    meshes = []
    half = 0.5 * math.pi

    def arc(bins: int):
        first = int(math.floor((math.radians(center_deg) - half) / (2 * math.pi) * bins))
        idx = _azimuth_window(first, bins // 2, bins)
        phi = (first + np.arange(bins // 2 + 1)) * 2 * math.pi / bins
        return idx, phi

    idx, phi = arc(S)
    for side in (-1, 1):
        r_land, z_land = p.land_radius_at(side), p.z_land(side)
        start = z_land
        if side in p.land_sides:
            band = _surface_of_revolution(pv, np.full(2, r_land), side * np.array([z_land, p.cage_half_width]), phi)
            band.cell_data["energy"] = bzm.sector_energy[idx]
            meshes.append((band, "burn"))
            start = p.cage_half_width
        plain = _surface_of_revolution(pv, np.full(2, r_land), side * np.array([start, p.half_width]), phi)
        face = _surface_of_revolution(pv, np.array([r_land, rim_radius]), np.full(2, side * p.half_width), phi)
        meshes += [(plain, "grey"), (face, "grey")]
    rim = _surface_of_revolution(pv, np.full(2, rim_radius), np.array([-p.half_width, p.half_width]), phi)
    meshes.append((rim, "grey"))
    idx_t, phi_t = arc(A)
    radius, z = p.groove_point(bzm.track_alpha_edges)
    race = _surface_of_revolution(pv, radius, z, phi_t)
    race.cell_data["tracks"] = bzm.track_density[idx_t, :].T.ravel()
    meshes.append((race, "tracks"))
    return meshes


def _in_view(phi: float, center_deg: float) -> bool:
    """Is azimuth phi [rad] on the half ring shown in the view centred on center_deg?"""
    return abs((math.degrees(phi) - center_deg + 180.0) % 360.0 - 180.0) <= 90.0


def _marks(pv, bzm: BurnZoneMap, center_deg: float) -> list:
    """Polylines on the lands of the shown half ring: the peak sector's centre line and
    the outline of the 80 % arc."""
    p = bzm.profile
    r = (1.0 - 0.001 * p.sign) * p.land_radius  # just off the land, on the camera's side
    lines = []
    if bzm.peak_sector is not None and _in_view(bzm.sector_center(bzm.peak_sector), center_deg):
        phi = bzm.sector_center(bzm.peak_sector)
        for side in p.land_sides:
            a = [r * math.cos(phi), r * math.sin(phi), side * p.z_land(side)]
            b = [r * math.cos(phi), r * math.sin(phi), side * p.cage_half_width]
            lines.append(pv.Line(a, b))
    if bzm.sector is not None:
        start, end = bzm.sector
        phi = np.linspace(start, end, max(2, int(4 * math.degrees(end - start)) + 1))
        phi = phi[[_in_view(a, center_deg) for a in phi]]
        if phi.size < 2:
            return lines
        for side in p.land_sides:
            for z in (p.z_land(side), p.cage_half_width):
                pts = np.column_stack([r * np.cos(phi), r * np.sin(phi), np.full(phi.size, side * z)])
                lines.append(pv.lines_from_points(pts))
            for edge in (start, end):
                if _in_view(edge, center_deg):
                    lines.append(pv.Line([r * math.cos(edge), r * math.sin(edge), side * p.z_land(side)],
                                         [r * math.cos(edge), r * math.sin(edge), side * p.cage_half_width]))
    return lines


def camera_side(bzm: BurnZoneMap) -> float:
    """+1: camera above the groove plane, -1: below. The contact tracks lie on the half of
    the groove that carries the thrust; that half faces the axis and the opposite side, so
    the camera looks from there (below when there are no tracks). A rule of the data,
    hence the same picture for the same results."""
    centres = 0.5 * (bzm.track_alpha_edges[1:] + bzm.track_alpha_edges[:-1])
    weight = bzm.track_density.sum(axis=0)
    _, z = bzm.profile.groove_point(centres)
    mean_z = float(np.sum(weight * z) / weight.sum()) if weight.sum() > 0.0 else 0.0
    return 1.0 if mean_z < 0.0 else -1.0


def _view(plotter, center_deg: float, profile: RaceProfile, side: float) -> None:
    """Camera above (side +1) or below (-1) the groove plane looking at the land around azimuth
    `center_deg`: for the outer ring's bore from the far side of the axis, for the inner ring's
    outside from beyond it."""
    c = math.radians(center_deg)
    R = profile.land_radius
    reach = -2.6 if profile.ring == "outer" else 3.2
    focus = (0.5 * R * math.cos(c), 0.5 * R * math.sin(c), side * 0.1 * R)
    eye = (reach * R * math.cos(c), reach * R * math.sin(c), side * 1.1 * R)
    plotter.camera_position = [eye, focus, (0.0, 0.0, 1.0)]
    plotter.camera.view_angle = 34.0


def render_burn_zone_3d(bzm: BurnZoneMap, path: Path, title: str, rim_radius: float | None = None,
                        show: bool = False) -> None:
    """Four fixed views of the guiding race coloured by burn energy and contact tracks;
    `rim_radius` [m] the ring's other surface (outer ring: its outside, inner ring: its bore)."""
    p = bzm.profile
    R_out = rim_radius or p.land_radius * (OUTSIDE_RADIUS_FACTOR if p.ring == "outer" else 1.0 / OUTSIDE_RADIUS_FACTOR)
    clim_burn, clim_track = _clim(bzm.sector_energy), _clim(bzm.track_density)
    deg = 360.0 / bzm.sectors
    side = camera_side(bzm)

    def populate(plotter) -> None:
        import pyvista as pv

        for n, center in enumerate(VIEW_AZIMUTHS_DEG):
            plotter.subplot(n // 2, n % 2)
            first = n == 0
            for mesh, kind in _race_meshes(pv, bzm, center, R_out):
                if kind == "burn":
                    plotter.add_mesh(mesh, scalars="energy", cmap=BURN_CMAP, clim=clim_burn,
                                     show_scalar_bar=first, lighting=False,
                                     scalar_bar_args={"title": f"land: heat per {deg:g} deg sector [J]\n",
                                                      "vertical": False, "position_x": 0.14, "position_y": 0.02,
                                                      "width": 0.36, "height": 0.1, "fmt": "%.3g", "title_font_size": 14,
                                                      "label_font_size": 12})
                elif kind == "tracks":
                    plotter.add_mesh(mesh, scalars="tracks", cmap=TRACK_CMAP, clim=clim_track,
                                     show_scalar_bar=first, lighting=False,
                                     scalar_bar_args={"title": "raceway: load x time [N s]\n",
                                                      "vertical": False, "position_x": 0.6, "position_y": 0.02,
                                                      "width": 0.36, "height": 0.1, "fmt": "%.3g", "title_font_size": 14,
                                                      "label_font_size": 12})
                else:
                    plotter.add_mesh(mesh, color="lightgrey")
            for line in _marks(pv, bzm, center):
                plotter.add_mesh(line, color=MARK_COLOR, line_width=4)
            _azimuth_labels(plotter, p, bzm, center, side)
            plotter.add_text(f"view centred on azimuth {center:.0f}°", position="upper_right", font_size=9)
            if first:
                plotter.add_text(title, position="upper_left", font_size=10)
            plotter.add_axes()
            _view(plotter, center, p, side)

    render_png(path, populate, shape=(2, 2), window_size=(1600, 1000), show=show)


def _azimuth_labels(plotter, p: RaceProfile, bzm: BurnZoneMap, center_deg: float, side: float) -> None:
    """Azimuth ticks every 30° on the face towards the camera, and the peak sector's value."""
    r = p.land_radius
    ticks = np.array([a for a in np.radians(np.arange(0, 360, 30)) if _in_view(a, center_deg)])
    pts = np.column_stack([r * np.cos(ticks), r * np.sin(ticks), np.full(ticks.size, side * p.half_width)])
    plotter.add_point_labels(pts, [f"{math.degrees(a):.0f}°" for a in ticks], font_size=10,
                             point_size=1, shape_opacity=0.0, always_visible=False)
    if bzm.peak_sector is not None and _in_view(bzm.sector_center(bzm.peak_sector), center_deg):
        phi = bzm.sector_center(bzm.peak_sector)
        pt = [[(1.0 - 0.03 * p.sign) * r * math.cos(phi), (1.0 - 0.03 * p.sign) * r * math.sin(phi),
               side * p.cage_half_width]]
        plotter.add_point_labels(pt, [f"peak {math.degrees(phi):.1f}°"], font_size=12,
                                 text_color="black", shape_color=MARK_COLOR, point_size=1)


def render_burn_zone_map(bzm: BurnZoneMap, path: Path, title: str) -> dict:
    """Unrolled race (azimuth × axial position) under the energy-per-sector curve.

    Returns the map's data limits and its pixel box in the PNG (`box_px`: left, top,
    right, bottom, rows counted from the top) so a reader can locate an azimuth."""
    p = bzm.profile
    mm, deg = 1e3, 180.0 / math.pi
    fig = new_figure(figsize=(11.0, 7.5))
    ax_e, ax_m = fig.subplots(2, 1, sharex=True, height_ratios=(1, 2.4))
    S = bzm.sectors
    sector_edges = np.linspace(0.0, 360.0, S + 1)
    if bzm.film_energy is not None and bzm.metal_energy is not None:
        ax_e.stairs(bzm.film_energy, sector_edges, fill=True, color="tab:orange", alpha=0.8,
                    label=f"film shear {bzm.film_energy.sum():.3g} J")
        ax_e.stairs(bzm.film_energy + bzm.metal_energy, sector_edges, baseline=bzm.film_energy, fill=True,
                    color="tab:red", alpha=0.8, label=f"metal friction {bzm.metal_energy.sum():.3g} J")
    else:
        ax_e.stairs(bzm.sector_energy, sector_edges, fill=True, color="tab:red", alpha=0.8)
    ax_e.set_ylabel(f"heat per {360 / S:g}° sector [J]")
    ax_e.set_ylim(0.0, _clim(bzm.sector_energy)[1] * 1.1)
    ax_e.grid(alpha=0.3)
    burn = None
    for side in (-1, 1):
        start = p.z_land(side)
        if side in p.land_sides:
            z_edges = np.sort(side * np.array([p.z_land(side), p.cage_half_width])) * mm
            burn = ax_m.pcolormesh(sector_edges, z_edges, bzm.sector_energy[None, :], cmap=BURN_CMAP,
                                   vmin=0.0, vmax=_clim(bzm.sector_energy)[1])
            start = p.cage_half_width
        ax_m.axhspan(*(np.sort(side * np.array([start, p.half_width])) * mm), color="lightgrey")
    A = bzm.track_density.shape[0]
    _, z_track = p.groove_point(bzm.track_alpha_edges)
    tracks = ax_m.pcolormesh(np.linspace(0.0, 360.0, A + 1), z_track * mm, bzm.track_density.T,
                             cmap=TRACK_CMAP, vmin=0.0, vmax=_clim(bzm.track_density)[1])
    for side in (-1, 1):
        for z in (p.z_land(side), p.cage_half_width):
            ax_m.axhline(side * z * mm, color="k", lw=0.6)
    _mark_sectors(bzm, (ax_e, ax_m), deg)
    ax_m.set_xlim(0.0, 360.0)
    ax_m.set_ylim(-p.half_width * mm, p.half_width * mm)
    ax_m.set_xticks(range(0, 361, 30))
    ax_m.set_xlabel("azimuth φ [deg] (from +x towards +y)" if p.ring == "outer" else
                    "azimuth φ on the inner ring [deg] (from where +x was at t = 0, turning with the ring)")
    ax_m.set_ylabel("axial position z [mm] (groove plane at 0)")
    fig.colorbar(burn, ax=ax_m, label=f"land: heat per {360 / S:g}° sector [J]", pad=0.01)
    fig.colorbar(tracks, ax=ax_m, label="raceway: load × time per bin [N·s]", pad=0.01)
    lands = "both lands" if len(p.land_sides) == 2 else "the guiding land"
    ax_e.set_title(f"{title}: the {p.ring} ring's land\n{heat_caption(bzm)}\neach sector's heat spread uniformly "
                   f"over the land overlap ({lands}, L = {p.land_overlap * mm:.2f} mm)", fontsize=9)
    fig.canvas.draw()  # fix the constrained layout before reading the axes' position
    box = ax_m.get_window_extent()
    height = fig.bbox.height
    dpi_scale = DPI / fig.dpi
    save_png(fig, path, dpi=DPI)
    return {"azimuth_deg": (0.0, 360.0), "z_m": (-p.half_width, p.half_width),
            "box_px": tuple(round(v * dpi_scale) for v in (box.x0, height - box.y1, box.x1, height - box.y0))}


def _mark_sectors(bzm: BurnZoneMap, axes, deg: float) -> None:
    """Peak sector line and the 80 % arc (split where it wraps past 360°) on both axes."""
    for ax in axes:
        if bzm.sector is not None:
            start, end = (v * deg for v in bzm.sector)
            spans = [(start, min(end, 360.0))] + ([(0.0, end - 360.0)] if end > 360.0 else [])
            for a, b in spans:
                ax.axvspan(a, b, facecolor="none", edgecolor=MARK_COLOR, lw=1.5, hatch="//",
                           label="80 % of the heat" if a == start else None)
        if bzm.peak_sector is not None:
            ax.axvline(math.degrees(bzm.sector_center(bzm.peak_sector)), color=MARK_COLOR, lw=1.5, ls="--",
                       label=f"peak sector {math.degrees(bzm.sector_center(bzm.peak_sector)):.1f}°")
    if bzm.sector is not None or bzm.peak_sector is not None:
        axes[0].legend(loc="upper right", fontsize=8)
    else:
        axes[0].text(0.5, 0.5, "no heat on the guide land in this window", ha="center",
                     va="center", transform=axes[0].transAxes)


def heat_caption(bzm: BurnZoneMap) -> str:
    """What the burn zone shows, in words and numbers (map title, report)."""
    total = float(bzm.sector_energy.sum())
    window = (f" over t = {bzm.window[0]:.4g}–{bzm.window[1]:.4g} s (settled)" if bzm.window is not None else "")
    if bzm.metal_energy is not None and bzm.film_energy is not None:
        text = (f"land heat {total:.3g} J{window}: metal friction {bzm.metal_energy.sum():.3g} J + "
                f"film shear {bzm.film_energy.sum():.3g} J")
    else:
        text = f"land heat {total:.3g} J{window}"
    if bzm.startup_metal_energy:
        text += f"; start-up metal energy {bzm.startup_metal_energy:.3g} J not shown"
    return text
