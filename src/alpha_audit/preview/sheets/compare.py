"""The ``compare`` layout: one sheet per size, a row per canvas.

Each row shows the whole set at ``alpha = 1`` beside each other coefficient
row, on panels of the canvas colour (the paper's gallery figures), on a white
page.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from alpha_audit.color import parse_color, srgb_decode
from alpha_audit.model import Icon, IconSet
from alpha_audit.preview.compose import composite_drawings
from alpha_audit.preview.figures import PreviewRows
from alpha_audit.preview.sheets.plan import (
    ICON_ALPHA,
    Alpha,
    SheetSpec,
    alpha_label,
    alphas_for,
)
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
    rgb,
)

__all__ = ["PAGE_COLOR", "CompareFrame", "compare_frame", "draw_compare", "panel_columns"]

PAGE_COLOR = "#ffffff"
"""The page around the canvas panels."""

# Spacing, in px.
_MIN_COLUMNS = 12
"""Panels are at least this many icons wide (when there are that many)."""
_MIN_GAP, _MIN_PAD = 4, 12
"""Smallest gap between icons and padding inside a panel (both grow with the size)."""
_PANEL_GAP = 20
"""Between the panels of one row."""
_HEADER_GAP = 6
"""Between the header and the first canvas row."""
_CAPTION_TOP = 24
"""From the top of a canvas row to its panels' captions."""
_CAPTION_TO_PANEL = 2 + 8
"""From a 14 px caption's bottom to its panel (2 px of descent, 8 px of air)."""
_ROW_GAP = 22
"""Between one canvas row's panels and the next row."""
_CAPTION_DROP = 2
"""Lowers the 14 px canvas colour so its baseline meets the 16 px name's."""


def panel_columns(n: int) -> int:
    """Icons across a panel: about twice as wide as tall, at least :data:`_MIN_COLUMNS`."""
    return max(1, min(n, max(_MIN_COLUMNS, math.ceil(math.sqrt(2 * n)))))


@dataclass(frozen=True)
class CompareFrame:
    """Everything about a comparison sheet but its pixels."""

    width: int
    height: int
    panels: tuple[Alpha, ...]
    cols: int
    gap: int
    pad: int
    panel_w: int
    panel_h: int
    row_head: int
    row_h: int
    top: int
    fonts: Fonts
    header: str
    legend: str


def compare_frame(
    spec: SheetSpec,
    icons: Sequence[Icon],
    alphas: Sequence[Alpha],
    title: str,
) -> CompareFrame:
    """Lay out a comparison sheet of ``icons`` on ``spec.canvases`` without drawing it."""
    size = spec.size
    n = len(icons)
    fonts = Fonts(12)
    panels: list[Alpha] = [1.0, *(a for a in alphas if a != 1.0)]
    if len(panels) == 1:
        panels.append(ICON_ALPHA)
    gap = max(_MIN_GAP, size // 5)
    pad = max(_MIN_PAD, size // 3)
    cols = panel_columns(n)
    rows = max(1, math.ceil(n / cols))
    panel_w = 2 * pad + cols * (size + gap) - gap
    panel_h = 2 * pad + rows * (size + gap) - gap
    row_head = _CAPTION_TOP + fonts.body_px + _CAPTION_TO_PANEL
    header = f"{title} · {size} px"
    legend = "each row: one canvas; left to right: " + ", ".join(
        alpha_label(a, icons) for a in panels
    )
    legend += "; counts: icons whose rows' size contrast passes; square: a hard-coded colour"
    content_w = max(
        len(panels) * (panel_w + _PANEL_GAP) - _PANEL_GAP,
        Fonts.width(fonts.title, header),
        Fonts.width(fonts.body, legend),
    )
    top = header_bottom(1) + _HEADER_GAP
    row_h = row_head + panel_h + _ROW_GAP
    width = 2 * MARGIN + content_w
    height = top + len(spec.canvases) * row_h - _ROW_GAP + MARGIN
    return CompareFrame(
        width,
        height,
        tuple(panels),
        cols,
        gap,
        pad,
        panel_w,
        panel_h,
        row_head,
        row_h,
        top,
        fonts,
        header,
        legend,
    )


def draw_compare(
    spec: SheetSpec,
    iconset: IconSet,
    drawn: PreviewRows,
    alphas: Sequence[Alpha],
    threshold: float,
    title: str,
) -> Sheet:
    """Draw a comparison sheet (see the module docstring)."""
    size = spec.size
    icons = available(iconset.icons, drawn.drawings, size)
    n = len(icons)
    frame = compare_frame(spec, icons, alphas, title)
    fonts, panels, cols, gap, pad = frame.fonts, frame.panels, frame.cols, frame.gap, frame.pad
    panel_w, panel_h, row_head, row_h = frame.panel_w, frame.panel_h, frame.row_head, frame.row_h
    top = frame.top
    page = srgb_decode(parse_color(PAGE_COLOR))
    ink = ink_on((float(page[0]), float(page[1]), float(page[2])))
    out = Surface(spec, frame.width, frame.height, rgb(PAGE_COLOR))
    out.text((MARGIN, MARGIN), frame.header, fonts.title, ink.text)
    out.text((MARGIN, header_bottom(0)), frame.legend, fonts.body, ink.muted)
    drawings = [drawn.drawings[i.name] for i in icons]
    contrast = {a: drawn.size_contrast(a, size, icons) for a in panels}
    for r, canvas in enumerate(spec.canvases):
        y = top + r * row_h
        background = np.array(canvas.linear)
        fill = fill_of(canvas.linear)
        ink_panel = ink_on(canvas.linear).text
        used = out.text((MARGIN, y), f"{canvas.name}  ", fonts.row, ink.text)
        out.text((MARGIN + used, y + _CAPTION_DROP), canvas.color, fonts.body, ink.muted)
        for p, alpha in enumerate(panels):
            coeff = alphas_for(alpha, icons)
            passing = int((contrast[alpha][:, drawn.canvas_index(canvas.name)] >= threshold).sum())
            x0 = MARGIN + p * (panel_w + _PANEL_GAP)
            caption = f"{alpha_label(alpha, icons)} · {passing}"
            caption += f" of {n} at or above {threshold:g}:1"
            out.text((x0, y + _CAPTION_TOP), caption, fonts.body, ink.muted)
            py = y + row_head
            out.rect((x0, py, x0 + panel_w, py + panel_h), fill)
            pixels = composite_drawings(drawings, size, background, coeff, drawn.pipeline)
            for k, icon in enumerate(icons):
                rr, cc = divmod(k, cols)
                x = x0 + pad + cc * (size + gap)
                yy = py + pad + rr * (size + gap)
                out.block(
                    Placement(
                        x, yy, size, icon.name, canvas.name, icon.linear, canvas.linear, coeff[k]
                    ),
                    pixels[k],
                )
                if drawings[k].fixed:
                    fixed_mark(out, x, yy, size, gap, ink_panel)
    return out.finish()
