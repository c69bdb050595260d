"""Reports for ``alpha-audit pair``: a rich table or ``alpha-audit.pair/1`` JSON."""

from __future__ import annotations

from typing import Any

from rich.console import RenderableType
from rich.text import Text

from alpha_audit.pair import PairReport
from alpha_audit.render.common import (
    RenderOptions,
    dumps,
    fitted_table,
    number_column,
    records,
    to_text,
)

__all__ = ["PAIR_SCHEMA", "pair_document", "render_json", "render_table"]

PAIR_SCHEMA = "alpha-audit.pair/1"
# Every column is a figure: none is ever cut (the first table fits 60 columns).
_LEFT = frozenset({"background", "output", "clipped", "linear", "css"})


def _table(title: str | Text, headers: tuple[str, ...], cells: list[Any]) -> RenderableType:
    columns = [number_column(h, "left" if h in _LEFT else "right") for h in headers]
    return fitted_table(columns, cells, title=title, padding=(0, 0))


def pair_document(report: PairReport) -> dict[str, Any]:
    """``{"schema": "alpha-audit.pair/1", "color": ..., "rows": [...]}``."""
    return {
        "schema": PAIR_SCHEMA,
        "color": report.color,
        "rows": records(report.rows),
        "gamut": records(report.gamut),
    }


def render_json(report: PairReport, options: RenderOptions) -> str:
    """The report as ``alpha-audit.pair/1`` JSON (``options`` change nothing)."""
    return dumps(pair_document(report))


def render_table(report: PairReport, options: RenderOptions) -> str:
    """One row per background x alpha, swatches shown when colour is on.

    A second table puts the linear pipeline beside ``css`` (what a browser draws for
    the same alpha: gamma-space blend, 8-bit) for every alpha in [0, 1) — the only
    coefficients CSS can express besides 1, where both agree.
    """
    rows = report.rows
    backgrounds = len({r.background for r in rows})
    # Never rich markup; the title also says what the ΔE00 column measures.
    title = Text(f"{report.color} on {backgrounds} background(s); ΔE00 from {report.color}")
    cells = [
        (
            Text(r.background, style=f"on {r.background}"),
            f"{r.alpha:g}",
            Text(r.output, style=f"on {r.output}"),
            f"{r.contrast_ref:.3f} → {r.contrast:.3f}",
            Text(f"{r.gain:+.3f}", style="green" if r.gain >= 0 else "red"),
            f"{r.delta_e_from_source:.2f}",
            "yes" if r.clipped else "",
        )
        for r in rows
    ]
    headers = ("background", "α", "output", "contrast", "gain", "ΔE00", "clipped")
    text = to_text(_table(title, headers, cells), options)
    if report.gamut:
        lines = [
            f"outside sRGB: {g.text} -> {g.output} (gamut {g.policy}, CIEDE2000 {g.delta_e:.2f})"
            for g in report.gamut
        ]
        text += to_text(Text("\n".join(lines)), options)
    drawable = [r for r in report.rows if r.css_output is not None and r.alpha != 1.0]
    if not drawable:
        return text
    css_rows = [
        (
            Text(r.background, style=f"on {r.background}"),
            f"{r.alpha:g}",
            Text(r.output, style=f"on {r.output}"),
            Text(str(r.css_output), style=f"on {r.css_output}"),
            f"{r.contrast:.3f} → {r.css_contrast:.3f}",
        )
        for r in drawable
    ]
    css = _table(
        "the same in a browser (pipeline css; alpha in [0, 1])",
        ("background", "α", "linear", "css", "contrast linear → css"),
        css_rows,
    )
    return text + to_text(css, options)
