"""Reports for ``alpha-audit pair``: a rich table or ``alpha-audit.pair/1`` JSON."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import asdict

from rich.table import Table
from rich.text import Text

from alpha_audit.pair import PairRow
from alpha_audit.render import RenderOptions
from alpha_audit.render.json import dumps
from alpha_audit.render.table import to_text

__all__ = ["PAIR_SCHEMA", "pair_json", "pair_table_text"]

PAIR_SCHEMA = "alpha-audit.pair/1"


def pair_json(color: str, rows: Sequence[PairRow]) -> str:
    """``{"schema": "alpha-audit.pair/1", "color": ..., "rows": [...]}``."""
    return dumps({"schema": PAIR_SCHEMA, "color": color, "rows": [asdict(r) for r in rows]})


def pair_table_text(color: str, rows: Sequence[PairRow], options: RenderOptions) -> str:
    """One row per background x alpha, swatches shown when colour is on.

    A second table puts the linear pipeline beside ``css`` (what a browser draws for
    the same alpha: gamma-space blend, 8-bit) for every alpha in [0, 1) — the only
    coefficients CSS can express besides 1, where both agree.
    """
    backgrounds = len({r.background for r in rows})
    table = Table(title=f"{color} on {backgrounds} background(s)", title_justify="left")
    for name in ("background", "α", "output", "contrast", "gain", "ΔE00 vs Cs", "clipped"):
        justify = "left" if name in ("background", "output", "clipped") else "right"
        table.add_column(name, justify=justify, no_wrap=True)
    for r in rows:
        table.add_row(
            Text(r.background, style=f"on {r.background}"),
            f"{r.alpha:g}",
            Text(r.output, style=f"on {r.output}"),
            f"{r.contrast_ref:.3f} → {r.contrast:.3f}",
            Text(f"{r.gain:+.3f}", style="green" if r.gain >= 0 else "red"),
            f"{r.delta_e_from_source:.2f}",
            "yes" if r.clipped else "",
        )
    text = to_text(table, options)
    drawable = [r for r in rows if r.css_output is not None and r.alpha != 1.0]
    if not drawable:
        return text
    css = Table(
        title="the same in a browser (pipeline css; alpha in [0, 1])",
        title_justify="left",
    )
    for name in ("background", "α", "linear", "css", "contrast linear → css"):
        css.add_column(name, justify="right" if name in ("α",) else "left", no_wrap=True)
    for r in drawable:
        css.add_row(
            Text(r.background, style=f"on {r.background}"),
            f"{r.alpha:g}",
            Text(r.output, style=f"on {r.output}"),
            Text(str(r.css_output), style=f"on {r.css_output}"),
            f"{r.contrast:.3f} → {r.css_contrast:.3f}",
        )
    return text + to_text(css, options)
