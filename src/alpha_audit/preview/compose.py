"""Pixel-exact compositing of an icon's paint groups, and the paper's near-source canvases.

An icon is drawn as its audit rows draw it (docs/model.md): each paint group
(:class:`Layer`, an SVG's fills and strokes of one colour and opacity; a
``currentColor`` group takes the icon's manifest colour) has its own coverage
mask ``q``, and the groups are painted in order over the canvas ``Cb``:

- ``linear``: ``X = clip(Cb + a (Cs - Cb))`` against the canvas (as the row),
  ``P = (o q) X + (1 - o q) P`` in linear light, starting at ``P = Cb``, then
  encoded and rounded half to even to 8 bits (paper, Appendix A.2);
- ``css``: in encoded values ``P' = clip(P' + a o q (Cs' - P'))``, starting
  at ``P' = Cb'``, then 8 bits (what a browser's source-over does).

Where one group covers a pixel this is the row's own formula at coverage
``q``: ``composite_paint(Cs, Cb, a, o q, pipeline)`` then 8 bits.

Cairo masks hold only the 256 values ``k / 255``, so a group's contribution
depends on the group and on ``k`` alone: it is evaluated once per
(group, k) and gathered.  An icon of one group needs nothing else: its pixels
are one table lookup (the same float64 operations on the same operands as
evaluating every pixel).  Icons of several groups carry the colour under
each group in float64 from one group to the next.
"""

from __future__ import annotations

import colorsys
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from enum import StrEnum
from pathlib import Path

import numpy as np
from numpy.typing import ArrayLike, NDArray

from alpha_audit.color import (
    composite_extended,
    difference_blend,
    exclusion_blend,
    parse_color,
    srgb_encode,
    to_8bit,
)
from alpha_audit.color.composite import Pipeline
from alpha_audit.errors import UsageError
from alpha_audit.model import Canvas, Icon
from alpha_audit.paints import CURRENT_COLOR

__all__ = [
    "DARK_GREY",
    "MAX_NEAR_SOURCE_COLORS",
    "NEAR_SOURCE_WHITE",
    "Blend",
    "Drawing",
    "Layer",
    "blend_colors",
    "composite_drawings",
    "mask_codes",
    "near_source_canvases",
    "solid_drawing",
]

_LEVELS = np.arange(256, dtype=np.float64) / 255.0  # the values a cairo mask can hold

Mask = NDArray[np.uint8]  # coverage codes, coverage x 255


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


@dataclass(frozen=True)
class Layer:
    """One paint group of an icon as drawn: its paint, source colour and opacity.

    ``paint`` is ``"currentColor"`` or the SVG's own ``#rrggbb``; ``source`` is
    the colour drawn in linear sRGB (the icon's manifest colour for
    ``currentColor``).
    """

    paint: str
    source: tuple[float, float, float]
    opacity: float

    @property
    def fixed(self) -> bool:
        """A hard-coded colour: it does not follow the theme."""
        return self.paint != CURRENT_COLOR


@dataclass(frozen=True)
class Drawing:
    """An icon as previews draw it: its paint groups in painter's order and their masks.

    ``masks[size][k]`` is group ``k``'s coverage at ``size`` as 8-bit codes.
    """

    icon: str
    layers: tuple[Layer, ...]
    masks: Mapping[int, tuple[Mask, ...]]

    @property
    def fixed(self) -> bool:
        """Some group hard-codes its colour."""
        return any(layer.fixed for layer in self.layers)


def solid_drawing(icon: Icon, masks: Mapping[int, ArrayLike]) -> Drawing:
    """An icon drawn as one ``currentColor`` group at opacity 1 (one coverage mask per size).

    Masks hold coverage in [0, 1] as cairo gives it (values ``k / 255``).
    """
    codes = {}
    for size, mask in masks.items():
        code = mask_codes(mask)
        if code is None:
            raise ValueError(f"{icon.name}: a coverage mask must hold values k / 255")
        codes[int(size)] = (code,)
    return Drawing(icon.name, (Layer(CURRENT_COLOR, icon.linear, 1.0),), codes)


def _packed(table: NDArray[np.uint8]) -> NDArray[np.uint32]:
    """``(..., 3)`` codes packed as one uint32 each, to gather whole pixels at once."""
    flat = table.reshape(-1, 3)
    packed = np.zeros((flat.shape[0], 4), dtype=np.uint8)
    packed[:, :3] = flat
    return packed.view(np.uint32).reshape(-1)


def _unpacked(pixels: NDArray[np.uint32]) -> NDArray[np.uint8]:
    return pixels[..., np.newaxis].view(np.uint8)[..., :3]


