"""Timing of the quasi-static solver on the helicopter scenes (docs/model.md §2).

Run: python -m benchmarks.quasistatic   (first call includes numba compile or cache load)
"""

from __future__ import annotations

import math
import time


def main() -> None:
    start = time.perf_counter()
    from bearingsim.dynamics.geometry import BearingGeometry, Material
    from bearingsim.dynamics.operating_point import OperatingPoint
    from bearingsim.dynamics.quasistatic.solver import solve_quasistatic
    import_time = time.perf_counter() - start

    steel = Material(208e9, 0.3, 7850.0)
    geometry = BearingGeometry(0.01905, 22, 0.1584, 0.1573, 0.009753, 0.009906,
                               inner_shoulder_diameter=0.150, outer_shoulder_diameter=0.166)
    speed = 3060.0 * 2.0 * math.pi / 60.0
    print(f"import: {import_time:.3f} s")
    print(f"{'case':<14}{'call':<7}{'time [s]':>10}{'iters':>7}{'u_z [µm]':>10}{'θ_y [mrad]':>12}"
          f"{'Q_i max [N]':>13}{'p_max [GPa]':>13}{'K asym':>10}")
    for name, moment in (("helicopter-a", 100.0), ("helicopter-b", 430.0)):
        for call in ("first", "second"):
            start = time.perf_counter()
            res = solve_quasistatic(geometry, steel, steel,
                                    OperatingPoint(axial=34000.0, moment=moment, inner_speed=speed))
            elapsed = time.perf_counter() - start
            print(f"{name:<14}{call:<7}{elapsed:>10.4f}{res.iterations:>7d}{res.inner_displacement[2] * 1e6:>10.2f}"
                  f"{res.inner_tilt[1] * 1e3:>12.4f}{res.inner_load.max():>13.1f}"
                  f"{res.max_pressure_inner.max() / 1e9:>13.3f}{res.stiffness_asymmetry:>10.1e}")


if __name__ == "__main__":
    main()
