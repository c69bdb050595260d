"""PNG sheets: icons composited on canvases, laid out like the paper's figures.

Three layouts share one drawing discipline: the sheet starts as flat colour,
labels are drawn into the gutters, and the composited icon pixels from
:func:`~alpha_audit.preview.compose.composite_masks` are copied in last, so
no label or gutter ever touches an icon pixel.  Every copied block is recorded
as a :class:`Placement`, which is what the tests recompute pixel by pixel.

- ``grid``: one sheet per canvas and size; a row of icons per coefficient,
  wrapping to a readable width, with each icon's contrast ratio underneath.
- ``swatches``: one sheet per canvas; palette colours across, coefficients
  down (the paper's figure "Outputs for all seven Vibrant source colors").
- ``compare``: one sheet per size; a row per canvas with the whole set at
  ``alpha = 1`` beside each other coefficient (the paper's gallery figures).
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable, Iterator, Mapping, Sequence
from dataclasses import dataclass
from enum import StrEnum
from pathlib import Path
from typing import assert_never

import numpy as np
from numpy.typing import NDArray
from PIL import Image, ImageDraw, ImageFont

from alpha_audit.color import (
    NON_TEXT_THRESHOLD,
    contrast_ratio,
    parse_color,
    srgb_decode,
    srgb_encode,
    to_8bit,
)
from alpha_audit.model import Canvas, Icon, IconSet
from alpha_audit.output import check_targets, write_bytes
from alpha_audit.preview.compose import blend_colors, composite_masks
from alpha_audit.preview.fonts import draw_text, text_metrics, text_width

__all__ = [
    "ICON_ALPHA",
    "SWATCH_ALPHAS",
    "Layout",
    "Placement",
    "Sheet",
    "SheetSpec",
    "check_writable",
    "default_alphas",
    "plan_sheets",
    "render_all",
    "render_sheet",
    "write_sheet",
]

Alpha = float | None
ICON_ALPHA: Alpha = None
"""An alpha row that uses each icon's own coefficient from the manifest."""

# Coefficients for the swatch layout when none are given: conventional
# transparency, the reference, and same-direction expansion up to the paper's
# gallery value of 2 (Appendix A.3).
SWATCH_ALPHAS: tuple[float, ...] = (0.6, 1.0, 1.1, 1.2, 1.4, 2.0)

_PNG_LEVEL = 1  # zlib level: flat canvases compress well even at 1; level 6 is ~3x slower


class Layout(StrEnum):
    """Sheet layouts offered by ``alpha-audit preview --layout``."""

    GRID = "grid"
    SWATCHES = "swatches"
    COMPARE = "compare"


@dataclass(frozen=True)
class Placement:
    """Where one composited block sits on a sheet, and what it shows.

    ``icon`` names the mask (``None`` for a solid swatch, coverage 1 everywhere);
    colours are linear sRGB.
    """

    x: int
    y: int
    size: int
    icon: str | None
    canvas: str
    source: tuple[float, float, float]
    background: tuple[float, float, float]
    alpha: float


@dataclass(frozen=True)
class SheetSpec:
    """One planned sheet: its file name, layout, canvases and icon size."""

    name: str
    layout: Layout
    canvases: tuple[Canvas, ...]
    size: int


@dataclass(frozen=True)
class Sheet:
    """A rendered sheet and the blocks composited onto it."""

    spec: SheetSpec
    image: Image.Image
    placements: tuple[Placement, ...]


def default_alphas(iconset: IconSet) -> list[Alpha]:
    """``1`` and the set's own coefficients (dropped when every icon has 1)."""
    return [1.0] if all(i.alpha == 1.0 for i in iconset.icons) else [1.0, ICON_ALPHA]


def _slug(text: str) -> str:
    return re.sub(r"[^a-z0-9]+", "-", text.lower()).strip("-") or "x"


