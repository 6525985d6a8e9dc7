"""The crush screen of the reference bearing over the moments of the study (seconds):

    python -m benchmarks.cage_verdict.screen OUT.json
"""

from __future__ import annotations

import json
import sys

from .plans import MOMENTS


def main(argv=None) -> None:
    from bearingsim.pipeline.scene import load_scene
    from bearingsim.pipeline.stages.quasistatic import cage_screen, solve

    out = {}
    for m in MOMENTS:
        scene = load_scene("helicopter-b-given-hinge", [f"load.moment={m}"])
        s = cage_screen(scene, solve(scene)).to_json_dict()
        s.pop("excursion_per_ball")
        out[str(m)] = s
        print(f"{m:4d} N m: {s['regime']:8s} s_pp {s['excursion_peak_to_peak'] * 1e3:.3f} mm, "
              f"margin {s['crush_margin']:+.2f}, push {round(s['push_azimuth_deg']) % 360} deg", file=sys.stderr)
    with open((argv or sys.argv[1:])[0], "w") as f:
        json.dump(out, f, indent=1)


if __name__ == "__main__":
    main()
