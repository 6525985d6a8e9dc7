"""How many chords the cone rule needs when the spin pole lies just outside the contact ellipse.

    python -m benchmarks.cone_edge            # ~30 s on 2 cores

The fast traction (dynamics/traction/fast.py) integrates over chords from the spin pole once the
pole lies outside the ellipse (|P| >= 1 ellipse radii). Close to the edge the cone of chords opens
to half a turn while, from near the end of the major axis, the contact fills a narrow wedge of it
(docs/model.md §6.4, *The pole just outside the edge*). For each chord count of the edge band
(`FastTraction.build(n_cone=(16, n))`), this prints the worst force and spin-moment error against
the (128, 1024) quadrature over 36 pole directions x 6 loads (inner and outer race, 100-6000 N)
x 2 speeds x 3 spin levels, at |P| = 1 + 1e-9 and 1 + 1e-3. Metrics as tests/test_traction_fast.py
(`benchmarks.traction.worst_errors`).
"""

from __future__ import annotations

import math

import numpy as np

from benchmarks.traction import contact, worst_errors

CHORDS = (24, 40, 48, 56, 64)
DISTANCES = (1.0 + 1e-9, 1.0 + 1e-3)
CONTACTS = [("inner", 6000.0), ("inner", 3000.0), ("inner", 300.0),
            ("outer", 3000.0), ("outer", 1000.0), ("outer", 100.0)]


def main() -> None:
    from bearingsim.dynamics.lubrication.lubricant import load_builtin_lubricant
    from bearingsim.dynamics.traction.fast import FastTraction
    from bearingsim.dynamics.traction.quadrature import traction_quadrature

    lub = load_builtin_lubricant("nato-o156")
    rules = {n: FastTraction.build(lub, n_cone=(16, n)) for n in CHORDS}
    print(f"{'|P|':<14}" + "".join(f"{f'{n} chords: F / M':>24}" for n in CHORDS))
    for rho in DISTANCES:
        points = []
        for race, load in CONTACTS:
            for speed, angle in ((1.0, 30.0), (0.3, 25.0)):
                a, b, p_h, h, u = contact(lub, race == "inner", math.cos(math.radians(angle)), load, speed)
                for spin in (0.01, 0.03, 0.1):
                    w = spin * u / b
                    for off in np.linspace(0.0, 2.0 * math.pi, 37)[:-1]:
                        X, Y = rho * math.sin(off), -rho * math.cos(off)  # pole in ellipse radii
                        points.append((a, b, p_h, h, w * b * Y, -w * a * X, w))
        P = np.array(points)
        ref = [traction_quadrature(*p[:4], lub.eyring_stress, lub.model_code, lub.rheology_params(), *p[4:], 128, 1024)
               for p in P]
        worst = [worst_errors(rule, P, ref) for rule in rules.values()]
        print(f"{rho:<14.9f}" + "".join(f"{f'{w[0]:.2%} / {w[1]:.2%}':>24}" for w in worst), flush=True)
    print("worst |dF|/|F| / |dM_z|/max(|M_z|, |F| b) against the (128, 1024) quadrature")


if __name__ == "__main__":
    main()