def plan_sheets(
    layout: Layout, canvases: Sequence[Canvas], sizes: Sequence[int], prefix: str
) -> list[SheetSpec]:
    """The sheets a layout produces, with predictable, distinct file names.

    >>> [s.name for s in plan_sheets(Layout.GRID, [Canvas("Paper", "#fff")], [16, 48], "demo")]
    ['demo-grid-paper-16px.png', 'demo-grid-paper-48px.png']
    """
    stem = _slug(prefix)
    slugs: list[str] = []
    for canvas in canvases:
        slug = _slug(canvas.name)
        slugs.append(slug if slug not in slugs else f"{slug}-{len(slugs) + 1}")
    match layout:
        case Layout.GRID:
            return [
                SheetSpec(f"{stem}-grid-{slug}-{size}px.png", layout, (canvas,), size)
                for canvas, slug in zip(canvases, slugs, strict=True)
                for size in sizes
            ]
        case Layout.SWATCHES:
            return [
                SheetSpec(f"{stem}-swatches-{slug}.png", layout, (canvas,), max(sizes))
                for canvas, slug in zip(canvases, slugs, strict=True)
            ]
        case Layout.COMPARE:
            return [
                SheetSpec(f"{stem}-compare-{size}px.png", layout, tuple(canvases), size)
                for size in sizes
            ]
        case _:
            assert_never(layout)


# ---------------------------------------------------------------------------
# Typography and colour of the labels


@dataclass(frozen=True)
class _Ink:
    """Label colours that read on one background."""

    text: tuple[int, int, int]
    muted: tuple[int, int, int]
    alert: tuple[int, int, int]


_DARK_TEXT, _LIGHT_TEXT = "#161616", "#f2f2f2"
_ALERT_ON_LIGHT, _ALERT_ON_DARK = "#b3261e", "#ff8a80"


def _rgb(hex_color: str) -> tuple[int, int, int]:
    r, g, b = (int(v) for v in np.rint(parse_color(hex_color) * 255.0))
    return r, g, b


def _ink(background: tuple[float, float, float]) -> _Ink:
    """Near-black or near-white text, whichever contrasts more with ``background``."""
    bg = np.asarray(background)
    dark, light = srgb_decode(parse_color(_DARK_TEXT)), srgb_decode(parse_color(_LIGHT_TEXT))
    on_light = float(contrast_ratio(dark, bg)) >= float(contrast_ratio(light, bg))
    text = dark if on_light else light
    alert = srgb_decode(parse_color(_ALERT_ON_LIGHT if on_light else _ALERT_ON_DARK))
    if float(contrast_ratio(alert, bg)) < 4.5:  # WCAG 1.4.3 for small text
        alert = text
    muted_encoded = 0.62 * srgb_encode(text) + 0.38 * srgb_encode(bg)  # a quieter label tone
    muted = srgb_decode(muted_encoded)
    return _Ink(*(tuple(int(v) for v in to_8bit(c)) for c in (text, muted, alert)))


class _Fonts:
    """Pillow's bundled font at the sizes the sheets use (no system fonts needed)."""

    def __init__(self, small: int) -> None:
        self.title = ImageFont.load_default(size=22)
        self.body = ImageFont.load_default(size=14)
        self.row = ImageFont.load_default(size=16)
        self.small = ImageFont.load_default(size=small)

    @staticmethod
    def width(font: ImageFont.FreeTypeFont | ImageFont.ImageFont, text: str) -> int:
        return text_width(font, text)  # non-ASCII names: fonts that have them


def _alpha_label(alpha: Alpha, icons: Sequence[Icon]) -> str:
    if alpha is not None:
        return f"alpha = {alpha:g}"
    values = sorted({i.alpha for i in icons})
    if len(values) == 1:
        return f"alpha = {values[0]:g} (the set's)"
    return f"alpha = each icon's own ({values[0]:g} to {values[-1]:g})"


def _alphas_for(alpha: Alpha, icons: Sequence[Icon]) -> NDArray[np.float64]:
    if alpha is None:
        return np.array([i.alpha for i in icons], dtype=np.float64)
    return np.full(len(icons), float(alpha))


# ---------------------------------------------------------------------------
# Drawing


