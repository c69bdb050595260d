"""Previews: PNG sheets and a self-contained WebGL2 page, pixel-exact to the paper's maths."""

from alpha_audit.preview.compose import (
    Blend,
    blend_colors,
    composite_masks,
    near_source_canvases,
)
from alpha_audit.preview.sheets import (
    ICON_ALPHA,
    SWATCH_ALPHAS,
    Layout,
    Placement,
    Sheet,
    SheetSpec,
    check_writable,
    default_alphas,
    plan_sheets,
    render_all,
    render_sheet,
    write_sheet,
)

__all__ = [
    "ICON_ALPHA",
    "SWATCH_ALPHAS",
    "Blend",
    "Layout",
    "Placement",
    "Sheet",
    "SheetSpec",
    "blend_colors",
    "check_writable",
    "composite_masks",
    "default_alphas",
    "near_source_canvases",
    "plan_sheets",
    "render_all",
    "render_sheet",
    "write_sheet",
]
