"""The ``grid`` layout: one sheet per canvas and size.

A block per coefficient row, each a grid of icons wrapping to a readable
width, each icon drawn paint group by paint group as its rows draw it, with
its rows' size contrast underneath (underlined below the threshold) and a
small square at its top right when it hard-codes a colour.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray
from PIL import ImageFont

from alpha_audit.model import Icon, IconSet
from alpha_audit.preview.compose import composite_drawings
from alpha_audit.preview.figures import PreviewRows
from alpha_audit.preview.sheets.plan import Alpha, SheetSpec, alpha_label, alphas_for
from alpha_audit.preview.sheets.surface import (
    MARGIN,
    Fonts,
    Placement,
    Sheet,
    Surface,
    available,
    fill_of,
    fixed_mark,
    header_bottom,
    ink_on,
)

__all__ = ["GridFrame", "draw_grid", "grid_frame"]

# Spacing, in px.
_MIN_GAP = 10
"""Smallest gap between icon cells (it grows with the icon size)."""
_LABEL_GAP = 4
"""Between an icon and its contrast label, and below the label."""
_LABEL_PAD = 4
"""Extra height of a contrast label's line over its font size."""
_BLOCK_GAP = 12
"""Above each coefficient block."""
_BLOCK_HEAD = 28
"""From the top of a block's caption to its first row of icons."""
_CAPTION_DROP = 2
"""Lowers the 14 px summary so its baseline meets the 16 px caption's."""
_UNDERLINE_DROP = 1
"""Below the label's font size, where the failing-contrast underline goes."""


@dataclass(frozen=True)
class GridFrame:
    """Everything about a grid sheet but its pixels: sizes, positions and the texts."""

    width: int
    height: int
    cols: int
    gap: int
    cell_w: int
    cell_h: int
    block_h: int
    fonts: Fonts
    header: str
    sub: str
    legend: tuple[str, str]
    blocks: tuple[tuple[NDArray[np.float64], NDArray[np.float64], str, str], ...]


