"""Drawing planned sheets: the one place that picks a layout's drawing function."""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from dataclasses import replace
from typing import assert_never

from alpha_audit.color import NON_TEXT_THRESHOLD
from alpha_audit.model import IconSet
from alpha_audit.preview.figures import PreviewRows
from alpha_audit.preview.sheets.compare import draw_compare
from alpha_audit.preview.sheets.grid import draw_grid
from alpha_audit.preview.sheets.plan import Alpha, Layout, SheetSpec, sheet_rows, sheet_title
from alpha_audit.preview.sheets.surface import Sheet
from alpha_audit.preview.sheets.swatches import draw_swatches, swatch_colors

__all__ = ["DEFAULT_MAX_WIDTH", "render_all", "render_sheet"]

DEFAULT_MAX_WIDTH = 1400
"""px; the grid layout wraps its icons to this width (a laptop screen at 100%)."""


def render_sheet(
    spec: SheetSpec,
    iconset: IconSet,
    drawn: PreviewRows,
    *,
    alphas: Sequence[Alpha] | None = None,
    threshold: float = NON_TEXT_THRESHOLD,
    max_width: int = DEFAULT_MAX_WIDTH,
    title: str | None = None,
) -> Sheet:
    """Draw one planned sheet.

    ``drawn`` holds the icons' drawings and rows (icons without a drawing are
    left out); ``alphas`` are the rows (``None`` entries use each icon's own
    coefficient; default :func:`default_alphas`, or :data:`SWATCH_ALPHAS` for
    swatches); ``max_width`` bounds the grid layout's width in pixels.
    """
    label = sheet_title(spec, title or iconset.name)
    rows = sheet_rows(spec.layout, iconset, alphas)
    part = slice(None) if spec.page is None else slice(spec.page.first, spec.page.stop)
    match spec.layout:
        case Layout.GRID:
            paged = replace(iconset, icons=iconset.icons[part])
            return draw_grid(spec, paged, drawn, rows, threshold, max_width, label)
        case Layout.SWATCHES:
            real = [a for a in rows if a is not None]  # swatch rows are never None
            colors = swatch_colors(iconset)[part]
            return draw_swatches(spec, colors, real, threshold, label, drawn.pipeline)
        case Layout.COMPARE:
            paged = replace(iconset, icons=iconset.icons[part])
            return draw_compare(spec, paged, drawn, rows, threshold, label)
        case _:
            assert_never(spec.layout)


def render_all(
    specs: Sequence[SheetSpec],
    iconset: IconSet,
    drawn: PreviewRows,
    *,
    alphas: Sequence[Alpha] | None = None,
    threshold: float = NON_TEXT_THRESHOLD,
    max_width: int = DEFAULT_MAX_WIDTH,
    title: str | None = None,
) -> Iterator[Sheet]:
    """Render ``specs`` one at a time (a sheet can be large; write each, then drop it).

    The keywords are :func:`render_sheet`'s, for every sheet.
    """
    for spec in specs:
        yield render_sheet(
            spec,
            iconset,
            drawn,
            alphas=alphas,
            threshold=threshold,
            max_width=max_width,
            title=title,
        )
