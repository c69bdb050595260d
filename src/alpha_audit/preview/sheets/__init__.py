"""PNG sheets: icons composited on canvases, laid out like the paper's figures.

- :mod:`~alpha_audit.preview.sheets.plan`: which sheets, their names and rows;
- :mod:`~alpha_audit.preview.sheets.surface`: the drawing surface and spacing;
- one module per layout: :mod:`~alpha_audit.preview.sheets.grid` (a sheet per
  canvas and size, a row of icons per coefficient, each icon's contrast ratio
  underneath), :mod:`~alpha_audit.preview.sheets.swatches` (a sheet per canvas,
  palette across, coefficients down: the paper's figure "Outputs for all seven
  Vibrant source colors") and :mod:`~alpha_audit.preview.sheets.compare` (a
  sheet per size, a row per canvas, ``alpha = 1`` beside each other
  coefficient: the paper's gallery figures);
- :mod:`~alpha_audit.preview.sheets.pages` splits sheets over
  :data:`PIXEL_BUDGET` into pages, :mod:`~alpha_audit.preview.sheets.render`
  picks the layout,
  :mod:`~alpha_audit.preview.sheets.write` writes the files.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from alpha_audit.lazy import lazy_exports

if TYPE_CHECKING:
    from alpha_audit.preview.sheets.pages import MAX_SHEETS, paginate
    from alpha_audit.preview.sheets.plan import (
        ICON_ALPHA,
        SWATCH_ALPHAS,
        Alpha,
        ImageFormat,
        Layout,
        Page,
        SheetSpec,
        default_alphas,
        plan_sheets,
    )
    from alpha_audit.preview.sheets.render import render_all, render_sheet
    from alpha_audit.preview.sheets.surface import PIXEL_BUDGET, Placement, Sheet
    from alpha_audit.preview.sheets.write import check_writable, write_sheet

__all__ = [
    "ICON_ALPHA",
    "MAX_SHEETS",
    "PIXEL_BUDGET",
    "SWATCH_ALPHAS",
    "Alpha",
    "ImageFormat",
    "Layout",
    "Page",
    "Placement",
    "Sheet",
    "SheetSpec",
    "check_writable",
    "default_alphas",
    "paginate",
    "plan_sheets",
    "render_all",
    "render_sheet",
    "write_sheet",
]

# Names load on first use: the CLI imports Layout at start-up without Pillow.
__getattr__ = lazy_exports(
    __name__,
    {
        "MAX_SHEETS": "alpha_audit.preview.sheets.pages",
        "paginate": "alpha_audit.preview.sheets.pages",
        "ICON_ALPHA": "alpha_audit.preview.sheets.plan",
        "SWATCH_ALPHAS": "alpha_audit.preview.sheets.plan",
        "Alpha": "alpha_audit.preview.sheets.plan",
        "ImageFormat": "alpha_audit.preview.sheets.plan",
        "Layout": "alpha_audit.preview.sheets.plan",
        "Page": "alpha_audit.preview.sheets.plan",
        "SheetSpec": "alpha_audit.preview.sheets.plan",
        "default_alphas": "alpha_audit.preview.sheets.plan",
        "plan_sheets": "alpha_audit.preview.sheets.plan",
        "render_all": "alpha_audit.preview.sheets.render",
        "render_sheet": "alpha_audit.preview.sheets.render",
        "PIXEL_BUDGET": "alpha_audit.preview.sheets.surface",
        "Placement": "alpha_audit.preview.sheets.surface",
        "Sheet": "alpha_audit.preview.sheets.surface",
        "check_writable": "alpha_audit.preview.sheets.write",
        "write_sheet": "alpha_audit.preview.sheets.write",
    },
)