class _Canvas2D:
    """A sheet under construction: flat colour, then labels, then icon blocks."""

    def __init__(self, width: int, height: int, fill: tuple[int, int, int]) -> None:
        self.image = Image.new("RGB", (width, height), fill)
        self.draw = ImageDraw.Draw(self.image)
        self.blocks: list[tuple[Placement, NDArray[np.uint8]]] = []
        self.patches: dict[
            tuple[str, int, tuple[int, int, int], tuple[int, int, int]], Image.Image
        ] = {}

    def rect(self, box: tuple[int, int, int, int], fill: tuple[int, int, int]) -> None:
        self.draw.rectangle((box[0], box[1], box[2] - 1, box[3] - 1), fill=fill)

    def text(self, xy: tuple[int, int], text: str, font: object, fill: tuple[int, int, int]) -> int:
        """Draw ``text`` with its top-left at ``xy``; return its width."""
        return draw_text(self.draw, xy, text, font, fill)  # type: ignore[arg-type]

    def label(
        self,
        xy: tuple[int, int],
        text: str,
        font: ImageFont.FreeTypeFont,
        fill: tuple[int, int, int],
        ground: tuple[int, int, int],
    ) -> int:
        """Like :meth:`text` on a flat ``ground``, rendering each distinct label only once.

        Sheets repeat a few hundred distinct numbers thousands of times; a
        cached patch drawn on the same ground colour is the same pixels.
        """
        key = (text, font.size, fill, ground)
        patch = self.patches.get(key)
        if patch is None:
            width = _Fonts.width(font, text)
            ascent, descent = text_metrics(font, text)
            patch = Image.new("RGB", (width + 2, ascent + descent + 2), ground)
            draw_text(ImageDraw.Draw(patch), (0, 0), text, font, fill)
            self.patches[key] = patch
        self.image.paste(patch, xy)
        return patch.size[0] - 2

    def block(self, placement: Placement, pixels: NDArray[np.uint8]) -> None:
        self.blocks.append((placement, pixels))

    def finish(self, spec: SheetSpec) -> Sheet:
        array = np.array(self.image)  # labels are in; icons go on top, untouched
        for p, pixels in self.blocks:
            array[p.y : p.y + p.size, p.x : p.x + p.size] = pixels
        return Sheet(spec, Image.fromarray(array, "RGB"), tuple(p for p, _ in self.blocks))


_MARGIN = 24
_NAME_CAP = 120  # px: the widest an icon name makes a grid cell


def _fit(font: ImageFont.FreeTypeFont, text: str, width: int) -> str:
    """``text``, or its longest prefix plus "..." that fits in ``width`` pixels."""
    if _Fonts.width(font, text) <= width:
        return text
    lo, hi = 0, len(text)
    while lo < hi:  # the longest prefix that fits with the ellipsis
        mid = (lo + hi + 1) // 2
        if _Fonts.width(font, text[:mid] + "...") <= width:
            lo = mid
        else:
            hi = mid - 1
    return text[:lo] + "..."


def _available(icons: Sequence[Icon], masks: Mapping[tuple[str, int], NDArray], size: int):
    return [i for i in icons if (i.name, size) in masks]


