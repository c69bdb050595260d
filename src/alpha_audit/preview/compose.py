"""Pixel-exact compositing of coverage masks, and the paper's near-source canvases.

Every icon pixel is ``encode(q * clip(Cb + a (Cs - Cb), 0, 1) + (1 - q) * Cb)``
in linear sRGB, rounded half to even to 8 bits (paper, Appendix A.2), where
``q`` is the coverage mask from :func:`alpha_audit.load.svg.rasterize`.

Cairo masks hold only the 256 values ``k / 255``, so a pixel depends on the
icon and on ``k`` alone: :func:`composite_masks` evaluates the expression once
per (icon, k) and gathers, which gives the same bits as evaluating it at every
pixel (the same float64 operations on the same operands) at a fraction of the
cost.  Masks with other values take the direct per-pixel path.
"""

from __future__ import annotations

import colorsys
from collections.abc import Mapping
from enum import StrEnum
from pathlib import Path

import numpy as np
from numpy.typing import ArrayLike, NDArray

from alpha_audit.color import (
    composite_extended,
    difference_blend,
    exclusion_blend,
    parse_color,
    to_8bit,
)
from alpha_audit.errors import UsageError
from alpha_audit.model import Canvas

__all__ = [
    "DARK_GREY",
    "MAX_NEAR_SOURCE_COLORS",
    "NEAR_SOURCE_WHITE",
    "Blend",
    "blend_colors",
    "composite_masks",
    "mask_codes",
    "near_source_canvases",
]

_LEVELS = np.arange(256, dtype=np.float64) / 255.0  # the values a cairo mask can hold


class Blend(StrEnum):
    """How a source meets a canvas: the extended coefficient or the paper's controls."""

    EXTENDED = "alpha"
    DIFFERENCE = "difference"
    EXCLUSION = "exclusion"


def blend_colors(
    source: ArrayLike, background: ArrayLike, alpha: ArrayLike = 1.0, blend: Blend = Blend.EXTENDED
) -> NDArray[np.float64]:
    """The fully covered output colour in linear sRGB, clipped to [0, 1].

    ``alpha`` is used only by :attr:`Blend.EXTENDED`; Difference and Exclusion
    are the W3C Compositing controls of the paper (Appendix A.1).

    >>> blend_colors([1.0, 0.5, 0.0], [0.5, 0.5, 0.5], 2.0).tolist()
    [1.0, 0.5, 0.0]
    >>> blend_colors([1.0, 0.5, 0.0], [0.5, 0.5, 0.5], blend=Blend.DIFFERENCE).tolist()
    [0.5, 0.0, 0.5]
    """
    match Blend(blend):
        case Blend.EXTENDED:
            return composite_extended(source, background, alpha)
        case Blend.DIFFERENCE:
            return np.clip(difference_blend(source, background), 0.0, 1.0)
        case Blend.EXCLUSION:
            return np.clip(exclusion_blend(source, background), 0.0, 1.0)


def mask_codes(masks: ArrayLike) -> NDArray[np.uint8] | None:
    """The 8-bit codes ``k`` of masks that hold only values ``k / 255``, else ``None``."""
    q = np.asarray(masks, dtype=np.float64)
    if q.size and (np.nanmin(q) < 0.0 or np.nanmax(q) > 1.0):
        return None
    codes = np.rint(q * 255.0)
    if not np.array_equal(_LEVELS[codes.astype(np.intp)], q):
        return None
    return codes.astype(np.uint8)


