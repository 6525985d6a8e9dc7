"""The tolerance analysis for people (`bearingsim tolerances`) and its command-line inputs."""

from __future__ import annotations

import tomllib
from pathlib import Path

from rich.console import Console
from rich.table import Table

from ..console import styled
from ..scene.schema import SceneError


def tolerance_overrides(path: Path | None, samples: int | None, seed: int | None) -> list[str]:
    """`--set` overrides for a tolerance file's [tolerances] table, --samples and --seed."""
    out = []
    if path is not None:
        try:
            if not Path(path).is_file():
                raise SceneError("--tolerances", f"{path} is not a file; give a TOML file with a [tolerances] table")
            if Path(path).stat().st_size > 1_000_000:
                raise SceneError("--tolerances", f"{path} is larger than 1 MB; a tolerance table is a few lines")
            table = tomllib.loads(Path(path).read_text(encoding="utf-8"))
        except (OSError, UnicodeDecodeError, tomllib.TOMLDecodeError) as exc:
            raise SceneError("--tolerances", f"cannot read {path}: {exc}") from None
        if not isinstance(table.get("tolerances"), dict):
            raise SceneError("--tolerances", f"{path} has no [tolerances] table")
        for key, value in table["tolerances"].items():
            if isinstance(value, dict):
                inner = ", ".join(f"{k} = {_toml(v)}" for k, v in value.items())
                out.append(f"tolerances.{key}={{{inner}}}")
            else:
                out.append(f"tolerances.{key}={_toml(value)}")
    if samples is not None:
        out.append(f"tolerances.samples={samples}")
    if seed is not None:
        out.append(f"tolerances.seed={seed}")
    return out


def _toml(value) -> str:
    """`value` as a TOML literal (true, not Python's True), as the file wrote it."""
    import tomli_w

    try:
        return tomli_w.dumps({"v": value})[len("v = "):].strip()
    except (TypeError, ValueError):
        return repr(value)


def print_tolerances(result: dict, console: Console) -> None:
    """Probabilities, the margin's percentiles, the drivers and the 5th-percentile stack."""
    t = result["crush_probability"]
    screen = result.get("cage_screen", {})
    probs = t["regime_probability"]
    console.print(styled((f"crush probability over {t.get('valid_samples', t['samples'])} tolerance stacks", "bold"),
                         f" (seed {t['seed']}, operating temperatures; docs/model.md §10.2)"))
    for name in ("free", "pressed", "crushed"):
        p = probs[name]
        console.print(f"  P({name:<7}) = {100 * p['probability']:6.2f} % ± {100 * p['standard_error']:.2f} %")
    invalid = t.get("invalid_stacks") or {}
    if invalid.get("count"):
        keys = ", ".join(f"{k} ({n})" for k, n in sorted(invalid["by_key"].items(), key=lambda kv: -kv[1]))
        console.print(styled(("  warning:", "yellow"), f" {invalid['count']} of {t['samples']} stacks "
                             f"({100 * invalid['fraction']:.2g} %) are no bearing the model covers and are left "
                             f"out of these probabilities; they fail the scene's checks of {keys}"), soft_wrap=True)
    if screen:
        console.print(f"  nominal stack: {screen['regime']}, margin {screen['crush_margin']:.2f}")
    q = t["margin_percentiles"]
    console.print("  crush margin percentiles: " + ", ".join(f"{k} {v:.2f}" for k, v in q.items()))
    if t["non_guiding_touch_probability"] > 0:
        console.print(f"  P(cage touches the non-guiding land) = {100 * t['non_guiding_touch_probability']:.2f} % "
                      "(the model applies no force there)")
    table = Table(box=None, title="drivers (ranked)", title_justify="left")
    # the key stays whole (it is what --set takes); the description wraps instead
    table.add_column("what drives the margin", no_wrap=True)
    for heading in ("varied as", "share of variance", "rank correlation"):
        table.add_column(heading)
    for row in t["drivers"]:
        table.add_row(row["quantity"], t["tolerances"][row["quantity"]], f"{100 * row['variance_share']:.1f} %",
                      f"{row['spearman']:+.2f}")
    console.print(table)
    if t.get("drivers_linear_r2") is not None:
        console.print(f"  the shares are those of a linear fit that explains {100 * t['drivers_linear_r2']:.0f} % of "
                      "the margin's variance" + ("" if t["drivers_linear_r2"] > 0.8 else
                                                 "; the margin responds non-linearly: rank by the rank correlation"))
    console.print(f"  stack at the 5th percentile of margin ({t['stack_at_p5']['margin']:.2f}), to confirm "
                  "with a dynamic run:\n    " + " ".join(f"--set {o}" for o in t["stack_at_p5_overrides"]),
                  highlight=False, soft_wrap=True, markup=False)
