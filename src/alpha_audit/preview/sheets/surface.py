"""The drawing surface every layout shares: flat colour, then labels, then icon blocks.

A sheet starts as flat colour, labels are drawn into the gutters, and the
composited icon pixels from :func:`~alpha_audit.preview.compose.composite_drawings`
are copied in last, so no label or gutter ever touches an icon pixel.  Every
copied block is recorded as a :class:`Placement`, which is what the tests
recompute pixel by pixel.
"""

from __future__ import annotations

import functools
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray
from PIL import Image, ImageDraw, ImageFont

from alpha_audit.color import contrast_ratio, parse_color, srgb_decode, srgb_encode, to_8bit
from alpha_audit.errors import UsageError
from alpha_audit.model import Icon
from alpha_audit.preview.compose import Drawing
from alpha_audit.preview.fonts import draw_text, text_metrics, text_width
from alpha_audit.preview.sheets.plan import SheetSpec

__all__ = [
    "BODY_LINE",
    "FIXED_MARK",
    "MARGIN",
    "PIXEL_BUDGET",
    "TITLE_LINE",
    "Fonts",
    "Ink",
    "Placement",
    "Sheet",
    "Surface",
    "available",
    "check_budget",
    "fill_of",
    "fixed_mark",
    "header_bottom",
    "ink_on",
    "rgb",
]

RGB8 = tuple[int, int, int]

# Spacing shared by every layout, in px.
MARGIN = 24
"""Empty border around a sheet's content."""
TITLE_LINE = 32
"""From the top of the 22 px title to the top of the line under it."""
BODY_LINE = 22
"""From the top of one 14 px header line to the top of the next."""


PIXEL_BUDGET = 1 << 24
"""Most pixels in one sheet image: 16,777,216 (a 4096 x 4096 square, 48 MiB as 8-bit RGB).

A sheet is held in memory about three times while it is drawn and encoded, so
this bounds a sheet's peak at roughly 150 MB; and it stays well under Pillow's
decompression-bomb limit (``PIL.Image.MAX_IMAGE_PIXELS``, 89,478,485 px, above
which Pillow warns and at twice which it refuses to open a file), so every
sheet opens in Pillow and ordinary image viewers.  Larger sheets are split into
pages (:mod:`~alpha_audit.preview.sheets.pages`) or refused.
"""


def check_budget(name: str, width: int, height: int) -> None:
    """Refuse a sheet of more than :data:`PIXEL_BUDGET` pixels."""
    if width * height > PIXEL_BUDGET:
        raise UsageError(
            f"sheet {name} would be {width:,} x {height:,} = {width * height:,} px, more than "
            f"the {PIXEL_BUDGET:,} px allowed per image even for one icon or colour a page; "
            "use fewer alpha rows, a smaller size or fewer canvases"
        )


def header_bottom(body_lines: int) -> int:
    """Where a header of the title and ``body_lines`` lines under it ends."""
    return MARGIN + TITLE_LINE + body_lines * BODY_LINE


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
class Sheet:
    """A rendered sheet and the blocks composited onto it."""

    spec: SheetSpec
    image: Image.Image
    placements: tuple[Placement, ...]


# ---------------------------------------------------------------------------
# Typography and colour of the labels


@dataclass(frozen=True)
class Ink:
    """Label colours that read on one background."""

    text: RGB8
    muted: RGB8
    alert: RGB8


_DARK_TEXT, _LIGHT_TEXT = "#161616", "#f2f2f2"
_ALERT_ON_LIGHT, _ALERT_ON_DARK = "#b3261e", "#ff8a80"
_SMALL_TEXT_CONTRAST = 4.5  # WCAG 2.2 SC 1.4.3, for small text
_MUTED_WEIGHT = 0.62  # share of the text colour in a quieter label tone (encoded sRGB mix)


def rgb(hex_color: str) -> RGB8:
    """The 8-bit code of a colour string, as Pillow takes it."""
    r, g, b = (int(v) for v in np.rint(parse_color(hex_color) * 255.0))
    return r, g, b


def fill_of(linear: ArrayLike) -> RGB8:
    """The 8-bit code of a linear sRGB colour."""
    r, g, b = (int(v) for v in to_8bit(linear))
    return r, g, b


def ink_on(background: tuple[float, float, float]) -> Ink:
    """Near-black or near-white text, whichever contrasts more with ``background``."""
    bg = np.asarray(background)
    dark, light = srgb_decode(parse_color(_DARK_TEXT)), srgb_decode(parse_color(_LIGHT_TEXT))
    on_light = float(contrast_ratio(dark, bg)) >= float(contrast_ratio(light, bg))
    text = dark if on_light else light
    alert = srgb_decode(parse_color(_ALERT_ON_LIGHT if on_light else _ALERT_ON_DARK))
    if float(contrast_ratio(alert, bg)) < _SMALL_TEXT_CONTRAST:
        alert = text
    muted_encoded = _MUTED_WEIGHT * srgb_encode(text) + (1 - _MUTED_WEIGHT) * srgb_encode(bg)
    muted = srgb_decode(muted_encoded)
    return Ink(fill_of(text), fill_of(muted), fill_of(alert))