def composite_drawings(
    drawings: Sequence[Drawing],
    size: int,
    background: ArrayLike,
    alphas: ArrayLike = 1.0,
    pipeline: Pipeline = "linear",
    blend: Blend = Blend.EXTENDED,
) -> NDArray[np.uint8]:
    """Composite ``n`` icons at ``size`` on one canvas to 8-bit sRGB pixels ``(n, h, w, 3)``.

    ``background`` is the canvas in linear sRGB ``(3,)``, ``alphas`` one
    coefficient per icon (or a scalar).  Groups are painted in order as the
    module docstring says; :attr:`Blend.DIFFERENCE` and :attr:`Blend.EXCLUSION`
    (the paper's controls) replace ``X`` and mix in linear light.  Under
    ``css`` a coefficient times an opacity above 1 raises :class:`ValueError`.

    >>> full = (np.array([[255]], np.uint8),)
    >>> red = Drawing("x", (Layer("#ff0000", (1.0, 0.0, 0.0), 1.0),), {1: full})
    >>> composite_drawings([red], 1, [1.0, 1.0, 1.0]).tolist()
    [[[[255, 0, 0]]]]
    """
    n = len(drawings)
    b = np.asarray(background, dtype=np.float64).reshape(3)
    a = np.broadcast_to(np.asarray(alphas, dtype=np.float64), (n,))
    single = [k for k, d in enumerate(drawings) if len(d.layers) == 1]
    out = np.empty((n, size, size, 3), dtype=np.uint8)
    css = pipeline == "css" and Blend(blend) is Blend.EXTENDED
    if pipeline not in ("linear", "css"):
        raise ValueError(f"unknown pipeline {pipeline!r}; use one of linear, css")
    start = srgb_encode(b) if css else b
    for k, d in enumerate(drawings):
        if not d.layers:  # nothing painted: the canvas
            out[k] = to_8bit(b)
    # Per (icon, group, level): the weight w = (a) o q and what the group adds.
    if single:
        codes = np.stack([drawings[k].masks[size][0] for k in single])
        weight, term = _tables([drawings[k].layers[0] for k in single], a[single], b, css, blend)
        w = weight[..., np.newaxis]
        # P after one group on the canvas, as composite_css or composite_coverage write it.
        first = np.clip(start + w * (term - start), 0.0, 1.0) if css else term + (1.0 - w) * start
        table = _finish(first, css)  # (s, 256, 3)
        index = codes.astype(np.intp) + 256 * np.arange(len(single), dtype=np.intp)[:, None, None]
        out[single] = _unpacked(np.take(_packed(table), index))
    several = [k for k, d in enumerate(drawings) if len(d.layers) > 1]
    for k in several:
        d = drawings[k]
        weight, term = _tables(d.layers, np.full(len(d.layers), a[k]), b, css, blend)
        colour = np.broadcast_to(start, (size, size, 3)).copy()
        for g, mask in enumerate(d.masks[size]):
            level = mask.astype(np.intp)
            if css:  # P' + w (Cs' - P'), as composite_css writes it
                w = weight[g, level][..., np.newaxis]
                colour = np.clip(colour + w * (term[g, 0] - colour), 0.0, 1.0)
            else:
                colour = term[g, level] + (1.0 - weight[g, level])[..., np.newaxis] * colour
        out[k] = _finish(colour, css)
    return out


def _tables(
    layers: Sequence[Layer],
    alphas: NDArray[np.float64],
    background: NDArray[np.float64],
    css: bool,
    blend: Blend,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Per group and level: the weight ``w`` and the term it adds.

    ``linear``: ``w = o q`` and the term ``w X``; ``css``: ``w = a (o q)``
    and the term ``Cs'`` (the same at every level), for ``P' + w (Cs' - P')``.
    """
    sources = np.array([layer.source for layer in layers], dtype=np.float64).reshape(-1, 3)
    opacity = np.array([layer.opacity for layer in layers], dtype=np.float64)
    q = opacity[:, np.newaxis] * _LEVELS[np.newaxis, :]  # (g, 256): o q, as the row's o * q50
    if css:
        weight = alphas[:, np.newaxis] * q
        if np.any((weight < 0.0) | (weight > 1.0)):
            raise ValueError(
                "alpha times opacity outside [0, 1] cannot be drawn by pipeline css "
                "(CSS opacity is limited to [0, 1])"
            )
        encoded = srgb_encode(sources)
        return weight, np.broadcast_to(encoded[:, np.newaxis, :], (len(layers), 256, 3))
    x = blend_colors(sources, background, alphas, blend)  # (g, 3)
    return q, q[..., np.newaxis] * x[:, np.newaxis, :]


def _finish(colour: NDArray[np.float64], css: bool) -> NDArray[np.uint8]:
    """8-bit codes: encoded values rounded (css), or linear light encoded and rounded."""
    if css:
        return np.rint(np.clip(colour, 0.0, 1.0) * 255.0).astype(np.uint8)
    return to_8bit(colour)


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
