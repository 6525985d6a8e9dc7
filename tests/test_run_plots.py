"""Plots on results: each `run.plot.*` returns a matplotlib Figure, the report embeds those same
figures, the animation has the frames asked for, the polar burn map keeps an arc across 0°
whole, and a short run says it is too short to settle."""

from __future__ import annotations

import base64
import math
import re

import numpy as np
import pytest
from matplotlib.figure import Figure
from typer.testing import CliRunner

import bearingsim
from bearingsim.pipeline.cli.commands import app
from bearingsim.pipeline.figures import save_png

from .test_render_stage import run_dir  # noqa: F401 - the synthetic finished run


def _with_impacts(run):
    (run / "simulate" / "impacts.csv").write_text(
        "time [s],ball [1],orbital_position [deg],peak_force [N],impact_speed [m/s],duration [s]\n"
        "0.002,3,250.0,40.0,0.1,0.0005\n0.007,5,265.0,30.0,0.1,0.0005\n", encoding="utf-8")
    return bearingsim.open_run(run)


def test_every_run_plot_returns_a_figure(run_dir):  # noqa: F811
    run = _with_impacts(run_dir[0])
    for name in ("orbit", "speed", "impacts", "burn_zone", "load_distribution"):
        assert isinstance(getattr(run.plot, name)(), Figure), name
    assert isinstance(run.plot.load_distribution(polar=False), Figure)


def test_the_report_embeds_the_figures_run_plot_draws(run_dir):  # noqa: F811
    """One drawing code: the orbit and the polar burn map in report.html are, byte for byte,
    the PNGs of run.plot.orbit() and run.plot.burn_zone()."""
    run_path = run_dir[0]
    assert CliRunner().invoke(app, ["render", str(run_path)]).exit_code == 0
    run = bearingsim.open_run(run_path)
    page = (run_path / "report" / "report.html").read_text(encoding="utf-8")
    embedded = set(re.findall(r'src="data:image/png;base64,([^"]+)"', page))
    for name, fig in (("verdict_orbit.png", run.plot.orbit()), ("burn_zone_polar.png", run.plot.burn_zone())):
        path = run_path / "report" / f"again-{name}"
        save_png(fig, path)
        assert base64.b64encode(path.read_bytes()).decode("ascii") in embedded, name
        path.unlink()
    assert len(re.findall(r'src="data:image/png;base64,', page)) == len(embedded)  # each figure once
    first = page[:page.index("<details")]
    assert "verdict_orbit.png" in first and "burn_zone_polar.png" in first and "Cage pressed" in first


def test_the_animation_has_the_frames_asked_for(run_dir, tmp_path):  # noqa: F811
    from PIL import Image

    run = bearingsim.open_run(run_dir[0])
    path = run.plot.animate(tmp_path / "orbit.gif", frames=12, fps=10)
    with Image.open(path) as gif:
        assert gif.n_frames == 12
    with pytest.raises(ValueError, match=r"\.gif or an \.mp4"):
        run.plot.animate(tmp_path / "orbit.avi")


def test_render_animate_writes_a_gif(run_dir):  # noqa: F811
    from PIL import Image

    result = CliRunner().invoke(app, ["render", str(run_dir[0]), "--animate"])
    assert result.exit_code == 0, result.output
    with Image.open(run_dir[0] / "animation" / "cage_orbit.gif") as gif:
        assert gif.n_frames == 120  # the default: 120 frames over the last cage revolutions


def test_the_polar_burn_map_keeps_an_arc_across_zero_whole_and_the_hot_sector_up():
    from bearingsim.pipeline.figures.burn_polar import burn_zone_polar_figure

    energy = np.zeros(360)
    energy[350], energy[5] = 2.0, 1.0  # hot at 350.5°, the arc 340–380° (20°) crosses 0°
    fig = burn_zone_polar_figure(energy, arc=(math.radians(340.0), math.radians(380.0)))
    ax = fig.axes[0]
    assert ax.get_theta_offset() == pytest.approx(math.pi / 2 - math.radians(350.5))
    (wedge,) = [c for c in ax.collections if c.get_label().startswith("80 %")]
    theta = np.degrees(wedge.get_paths()[0].vertices[:, 0])
    assert theta.min() == pytest.approx(340.0) and theta.max() == pytest.approx(380.0)  # one piece, not two
    assert "340–20°" in wedge.get_label()


def test_the_burn_map_names_the_guiding_land():
    from bearingsim.pipeline.figures.burn_polar import burn_zone_polar_figure
    from bearingsim.pipeline.render.run_plots import land_name

    scene = bearingsim.load_scene("helicopter-b-given-hinge")
    assert land_name(scene) == "outer-race land"
    assert land_name(scene.replace(**{"cage.guidance": "inner"})) == "inner-race land"
    energy = np.ones(36)
    assert "inner-race land" in burn_zone_polar_figure(energy, land="inner-race land").axes[0].get_title()
    ball = burn_zone_polar_figure(energy, land=None)
    assert "no land burn zone" in ball.axes[0].texts[0].get_text()


def test_a_short_run_says_too_short_to_settle(run_dir):  # noqa: F811
    """The synthetic run is 10 ms, far less than ten cage revolutions."""
    run = bearingsim.open_run(run_dir[0])
    assert "too short to settle" in repr(run)
    assert "too short to settle" in run.summary["verdict"]["text"]


def test_a_sweep_of_one_key_plots_lines():
    from bearingsim.pipeline.sweep.stability_map import stability_map_figure

    rows = [{"load.moment": m, "cage_class": c, "cage_metal_contact_fraction": f, "cage_eps_mean": e,
             "too_short_to_settle": s} for m, c, f, e, s in
            ((200.0, "centred", 0.0, 0.3, False), (430.0, "pressed", 0.0, 0.9, True), (600.0, "crushed", 0.8, 1.02, False))]
    fig = stability_map_figure(rows, ["load.moment"])
    ax = fig.axes[0]
    assert ax.get_xlabel().startswith("load.moment") or "moment" in ax.get_xlabel()
    assert not ax.collections  # lines and markers, no 2-D cells
    assert "too short to settle" in [t.get_text() for t in ax.get_legend().get_texts()]
