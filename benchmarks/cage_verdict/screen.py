"""The crush screen of the reference bearing over the moments of the study, at operating
temperatures and with the clearances as drawn, and the crush threshold of each (seconds):

    python -m benchmarks.cage_verdict.screen OUT.json
"""

from __future__ import annotations

import json
import sys

from .plans import MOMENTS

STATES = {"operating": [], "cold": ["thermal.parts_degC=20"]}


def _screen(moment: float, extra: list[str]) -> dict:
    from bearingsim.pipeline.scene.load import load_scene
    from bearingsim.pipeline.stages.quasistatic import cage_screen, solve

    scene = load_scene("helicopter-b-given-hinge", [f"load.moment={moment}"] + extra)
    s = cage_screen(scene, solve(scene)).to_json_dict()
    s.pop("excursion_per_ball")
    return s


def threshold(extra: list[str], lo: float = 300.0, hi: float = 800.0) -> float:
    """The moment [N m] at which the crush margin reaches 0 (bisection to 0.5 N m)."""
    while hi - lo > 0.5:
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if _screen(mid, extra)["crush_margin"] > 0.0 else (lo, mid)
    return 0.5 * (lo + hi)


def main(argv=None) -> None:
    out = {}
    for state, extra in STATES.items():
        out[state] = {str(m): _screen(m, extra) for m in MOMENTS}
        out[state]["crush_threshold_moment"] = threshold(extra)
        for m in MOMENTS:
            s = out[state][str(m)]
            print(f"{state:9s} {m:4d} N m: {s['regime']:8s} s_pp {s['excursion_peak_to_peak'] * 1e3:.3f} mm, "
                  f"margin {s['crush_margin']:+.2f}, non-guiding gap {s['non_guiding_gap'] * 1e6:.0f} µm",
                  file=sys.stderr)
        print(f"{state}: crush threshold {out[state]['crush_threshold_moment']:.0f} N m", file=sys.stderr)
    with open((argv or sys.argv[1:])[0], "w") as f:
        json.dump(out, f, indent=1)


if __name__ == "__main__":
    main()
