"""Draw the README's and the user guide's pictures from a finished run of helicopter-b.

    bearingsim run helicopter-b && python docs/_hooks/draw_pictures.py runs/helicopter-b

Writes docs/pictures/orbit_helicopter-b.png and burn_zone_helicopter-b.png with `run.plot`
(the report's own figures), small enough to commit.
"""

from __future__ import annotations

import sys
from pathlib import Path

OUT = Path(__file__).resolve().parents[1] / "pictures"


def main(run_dir: str) -> None:
    import bearingsim
    from bearingsim.pipeline.figures import save_png

    run = bearingsim.open_run(run_dir)
    OUT.mkdir(exist_ok=True)
    for name, fig in (("orbit", run.plot.orbit()), ("burn_zone", run.plot.burn_zone())):
        path = OUT / f"{name}_{run.scene.name}.png"
        save_png(fig, path, dpi=72)
        print(f"{path} ({path.stat().st_size // 1000} kB)")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "runs/helicopter-b")