def composite_masks(
    masks: ArrayLike,
    sources: ArrayLike,
    background: ArrayLike,
    alphas: ArrayLike = 1.0,
    blend: Blend = Blend.EXTENDED,
) -> NDArray[np.uint8]:
    """Composite ``n`` coverage masks on one canvas to 8-bit sRGB pixels.

    ``masks`` is ``(n, h, w)`` coverage in [0, 1], ``sources`` ``(n, 3)`` linear
    sRGB, ``background`` one linear colour ``(3,)`` and ``alphas`` ``(n,)`` (or a
    scalar).  Returns ``(n, h, w, 3)`` codes.

    >>> q = np.array([[[0.0, 1.0]]])
    >>> composite_masks(q, [[1.0, 0.0, 0.0]], [1.0, 1.0, 1.0], 1.0).tolist()
    [[[[255, 255, 255], [255, 0, 0]]]]
    """
    q = np.asarray(masks, dtype=np.float64)
    n = q.shape[0]
    b = np.asarray(background, dtype=np.float64).reshape(3)
    s = np.broadcast_to(np.asarray(sources, dtype=np.float64), (n, 3))
    a = np.broadcast_to(np.asarray(alphas, dtype=np.float64), (n,))
    out = blend_colors(s, b, a, blend)  # (n, 3)
    codes = mask_codes(q)
    if codes is None:  # arbitrary coverage: evaluate at every pixel
        qq = q[..., np.newaxis]
        return to_8bit(qq * out[:, np.newaxis, np.newaxis, :] + (1.0 - qq) * b)
    level = _LEVELS[np.newaxis, :, np.newaxis]  # (1, 256, 1)
    table = to_8bit(level * out[:, np.newaxis, :] + (1.0 - level) * b)  # (n, 256, 3)
    # Gather whole pixels, not channels: pack RGB(+pad) into one uint32 per entry.
    packed = np.zeros((n * 256, 4), dtype=np.uint8)
    packed[:, :3] = table.reshape(-1, 3)
    index = codes.astype(np.intp) + 256 * np.arange(n, dtype=np.intp)[:, np.newaxis, np.newaxis]
    pixels = np.take(packed.view(np.uint32).reshape(-1), index)
    return pixels[..., np.newaxis].view(np.uint8)[..., :3]


# Paper, Appendix A.3: "Vibrant colors mixed with 10% white in encoded sRGB".
NEAR_SOURCE_WHITE = 0.10
# The paper's galleries add "a dark gray canvas" without giving its value; ours.
DARK_GREY = "#333333"
# The paper's galleries use the seven Vibrant colours.  A set without a palette
# gets one canvas per distinct icon colour (a brand set: thousands), and every
# canvas is a sheet, a row or a page; beyond this many the preview is refused.
MAX_NEAR_SOURCE_COLORS = 64
# Below this HSV saturation a palette colour counts as grey and goes after the hues.
_NEUTRAL_SATURATION = 0.08


def near_source_canvases(
    palette: Mapping[str, str], *, path: str | Path | None = None
) -> tuple[Canvas, ...]:
    """Canvases close to each palette colour, plus a dark grey (the paper's galleries).

    Each colour is mixed with 10% white in encoded sRGB and rounded to 8 bits;
    chromatic colours come first from warm to cool hue, then greys, then dark grey.
    More than :data:`MAX_NEAR_SOURCE_COLORS` colours are refused (``path``
    names the icon set in the message).

    >>> [c.color for c in near_source_canvases({"orange": "#ee7733", "grey": "#bbbbbb"})]
    ['#f08547', '#c2c2c2', '#333333']
    """
    if len(palette) > MAX_NEAR_SOURCE_COLORS:
        raise UsageError(
            f"near-source canvases: {len(palette):,} colours (palette, else distinct icon "
            f"colours), at most {MAX_NEAR_SOURCE_COLORS} are allowed; give the manifest a "
            "palette of the colours to compare",
            path=path,
        )
    entries = []
    for name, color in palette.items():
        encoded = parse_color(color)
        mixed = (1.0 - NEAR_SOURCE_WHITE) * encoded + NEAR_SOURCE_WHITE
        r, g, b = (int(v) for v in np.rint(mixed * 255.0))
        hue, saturation, _ = colorsys.rgb_to_hsv(*encoded)
        neutral = saturation < _NEUTRAL_SATURATION
        # Hues just below 360 degrees are reds; start the wheel at magenta's far side.
        key = (neutral, 0.0 if neutral else (hue + 0.05) % 1.0)
        entries.append((key, Canvas(f"near-{name}", f"#{r:02x}{g:02x}{b:02x}")))
    entries.sort(key=lambda e: e[0])
    return (*(c for _, c in entries), Canvas("dark-grey", DARK_GREY))