def grid_frame(
    spec: SheetSpec,
    icons: Sequence[Icon],
    alphas: Sequence[Alpha],
    threshold: float,
    max_width: int,
    title: str,
    contrast: Sequence[NDArray[np.float64]] | None = None,
    contrast_ref: NDArray[np.float64] | None = None,
) -> GridFrame:
    """Lay out a grid sheet of ``icons`` without drawing it (its size is known before).

    ``contrast`` is each alpha row's labels (the icons' size contrast on the
    sheet's canvas), ``contrast_ref`` the same at alpha 1; without them the
    counts in the captions are laid out at their widest (every icon passing).
    """
    canvas, size = spec.canvases[0], spec.size
    fonts = Fonts(11 if size <= 24 else 12)
    n = len(icons)

    gap = max(_MIN_GAP, size // 3)
    label_w = Fonts.width(fonts.small, "00.00")
    label_h = fonts.small_px + _LABEL_PAD
    # Each cell names its icon under the ratio; a long name is shortened with
    # "..." to the cell (at most _NAME_CAP wide); the HTML page has every name whole.
    widest = max((Fonts.width(fonts.small, i.name) for i in icons), default=0)
    cell_w = max(size, label_w, min(widest, _NAME_CAP)) + gap
    cell_h = size + _LABEL_GAP + 2 * label_h + gap // 2 + _LABEL_GAP
    cols = max(1, min(n, (max_width - 2 * MARGIN + gap) // cell_w))
    rows = max(1, math.ceil(n / cols))

    passing_ref = n if contrast_ref is None else int((contrast_ref >= threshold).sum())
    blocks = []
    for r, alpha in enumerate(alphas):
        coeff = alphas_for(alpha, icons)
        labels = np.full(n, np.inf) if contrast is None else contrast[r]
        summary = f"   {int((labels >= threshold).sum())} of {n} at or above {threshold:g}:1"
        if alpha != 1.0:
            summary += f" (alpha = 1: {passing_ref})"
        blocks.append((coeff, labels, alpha_label(alpha, icons), summary))

    header = f"{canvas.name}  {canvas.color}"
    sub = f"{title} · {canvas.mode} canvas · {size} px"
    legend = (
        f"under each icon: its rows' size contrast at {size} px (lowest over its paints),",
        f"underlined below {threshold:g}:1; a square at its top right: a hard-coded colour",
    )
    content_w = max(
        cols * cell_w - gap,
        Fonts.width(fonts.title, header),
        Fonts.width(fonts.body, sub),
        *(Fonts.width(fonts.body, line) for line in legend),
        *(Fonts.width(fonts.row, b[2]) + Fonts.width(fonts.body, b[3]) for b in blocks),
    )
    block_h = _BLOCK_GAP + _BLOCK_HEAD + rows * cell_h
    width = 2 * MARGIN + content_w
    height = header_bottom(3) + len(alphas) * block_h + MARGIN
    return GridFrame(
        width, height, cols, gap, cell_w, cell_h, block_h, fonts, header, sub, legend, tuple(blocks)
    )


_NAME_CAP = 120  # px: the widest an icon name makes a grid cell


def _fit(font: ImageFont.FreeTypeFont, text: str, width: int) -> str:
    """``text``, or its longest prefix plus "..." that fits in ``width`` pixels."""
    if Fonts.width(font, text) <= width:
        return text
    lo, hi = 0, len(text)
    while lo < hi:  # the longest prefix that fits with the ellipsis
        mid = (lo + hi + 1) // 2
        if Fonts.width(font, text[:mid] + "...") <= width:
            lo = mid
        else:
            hi = mid - 1
    return text[:lo] + "..."


def draw_grid(
    spec: SheetSpec,
    iconset: IconSet,
    drawn: PreviewRows,
    alphas: Sequence[Alpha],
    threshold: float,
    max_width: int,
    title: str,
) -> Sheet:
    """Draw a grid sheet: a block per coefficient row (see the module docstring)."""
    canvas, size = spec.canvases[0], spec.size
    icons = available(iconset.icons, drawn.drawings, size)
    j = drawn.canvas_index(canvas.name)
    each = {a: drawn.size_contrast(a, size, icons)[:, j] for a in dict.fromkeys(alphas)}
    labels = [each[a] for a in alphas]
    labels_ref = drawn.size_contrast(1.0, size, icons)[:, j]
    frame = grid_frame(spec, icons, alphas, threshold, max_width, title, labels, labels_ref)
    fonts, cols, gap = frame.fonts, frame.cols, frame.gap
    cell_w, cell_h = frame.cell_w, frame.cell_h
    ink = ink_on(canvas.linear)
    fill = fill_of(canvas.linear)
    drawings = [drawn.drawings[i.name] for i in icons]
    background = np.array(canvas.linear)
    out = Surface(spec, frame.width, frame.height, fill)

    out.text((MARGIN, MARGIN), frame.header, fonts.title, ink.text)
    out.text((MARGIN, header_bottom(0)), frame.sub, fonts.body, ink.muted)
    for line, text in enumerate(frame.legend, start=1):
        out.text((MARGIN, header_bottom(line)), text, fonts.body, ink.muted)
    y = header_bottom(3) + _BLOCK_GAP
    for coeff, contrast, label, summary in frame.blocks:
        pixels = composite_drawings(drawings, size, background, coeff, drawn.pipeline)
        used = out.text((MARGIN, y), label, fonts.row, ink.text)
        out.text((MARGIN + used, y + _CAPTION_DROP), summary, fonts.body, ink.muted)
        row_top = y + _BLOCK_HEAD
        for k, icon in enumerate(icons):
            r, c = divmod(k, cols)
            cx = MARGIN + c * cell_w
            cy = row_top + r * cell_h
            x = cx + (cell_w - gap - size) // 2
            out.block(
                Placement(
                    x, cy, size, icon.name, canvas.name, icon.linear, canvas.linear, coeff[k]
                ),
                pixels[k],
            )
            if drawings[k].fixed:
                fixed_mark(out, x, cy, size, (cell_w - gap - size) // 2 + gap, ink.text)
            value = float(contrast[k])
            text = "-" if math.isnan(value) else f"{value:.2f}" if value < 10 else f"{value:.1f}"
            color = ink.text if not value < threshold else ink.alert
            tw = Fonts.width(fonts.small, text)
            tx = cx + (cell_w - gap - tw) // 2
            ty = cy + size + _LABEL_GAP
            out.label((tx, ty), text, fonts.small, color, fill)
            if value < threshold:  # NaN (nothing drawn) is not underlined
                underline = ty + fonts.small_px + _UNDERLINE_DROP
                out.rect((tx, underline, tx + tw, underline + 1), color)
            name = _fit(fonts.small, icon.name, cell_w - gap)
            nx = cx + (cell_w - gap - Fonts.width(fonts.small, name)) // 2
            out.label((nx, ty + fonts.small_px + _LABEL_PAD), name, fonts.small, ink.muted, fill)
        y += frame.block_h
    return out.finish()