def _grid(
    spec: SheetSpec,
    iconset: IconSet,
    masks: Mapping[tuple[str, int], NDArray[np.float64]],
    alphas: Sequence[Alpha],
    threshold: float,
    max_width: int,
    title: str,
) -> Sheet:
    canvas, size = spec.canvases[0], spec.size
    icons = _available(iconset.icons, masks, size)
    fonts = _Fonts(11 if size <= 24 else 12)
    ink = _ink(canvas.linear)
    fill = tuple(int(v) for v in to_8bit(canvas.linear))
    n = len(icons)

    gap = max(10, size // 3)
    label_w = _Fonts.width(fonts.small, "00.00")
    label_h = fonts.small.size + 4
    # Each cell names its icon under the ratio; long names are shortened with "..."
    # to the cell (at most _NAME_CAP wide), the full names being in the HTML page.
    widest = max((_Fonts.width(fonts.small, i.name) for i in icons), default=0)
    cell_w = max(size, label_w, min(widest, _NAME_CAP)) + gap
    cell_h = size + 4 + 2 * label_h + gap // 2 + 4
    cols = max(1, min(n, (max_width - 2 * _MARGIN + gap) // cell_w))
    rows = max(1, math.ceil(n / cols))

    stack = np.stack([masks[(i.name, size)] for i in icons]) if icons else np.zeros((0, size, size))
    sources = np.array([i.linear for i in icons], dtype=np.float64).reshape(-1, 3)
    background = np.array(canvas.linear)
    passing_ref = int((contrast_ratio(sources, background) >= threshold).sum())
    blocks = []
    for alpha in alphas:
        coeff = _alphas_for(alpha, icons)
        contrast = contrast_ratio(blend_colors(sources, background, coeff), background)
        summary = f"   {int((contrast >= threshold).sum())} of {n} at or above {threshold:g}:1"
        if alpha != 1.0:
            summary += f" (alpha = 1: {passing_ref})"
        blocks.append((coeff, contrast, _alpha_label(alpha, icons), summary))

    header = f"{canvas.name}  {canvas.color}"
    sub = f"{title} · {canvas.mode} canvas · {size} px"
    legend = (
        f"under each icon: WCAG contrast ratio on this canvas; underlined below {threshold:g}:1"
    )
    content_w = max(
        cols * cell_w - gap,
        _Fonts.width(fonts.title, header),
        _Fonts.width(fonts.body, sub),
        _Fonts.width(fonts.body, legend),
        *(_Fonts.width(fonts.row, b[2]) + _Fonts.width(fonts.body, b[3]) for b in blocks),
    )
    block_h = 28 + rows * cell_h + 12
    width = 2 * _MARGIN + content_w
    height = _MARGIN + 30 + 22 + 22 + 14 + len(alphas) * block_h + _MARGIN - 12
    out = _Canvas2D(width, height, fill)  # type: ignore[arg-type]

    out.text((_MARGIN, _MARGIN), header, fonts.title, ink.text)
    out.text((_MARGIN, _MARGIN + 32), sub, fonts.body, ink.muted)
    out.text((_MARGIN, _MARGIN + 54), legend, fonts.body, ink.muted)
    y = _MARGIN + 30 + 22 + 22 + 14
    for coeff, contrast, label, summary in blocks:
        pixels = composite_masks(stack, sources, background, coeff)
        used = out.text((_MARGIN, y), label, fonts.row, ink.text)
        out.text((_MARGIN + used, y + 2), summary, fonts.body, ink.muted)
        top = y + 28
        for k, icon in enumerate(icons):
            r, c = divmod(k, cols)
            cx = _MARGIN + c * cell_w
            cy = top + r * cell_h
            x = cx + (cell_w - gap - size) // 2
            out.block(
                Placement(
                    x, cy, size, icon.name, canvas.name, icon.linear, canvas.linear, coeff[k]
                ),
                pixels[k],
            )
            value = float(contrast[k])
            text = f"{value:.2f}" if value < 10 else f"{value:.1f}"
            color = ink.text if value >= threshold else ink.alert
            tw = _Fonts.width(fonts.small, text)
            tx = cx + (cell_w - gap - tw) // 2
            ty = cy + size + 4
            out.label((tx, ty), text, fonts.small, color, fill)  # type: ignore[arg-type]
            if value < threshold:
                underline = ty + fonts.small.size + 1
                out.rect((tx, underline, tx + tw, underline + 1), color)
            name = _fit(fonts.small, icon.name, cell_w - gap)
            nw = _Fonts.width(fonts.small, name)
            out.label(
                (cx + (cell_w - gap - nw) // 2, ty + label_h), name, fonts.small, ink.muted, fill
            )  # type: ignore[arg-type]
        y += block_h
    return out.finish(spec)


def _swatch_colors(iconset: IconSet) -> list[tuple[str, str]]:
    """(label, hex) for every palette colour, else every distinct icon colour."""
    if iconset.palette:
        return list(iconset.palette.items())
    seen: dict[str, str] = {}
    for icon in iconset.icons:
        seen.setdefault(icon.color, icon.color_name or icon.color)
    return [(label, color) for color, label in seen.items()]


def _swatches(
    spec: SheetSpec, iconset: IconSet, alphas: Sequence[float], threshold: float, title: str
) -> Sheet:
    canvas = spec.canvases[0]
    fonts = _Fonts(12)
    ink = _ink(canvas.linear)
    fill = tuple(int(v) for v in to_8bit(canvas.linear))
    colors = _swatch_colors(iconset)
    side = max(56, min(spec.size, 96))
    gap = 18
    labels = [f"alpha = {a:g}" for a in alphas]
    left = max(_Fonts.width(fonts.row, t) for t in labels) + 20
    col_w = max(
        side,
        _Fonts.width(fonts.small, "#000000"),
        *(_Fonts.width(fonts.body, name) for name, _ in colors),
    )
    cell_w = col_w + gap
    cell_h = side + 2 * (fonts.small.size + 3) + gap
    header = f"{canvas.name}  {canvas.color}"
    sub = f"{title} · palette across, coefficient down"
    legend = f"under each swatch: output colour and contrast; underlined below {threshold:g}:1"
    content_w = max(
        left + len(colors) * cell_w - gap,
        _Fonts.width(fonts.title, header),
        _Fonts.width(fonts.body, sub),
        _Fonts.width(fonts.body, legend),
    )
    top = _MARGIN + 30 + 22 + 30
    head_h = 2 * (fonts.body.size + 4) + 8
    width = 2 * _MARGIN + content_w
    height = top + head_h + len(alphas) * cell_h + _MARGIN - gap + 4
    out = _Canvas2D(width, height, fill)  # type: ignore[arg-type]
    out.text((_MARGIN, _MARGIN), header, fonts.title, ink.text)
    out.text((_MARGIN, _MARGIN + 32), sub, fonts.body, ink.muted)
    out.text((_MARGIN, _MARGIN + 54), legend, fonts.body, ink.muted)

    sources = srgb_decode(np.array([parse_color(c) for _, c in colors])).reshape(-1, 3)
    background = np.array(canvas.linear)
    for j, (name, color) in enumerate(colors):
        x = _MARGIN + left + j * cell_w
        out.text((x, top), name, fonts.body, ink.text)
        out.text((x, top + fonts.body.size + 4), color, fonts.small, ink.muted)
    full = np.ones((len(colors), side, side))
    for r, alpha in enumerate(alphas):
        y = top + head_h + r * cell_h
        out.text((_MARGIN, y + (side - fonts.row.size) // 2), labels[r], fonts.row, ink.text)
        coeff = np.full(len(colors), float(alpha))
        pixels = composite_masks(full, sources, background, coeff)
        output = blend_colors(sources, background, coeff)
        contrast = contrast_ratio(output, background)
        for j in range(len(colors)):
            x = _MARGIN + left + j * cell_w
            source = (float(sources[j, 0]), float(sources[j, 1]), float(sources[j, 2]))
            out.block(
                Placement(x, y, side, None, canvas.name, source, canvas.linear, float(alpha)),
                pixels[j],
            )
            code = to_8bit(output[j])
            hex_out = "#" + "".join(f"{int(v):02x}" for v in code)
            ty = y + side + 3
            out.text((x, ty), hex_out, fonts.small, ink.muted)
            value = float(contrast[j])
            color = ink.text if value >= threshold else ink.alert
            ty2 = ty + fonts.small.size + 3
            tw = out.text((x, ty2), f"{value:.2f}:1", fonts.small, color)
            if value < threshold:
                line = ty2 + fonts.small.size + 1
                out.rect((x, line, x + tw, line + 1), color)
    return out.finish(spec)


_PAGE = "#ffffff"


def _compare(
    spec: SheetSpec,
    iconset: IconSet,
    masks: Mapping[tuple[str, int], NDArray[np.float64]],
    alphas: Sequence[Alpha],
    threshold: float,
    title: str,
) -> Sheet:
    size = spec.size
    icons = _available(iconset.icons, masks, size)
    n = len(icons)
    fonts = _Fonts(12)
    page = srgb_decode(parse_color(_PAGE))
    ink = _ink((float(page[0]), float(page[1]), float(page[2])))
    panels: list[Alpha] = [1.0, *(a for a in alphas if a != 1.0)]
    if len(panels) == 1:
        panels.append(ICON_ALPHA)
    gap = max(4, size // 5)
    pad = max(12, size // 3)
    cols = max(1, min(n, max(12, math.ceil(math.sqrt(2 * n)))))
    rows = max(1, math.ceil(n / cols))
    panel_w = 2 * pad + cols * (size + gap) - gap
    panel_h = 2 * pad + rows * (size + gap) - gap
    between = 20
    row_head = 26 + fonts.body.size + 8
    header = f"{title} · {size} px"
    legend = "each row: one canvas; left to right: " + ", ".join(
        _alpha_label(a, icons) for a in panels
    )
    content_w = max(
        len(panels) * (panel_w + between) - between,
        _Fonts.width(fonts.title, header),
        _Fonts.width(fonts.body, legend),
    )
    top = _MARGIN + 30 + 30
    row_h = row_head + panel_h + 22
    width = 2 * _MARGIN + content_w
    height = top + len(spec.canvases) * row_h + _MARGIN - 22
    out = _Canvas2D(width, height, _rgb(_PAGE))
    out.text((_MARGIN, _MARGIN), header, fonts.title, ink.text)
    out.text((_MARGIN, _MARGIN + 32), legend, fonts.body, ink.muted)
    stack = np.stack([masks[(i.name, size)] for i in icons]) if icons else np.zeros((0, size, size))
    sources = np.array([i.linear for i in icons], dtype=np.float64).reshape(-1, 3)
    for r, canvas in enumerate(spec.canvases):
        y = top + r * row_h
        background = np.array(canvas.linear)
        fill = tuple(int(v) for v in to_8bit(canvas.linear))
        used = out.text((_MARGIN, y), f"{canvas.name}  ", fonts.row, ink.text)
        out.text((_MARGIN + used, y + 2), canvas.color, fonts.body, ink.muted)
        for p, alpha in enumerate(panels):
            coeff = _alphas_for(alpha, icons)
            contrast = contrast_ratio(blend_colors(sources, background, coeff), background)
            x0 = _MARGIN + p * (panel_w + between)
            caption = f"{_alpha_label(alpha, icons)} · {int((contrast >= threshold).sum())}"
            caption += f" of {n} at or above {threshold:g}:1"
            out.text((x0, y + 24), caption, fonts.body, ink.muted)
            py = y + row_head
            out.rect((x0, py, x0 + panel_w, py + panel_h), fill)  # type: ignore[arg-type]
            pixels = composite_masks(stack, sources, background, coeff)
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
    return out.finish(spec)


def render_sheet(
    spec: SheetSpec,
    iconset: IconSet,
    masks: Mapping[tuple[str, int], NDArray[np.float64]],
    *,
    alphas: Sequence[Alpha] | None = None,
    threshold: float = NON_TEXT_THRESHOLD,
    max_width: int = 1400,
    title: str | None = None,
) -> Sheet:
    """Draw one planned sheet.

    ``masks`` maps ``(icon name, size)`` to coverage (icons without a mask are
    left out); ``alphas`` are the rows (``None`` entries use each icon's own
    coefficient; default :func:`default_alphas`, or :data:`SWATCH_ALPHAS` for
    swatches); ``max_width`` bounds the grid layout's width in pixels.
    """
    label = title or iconset.name
    match spec.layout:
        case Layout.GRID:
            rows = default_alphas(iconset) if alphas is None else list(alphas)
            return _grid(spec, iconset, masks, rows, threshold, max_width, label)
        case Layout.SWATCHES:
            picked = [a for a in (alphas or ()) if a is not None] or list(SWATCH_ALPHAS)
            return _swatches(spec, iconset, picked, threshold, label)
        case Layout.COMPARE:
            rows = default_alphas(iconset) if alphas is None else list(alphas)
            return _compare(spec, iconset, masks, rows, threshold, label)
        case _:
            assert_never(spec.layout)


def write_sheet(sheet: Sheet, folder: str | Path, *, overwrite: bool = False) -> Path:
    """Save ``sheet`` as ``folder/<name>`` atomically (:func:`alpha_audit.output.write_bytes`).

    An existing file is replaced only with ``overwrite=True``.
    """
    return write_bytes(
        Path(folder) / sheet.spec.name,
        lambda fh: sheet.image.save(fh, format="PNG", compress_level=_PNG_LEVEL),
        overwrite=overwrite,
    )


def check_writable(targets: Sequence[Path], *, overwrite: bool) -> None:
    """Refuse before any work if the targets cannot all be written (:mod:`alpha_audit.output`)."""
    check_targets(targets, overwrite=overwrite)


def render_all(
    specs: Sequence[SheetSpec],
    iconset: IconSet,
    masks: Mapping[tuple[str, int], NDArray[np.float64]],
    *,
    on_sheet: Callable[[], None] | None = None,
    **options: object,
) -> Iterator[Sheet]:
    """Render ``specs`` one at a time (a sheet can be large; write each, then drop it)."""
    for spec in specs:
        sheet = render_sheet(spec, iconset, masks, **options)  # type: ignore[arg-type]
        yield sheet
        if on_sheet is not None:
            on_sheet()
