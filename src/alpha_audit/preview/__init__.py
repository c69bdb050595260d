"""Previews: PNG sheets and a self-contained WebGL2 page, pixel-exact to the paper's maths."""

from alpha_audit.preview.compose import (
    MAX_NEAR_SOURCE_COLORS,
    Blend,
    blend_colors,
    composite_masks,
    near_source_canvases,
)
from alpha_audit.preview.sheets import (
    ICON_ALPHA,
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
    "PIXEL_BUDGET",
    "SWATCH_ALPHAS",
    "Blend",
    "Layout",
    "Page",
    "Placement",
    "Sheet",
    "SheetSpec",
    "blend_colors",
    "check_writable",
    "composite_masks",
    "default_alphas",
    "near_source_canvases",
    "paginate",
    "plan_sheets",
    "render_all",
    "render_sheet",
    "write_sheet",
]
