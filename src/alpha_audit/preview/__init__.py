"""Previews: PNG sheets and a self-contained WebGL2 page, pixel-exact to the paper's maths."""

from __future__ import annotations

from typing import TYPE_CHECKING

from alpha_audit.lazy import lazy_exports

if TYPE_CHECKING:
    from alpha_audit.preview.compose import (
        MAX_NEAR_SOURCE_COLORS,
        Blend,
        Drawing,
        Layer,
        blend_colors,
        composite_drawings,
        near_source_canvases,
    )
    from alpha_audit.preview.sheets import (
        ICON_ALPHA,
        MAX_SHEETS,
        PIXEL_BUDGET,
        SWATCH_ALPHAS,
        Layout,
        Page,
        Placement,
        Sheet,
        SheetSpec,
        check_writable,
        default_alphas,
        paginate,
        plan_sheets,
        render_all,
        render_sheet,
        write_sheet,
    )

__all__ = [
    "ICON_ALPHA",
    "MAX_NEAR_SOURCE_COLORS",
    "MAX_SHEETS",
    "PIXEL_BUDGET",
    "SWATCH_ALPHAS",
    "Blend",
    "Drawing",
    "Layer",
    "Layout",
    "Page",
    "Placement",
    "Sheet",
    "SheetSpec",
    "blend_colors",
    "check_writable",
    "composite_drawings",
    "default_alphas",
    "near_source_canvases",
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
        "MAX_NEAR_SOURCE_COLORS": "alpha_audit.preview.compose",
        "Blend": "alpha_audit.preview.compose",
        "blend_colors": "alpha_audit.preview.compose",
        "Drawing": "alpha_audit.preview.compose",
        "Layer": "alpha_audit.preview.compose",
        "composite_drawings": "alpha_audit.preview.compose",
        "near_source_canvases": "alpha_audit.preview.compose",
        "ICON_ALPHA": "alpha_audit.preview.sheets",
        "MAX_SHEETS": "alpha_audit.preview.sheets",
        "PIXEL_BUDGET": "alpha_audit.preview.sheets",
        "SWATCH_ALPHAS": "alpha_audit.preview.sheets",
        "Layout": "alpha_audit.preview.sheets",
        "Page": "alpha_audit.preview.sheets",
        "Placement": "alpha_audit.preview.sheets",
        "Sheet": "alpha_audit.preview.sheets",
        "SheetSpec": "alpha_audit.preview.sheets",
        "check_writable": "alpha_audit.preview.sheets",
        "default_alphas": "alpha_audit.preview.sheets",
        "paginate": "alpha_audit.preview.sheets",
        "plan_sheets": "alpha_audit.preview.sheets",
        "render_all": "alpha_audit.preview.sheets",
        "render_sheet": "alpha_audit.preview.sheets",
        "write_sheet": "alpha_audit.preview.sheets",
    },
)
