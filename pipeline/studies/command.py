"""`bearingsim bench SCENE`: the work–precision studies for one scene.

Dynamics: `work_precision` (error against wall time, one curve per method, solve_ivp
baseline). Identification (scenes whose hinge is identified by FE): `identify_precision`
(hinge stiffness against mesh size and order, Richardson, wall time and memory).
"""

from __future__ import annotations

from pathlib import Path


def run_bench(scene, identify_dir, quick: bool, out_dir: Path, with_fe: bool = True,
              progress=print) -> tuple[list[Path], str]:
    """Run the studies; returns (written files, markdown tables)."""
    from ..stages.simulate import build_model

    from . import work_precision as wp

    progress(f"{scene.name}: quasi-static start and model")
    params, start = build_model(scene, identify_dir)
    study = wp.run_study(params, start, scene.solver, quick, progress=progress)
    paths = wp.write_study(study, Path(out_dir))
    tables = ["## Dynamics: error against wall time", "", wp.markdown_table(study)]
    if with_fe and scene.fe is not None:
        from ..stages.identify import ring_seat

        from . import identify_precision as ip

        fe_study = ip.run_identification_study(scene.fe, ring_seat(scene), quick, progress=progress)
        paths += ip.write_identification(fe_study, Path(out_dir))
        tables += ["", "## Identification: hinge stiffness against mesh", "", ip.markdown_table(fe_study)]
    return paths, "\n".join(tables)