@functools.lru_cache(maxsize=8)
def _default_font(size: int) -> ImageFont.FreeTypeFont:
    return ImageFont.load_default(size=size)  # type: ignore[return-value]  # FreeType whenever a size is given


@functools.lru_cache(maxsize=1 << 16)
def _text_width(size: float, text: str) -> int:
    # Pages are planned by measuring the same labels many times; they are measured once.
    # Non-ASCII names are measured as drawn: each character in a font that has it.
    return text_width(_default_font(int(size)), text)


class Fonts:
    """Pillow's bundled font at the sizes the sheets use (no system fonts needed)."""

    def __init__(self, small: int) -> None:
        self.title_px, self.body_px, self.row_px, self.small_px = 22, 14, 16, small
        self.title = _default_font(self.title_px)
        self.body = _default_font(self.body_px)
        self.row = _default_font(self.row_px)
        self.small = _default_font(self.small_px)

    @staticmethod
    def width(font: ImageFont.FreeTypeFont, text: str) -> int:
        """Advance width of ``text`` in whole pixels (``font`` is one of :class:`Fonts`')."""
        return _text_width(font.size, text)


def available(icons: Sequence[Icon], drawings: Mapping[str, Drawing], size: int) -> list[Icon]:
    """The icons drawn at ``size`` (the others, unreadable or unrendered, are left off)."""
    return [i for i in icons if i.name in drawings and size in drawings[i.name].masks]


FIXED_MARK = 4
"""px; the side of the square at an icon's top right that says it hard-codes a colour."""


def fixed_mark(out: Surface, x: int, y: int, size: int, room: int, fill: RGB8) -> None:
    """Mark the icon drawn at (x, y) as hard-coding a colour: a square in the gutter at its
    top right, ``room`` px wide at most (never over an icon pixel)."""
    side = min(FIXED_MARK, room - 2)
    if side > 0:
        out.rect((x + size + 1, y, x + size + 1 + side, y + side), fill)


class Surface:
    """A sheet under construction: flat colour, then labels, then icon blocks."""

    def __init__(self, spec: SheetSpec, width: int, height: int, fill: RGB8) -> None:
        check_budget(spec.name, width, height)
        self.spec = spec
        self.image = Image.new("RGB", (width, height), fill)
        self.draw = ImageDraw.Draw(self.image)
        self.blocks: list[tuple[Placement, NDArray[np.uint8]]] = []
        self.patches: dict[tuple[str, float, RGB8, RGB8], Image.Image] = {}

    def rect(self, box: tuple[int, int, int, int], fill: RGB8) -> None:
        """Fill ``box`` = (left, top, right, bottom), right and bottom exclusive."""
        self.draw.rectangle((box[0], box[1], box[2] - 1, box[3] - 1), fill=fill)

    def text(self, xy: tuple[int, int], text: str, font: ImageFont.FreeTypeFont, fill: RGB8) -> int:
        """Draw ``text`` with its top-left at ``xy``; return its width."""
        return draw_text(self.draw, xy, text, font, fill)

    def label(
        self,
        xy: tuple[int, int],
        text: str,
        font: ImageFont.FreeTypeFont,
        fill: RGB8,
        ground: RGB8,
    ) -> int:
        """Like :meth:`text` on a flat ``ground``, rendering each distinct label only once.

        Sheets repeat a few hundred distinct numbers thousands of times; a
        cached patch drawn on the same ground colour is the same pixels.
        """
        key = (text, font.size, fill, ground)
        patch = self.patches.get(key)
        if patch is None:
            width = Fonts.width(font, text)
            ascent, descent = text_metrics(font, text)
            patch = Image.new("RGB", (width + 2, ascent + descent + 2), ground)
            draw_text(ImageDraw.Draw(patch), (0, 0), text, font, fill)
            self.patches[key] = patch
        self.image.paste(patch, xy)
        return patch.size[0] - 2

    def block(self, placement: Placement, pixels: NDArray[np.uint8]) -> None:
        """Queue composited pixels; they are copied in by :meth:`finish`, over any label."""
        self.blocks.append((placement, pixels))

    def finish(self) -> Sheet:
        """The finished sheet: labels are in, icons go on top, untouched."""
        array = np.array(self.image)
        for p, pixels in self.blocks:
            array[p.y : p.y + p.size, p.x : p.x + p.size] = pixels
        return Sheet(self.spec, Image.fromarray(array, "RGB"), tuple(p for p, _ in self.blocks))
