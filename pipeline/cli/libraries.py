"""`bearingsim lubricants` and `bearingsim materials`: the built-in data sets, with their sources
(dynamics/lubrication/data, dynamics/materials/data; docs/scenes.md)."""

from __future__ import annotations

from rich.console import Console
from rich.table import Table

_TEMPERATURES_DEGC = (40.0, 100.0)


def lubricant_rows() -> list[dict]:
    """One row a built-in lubricant: viscosities at 40 and 100 degC, model, alpha*, source."""
    from ...dynamics.lubrication.lubricant import builtin_lubricant_names, load_builtin_lubricant

    rows = []
    for name in builtin_lubricant_names():
        lub = load_builtin_lubricant(name)
        row = {"name": name, "description": lub.description, "model": lub.viscosity_model, "source": lub.source}
        for t in _TEMPERATURES_DEGC:
            hot = lub.at_temperature(t)
            row[f"eta_{t:g}"] = hot.eta0  # Pa.s
            row[f"nu_{t:g}"] = hot.eta0 / hot.density_at_temperature()  # m^2/s
            row[f"alpha_{t:g}"] = hot.alpha_star  # 1/Pa
        rows.append(row)
    return rows


def print_lubricants(console: Console) -> None:
    rows = lubricant_rows()
    table = Table("lubricant", "model", "η 40 °C", "ν 40 °C", "η 100 °C", "ν 100 °C", "α* 40 °C", "α* 100 °C",
                  box=None, title=("built-in lubricants: [lubricant] name = \"...\" (any other key refines "
                                   "the set); η in mPa·s, ν in cSt (mm²/s), α* in 1e-8 1/Pa"),
                  title_justify="left")
    for r in rows:
        table.add_row(r["name"], r["model"], f"{r['eta_40'] * 1e3:.3g}", f"{r['nu_40'] * 1e6:.3g}",
                      f"{r['eta_100'] * 1e3:.3g}", f"{r['nu_100'] * 1e6:.3g}", f"{r['alpha_40'] * 1e8:.3g}",
                      f"{r['alpha_100'] * 1e8:.3g}")
    console.print(table)
    _print_sources(console, [(r["name"], r["description"], r["source"]) for r in rows])


def _print_sources(console: Console, items) -> None:
    """What each set is and where its numbers come from (the data file has them number by number)."""
    for name, description, source in items:
        console.print(f"  {name}: {description}. Source: {source}", highlight=False, soft_wrap=True)


def print_materials(console: Console) -> None:
    from ...dynamics.materials.library import builtin_material_names, load_builtin_material

    table = Table("material", "for", "E [GPa]", "ν", "ρ [kg/m³]", "α [1e-6/K]", "max [°C]", box=None,
                  title=("built-in materials: [materials] cage = \"name\", or { name = \"...\", key = value } "
                         "to refine one; max: continuous operating temperature"), title_justify="left")
    named = [load_builtin_material(name) for name in builtin_material_names()]
    for m in named:
        mat = m.material
        table.add_row(m.name, ", ".join(m.roles), f"{mat.youngs_modulus * 1e-9:.4g}", f"{mat.poisson_ratio:.3g}",
                      f"{mat.density:.4g}", f"{mat.thermal_expansion * 1e6:.3g}",
                      "—" if m.max_temperature_degC is None else f"{m.max_temperature_degC:g}")
    console.print(table)
    _print_sources(console, [(m.name, m.description, m.source) for m in named])
