"""Reports for ``alpha-audit pair``: a rich table or ``alpha-audit.pair/1`` JSON."""

from __future__ import annotations

from enum import StrEnum
from typing import Any, assert_never

from rich.table import Table
from rich.text import Text

from alpha_audit.pair import PairReport
from alpha_audit.render.common import Renderer, RenderOptions, dumps, records, to_text

__all__ = ["PAIR_SCHEMA", "PairFormat", "pair_document", "render_json", "render_table"]

PAIR_SCHEMA = "alpha-audit.pair/1"


class PairFormat(StrEnum):
    """Output formats of ``alpha-audit pair``."""

    TABLE = "table"
    JSON = "json"

    def renderer(self) -> Renderer[PairReport]:
        """The render function for this format."""
        if self is PairFormat.TABLE:
            return render_table
        if self is PairFormat.JSON:
            return render_json
        assert_never(self)


def pair_document(report: PairReport) -> dict[str, Any]:
    """``{"schema": "alpha-audit.pair/1", "color": ..., "rows": [...]}``."""
    return {"schema": PAIR_SCHEMA, "color": report.color, "rows": records(report.rows)}


def render_json(report: PairReport, options: RenderOptions) -> str:
    """The report as ``alpha-audit.pair/1`` JSON (``options`` change nothing)."""
    return dumps(pair_document(report))


def render_table(report: PairReport, options: RenderOptions) -> str:
    """One row per background x alpha, swatches shown when colour is on."""
    rows = report.rows
    backgrounds = len({r.background for r in rows})
    title = Text(f"{report.color} on {backgrounds} background(s)")  # never rich markup
    table = Table(title=title, title_justify="left")
    for name in ("background", "α", "output", "contrast", "gain", "ΔE00 vs Cs", "clipped"):
        left = name in ("background", "output", "clipped")
        table.add_column(name, justify="left" if left else "right", no_wrap=True)
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
    return to_text(table, options)
