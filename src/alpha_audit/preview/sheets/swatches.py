"""The ``swatches`` layout: one sheet per canvas, palette colours across, coefficients down.

The paper's figure "Outputs for all seven Vibrant source colors": each cell is
a solid swatch of the composited colour with its hex code and contrast ratio
underneath.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from alpha_audit.color import judged_contrast, parse_color, srgb_decode, to_8bit
from alpha_audit.color.composite import Pipeline, composite_paint
from alpha_audit.model import IconSet
from alpha_audit.paints import CURRENT_COLOR
from alpha_audit.preview.compose import Drawing, Layer, composite_drawings
from alpha_audit.preview.sheets.plan import SheetSpec
from alpha_audit.preview.sheets.surface import (
    MARGIN,
    Fonts,
    Placement,
    Sheet,
    Surface,
    fill_of,
    header_bottom,
    ink_on,
)

__all__ = ["SwatchFrame", "draw_swatches", "swatch_colors", "swatch_frame"]

# Spacing, in px.
_MIN_SIDE, _MAX_SIDE = 56, 96
"""Swatch side: the icon size, kept between these so hex codes and names fit."""
_GAP = 18
"""Between swatch cells, across and down."""
_ROW_LABEL_GAP = 20
"""Between the widest row caption and the first swatch column."""
_HEADER_GAP = 6
"""Between the header and the column heads."""
_LINE_PAD = 4
"""Extra height of a column-head line over its font size."""
_HEAD_GAP = 8
"""Between the column heads and the first row of swatches."""
_LABEL_GAP = 3
"""Above each of the two small label lines under a swatch."""
_BOTTOM_PAD = 4
"""Below the last row's labels (room for an underline)."""
_UNDERLINE_DROP = 1
"""Below the label's font size, where the failing-contrast underline goes."""


def swatch_colors(iconset: IconSet) -> list[tuple[str, str]]:
    """(label, hex) for every palette colour, else every distinct icon colour."""
    if iconset.palette:
        return list(iconset.palette.items())
    seen: dict[str, str] = {}
    for icon in iconset.icons:
        seen.setdefault(icon.color, icon.color_name or icon.color)
    return [(label, color) for color, label in seen.items()]


@dataclass(frozen=True)
class SwatchFrame:
    """Everything about a swatch sheet but its pixels."""

    width: int
    height: int
    side: int
    left: int
    top: int
    head_h: int
    cell_w: int
    cell_h: int
    fonts: Fonts
    header: str
    sub: str
    legend: str
    labels: tuple[str, ...]


def swatch_frame(
    spec: SheetSpec,
    colors: Sequence[tuple[str, str]],
    alphas: Sequence[float],
    threshold: float,
    title: str,
) -> SwatchFrame:
    """Lay out a swatch sheet of ``colors`` (label, hex) without drawing it."""
    canvas = spec.canvases[0]
    fonts = Fonts(12)
    side = max(_MIN_SIDE, min(spec.size, _MAX_SIDE))
    labels = tuple(f"alpha = {a:g}" for a in alphas)
    left = max(Fonts.width(fonts.row, t) for t in labels) + _ROW_LABEL_GAP
    col_w = max(
        side,
        Fonts.width(fonts.small, "#000000"),
        *(Fonts.width(fonts.body, name) for name, _ in colors),
    )
    cell_w = col_w + _GAP
    cell_h = side + 2 * (fonts.small_px + _LABEL_GAP) + _GAP
    header = f"{canvas.name}  {canvas.color}"
    sub = f"{title} · palette across, coefficient down"
    legend = f"under each swatch: output colour and contrast; underlined below {threshold:g}:1"
    content_w = max(
        left + len(colors) * cell_w - _GAP,
        Fonts.width(fonts.title, header),
        Fonts.width(fonts.body, sub),
        Fonts.width(fonts.body, legend),
    )
    top = header_bottom(2) + _HEADER_GAP
    head_h = 2 * (fonts.body_px + _LINE_PAD) + _HEAD_GAP
    width = 2 * MARGIN + content_w
    height = top + head_h + len(alphas) * cell_h - _GAP + _BOTTOM_PAD + MARGIN
    return SwatchFrame(
        width, height, side, left, top, head_h, cell_w, cell_h, fonts, header, sub, legend, labels
    )


def draw_swatches(
    spec: SheetSpec,
    colors: Sequence[tuple[str, str]],
    alphas: Sequence[float],
    threshold: float,
    title: str,
    pipeline: Pipeline = "linear",
) -> Sheet:
    """Draw a swatch sheet of ``colors`` (label, hex; see the module docstring).

    Each swatch is the colour as a solid paint shows it under ``pipeline``;
    its contrast is that of the 8-bit colour on the 8-bit canvas, as a row's.
    """
    canvas = spec.canvases[0]
    frame = swatch_frame(spec, colors, alphas, threshold, title)
    fonts, side, left, top = frame.fonts, frame.side, frame.left, frame.top
    cell_w, cell_h, head_h, labels = frame.cell_w, frame.cell_h, frame.head_h, frame.labels
    ink = ink_on(canvas.linear)
    fill = fill_of(canvas.linear)
    out = Surface(spec, frame.width, frame.height, fill)
    out.text((MARGIN, MARGIN), frame.header, fonts.title, ink.text)
    out.text((MARGIN, header_bottom(0)), frame.sub, fonts.body, ink.muted)
    out.text((MARGIN, header_bottom(1)), frame.legend, fonts.body, ink.muted)

    sources = srgb_decode(np.array([parse_color(c) for _, c in colors])).reshape(-1, 3)
    background = np.array(canvas.linear)
    for j, (name, color) in enumerate(colors):
        x = MARGIN + left + j * cell_w
        out.text((x, top), name, fonts.body, ink.text)
        out.text((x, top + fonts.body_px + _LINE_PAD), color, fonts.small, ink.muted)
    full = (np.full((side, side), 255, dtype=np.uint8),)
    solids = [
        Drawing(
            name,
            (Layer(CURRENT_COLOR, (float(s[0]), float(s[1]), float(s[2])), 1.0),),
            {side: full},
        )
        for (name, _), s in zip(colors, sources, strict=True)
    ]
    for r, alpha in enumerate(alphas):
        y = top + head_h + r * cell_h
        out.text((MARGIN, y + (side - fonts.row_px) // 2), labels[r], fonts.row, ink.text)
        coeff = np.full(len(colors), float(alpha))
        pixels = composite_drawings(solids, side, background, coeff, pipeline)
        output = composite_paint(sources, background, coeff, 1.0, pipeline)
        contrast = judged_contrast(output, background)
        for j in range(len(colors)):
            x = MARGIN + left + j * cell_w
            source = (float(sources[j, 0]), float(sources[j, 1]), float(sources[j, 2]))
            out.block(
                Placement(x, y, side, None, canvas.name, source, canvas.linear, float(alpha)),
                pixels[j],
            )
            code = to_8bit(output[j])
            hex_out = "#" + "".join(f"{int(v):02x}" for v in code)
            ty = y + side + _LABEL_GAP
            out.text((x, ty), hex_out, fonts.small, ink.muted)
            value = float(contrast[j])
            tone = ink.text if value >= threshold else ink.alert
            ty2 = ty + fonts.small_px + _LABEL_GAP
            tw = out.text((x, ty2), f"{value:.2f}:1", fonts.small, tone)
            if value < threshold:
                line = ty2 + fonts.small_px + _UNDERLINE_DROP
                out.rect((x, line, x + tw, line + 1), tone)
    return out.finish()
