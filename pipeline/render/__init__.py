"""Renders and the run report (docs/model.md §11): FE deflections, burn zone, HTML page.

Reads saved results only and never re-solves (docs/contributing.md rule 5). pyvista/VTK and
matplotlib are imported inside the functions that draw (rule 6), so importing this
package costs nothing. Entry points:

- `run_report.write_run_report` — everything the `report` stage writes;
- `fe_deflection.render_case` — one FE load case (PNG + ParaView `.vtu`);
- `burn_zone_data.burn_zone_map` + `burn_zone.render_burn_zone_3d` /
  `render_burn_zone_map` — the burn zone on the outer race;
- `paraview_series.write_paraview` — the ParaView motion series and the land heat on the
  outer race (`body_surfaces` gives the bodies' surfaces);
- `report.write_report_html` — the self-contained page.
"""
