"""sRGB transfer functions, 8-bit quantisation and colour parsing.

All functions take ``ArrayLike`` with channels on the last axis (where there
are channels) and return float64 arrays of the same leading shape.

The transfer functions are the CSS Color 4 ones (section 10.2, "sRGB"), the
same piecewise curve as IEC 61966-2-1.  They are written out here rather than
taken from ``colour.models.eotf_sRGB`` because the paper pins CSS Color 4's
decode breakpoint (0.04045) while colour-science derives it as
``12.92 * 0.0031308`` (0.040449936), and because colour-science's
domain/range bookkeeping costs several times more than the arithmetic on the
large grids of ``reproduce``.  ``tests/color/test_srgb.py`` checks both
against colour-science.
"""

from __future__ import annotations

import re

import numpy as np
from numpy.typing import ArrayLike, NDArray
from PIL import ImageColor

from alpha_audit.errors import ColorSyntaxError

__all__ = [
    "from_8bit",
    "hex_to_linear",
    "linear_to_hex",
    "pack_8bit",
    "parse_color",
    "srgb_decode",
    "srgb_encode",
    "to_8bit",
]

# CSS Color 4, 10.2 (lin_sRGB / gam_sRGB).
_DECODE_BREAK = 0.04045
_ENCODE_BREAK = 0.0031308
_LINEAR_SLOPE = 12.92
_GAMMA = 2.4
_OFFSET = 0.055


def srgb_decode(encoded: ArrayLike) -> NDArray[np.float64]:
    """Encoded sRGB (0..1) to linear light, CSS Color 4 ``lin_sRGB``.

    >>> float(srgb_decode(1.0)), float(srgb_decode(0.5))
    (1.0, 0.21404114048223255)
    """
    v = np.asarray(encoded, dtype=np.float64)
    magnitude = np.abs(v)
    curve = np.sign(v) * ((magnitude + _OFFSET) / (1 + _OFFSET)) ** _GAMMA
    return np.where(magnitude <= _DECODE_BREAK, v / _LINEAR_SLOPE, curve)


def srgb_encode(linear: ArrayLike) -> NDArray[np.float64]:
    """Linear light to encoded sRGB (0..1), CSS Color 4 ``gam_sRGB``.

    >>> round(float(srgb_encode(0.21404114048223255)), 12)
    0.5
    """
    v = np.asarray(linear, dtype=np.float64)
    magnitude = np.abs(v)
    curve = np.sign(v) * ((1 + _OFFSET) * magnitude ** (1 / _GAMMA) - _OFFSET)
    return np.where(magnitude > _ENCODE_BREAK, curve, v * _LINEAR_SLOPE)


def to_8bit(linear: ArrayLike) -> NDArray[np.uint8]:
    """Linear colour to 8-bit sRGB codes: clip, encode, x255, round half to even.

    The paper (Appendix A.1) counts collisions on these codes.

    >>> to_8bit([1.0, 0.21404114048223255, 0.0]).tolist()
    [255, 128, 0]
    """
    encoded = srgb_encode(np.clip(np.asarray(linear, dtype=np.float64), 0.0, 1.0))
    return np.rint(encoded * 255.0).astype(np.uint8)  # np.rint rounds half to even


def pack_8bit(codes: ArrayLike) -> NDArray[np.int64]:
    """8-bit RGB codes ``(..., 3)`` to one 24-bit integer ``0xRRGGBB`` per colour.

    The key every 8-bit collision is decided on (audit, gate and suggest alike):
    two outputs collide exactly when their packed codes are equal.

    >>> int(pack_8bit([255, 128, 0]))
    16744448
    """
    c = np.asarray(codes).astype(np.int64)
    return (c[..., 0] << 16) | (c[..., 1] << 8) | c[..., 2]


def from_8bit(codes: ArrayLike) -> NDArray[np.float64]:
    """8-bit sRGB codes to linear colour."""
    return srgb_decode(np.asarray(codes, dtype=np.float64) / 255.0)


def linear_to_hex(linear: ArrayLike) -> str:
    """One linear colour to ``#rrggbb`` via :func:`to_8bit`.

    >>> linear_to_hex([1.0, 0.0, 0.0])
    '#ff0000'
    """
    r, g, b = (int(c) for c in to_8bit(linear).reshape(3))
    return f"#{r:02x}{g:02x}{b:02x}"


def hex_to_linear(text: str) -> NDArray[np.float64]:
    """``#rrggbb`` (or any :func:`parse_color` notation) to linear colour."""
    return srgb_decode(parse_color(text))


_ALLOWED = "use #rgb, #rrggbb, rgb(r g b), rgb(r, g, b) or a CSS colour name"
_HEX = re.compile(r"#([0-9a-fA-F]{3}|[0-9a-fA-F]{6})")
_HEX_WITH_ALPHA = re.compile(r"#([0-9a-fA-F]{4}|[0-9a-fA-F]{8})")
_NUMBER = r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?%?"
_RGB = re.compile(
    rf"rgba?\(\s*({_NUMBER})\s*(?:,\s*|\s+)({_NUMBER})\s*(?:,\s*|\s+)({_NUMBER})\s*"
    rf"(?:(?:/|,)\s*({_NUMBER})\s*)?\)",
    re.IGNORECASE,
)


def parse_color(text: str) -> NDArray[np.float64]:
    """Parse a CSS sRGB colour to encoded sRGB floats in [0, 1].

    Accepts ``#rgb``, ``#rrggbb``, ``rgb(r g b)``, ``rgb(r, g, b)`` (numbers
    0-255 or percentages) and the 148 CSS named colours.  A colour with its
    own alpha, or a channel outside sRGB, raises :class:`ColorSyntaxError`:
    alpha-audit's coefficient lives in ``alpha:``, never in the colour.

    >>> parse_color("#ee7733").tolist() == [0xEE / 255, 0x77 / 255, 0x33 / 255]
    True
    >>> parse_color("rgb(255 0 0)").tolist()
    [1.0, 0.0, 0.0]
    """
    if not isinstance(text, str):
        raise ColorSyntaxError(f"{text!r} is not a colour string; {_ALLOWED}")
    value = text.strip()
    lowered = value.lower()
    if match := _HEX.fullmatch(value):
        digits = match.group(1)
        if len(digits) == 3:
            digits = "".join(ch * 2 for ch in digits)
        return np.array([int(digits[i : i + 2], 16) for i in (0, 2, 4)], dtype=np.float64) / 255
    if _HEX_WITH_ALPHA.fullmatch(value):
        raise ColorSyntaxError(
            f"{value!r} carries its own alpha; give an opaque colour and set the coefficient "
            "with alpha:"
        )
    if match := _RGB.fullmatch(value):
        if match.group(4) is not None or lowered.startswith("rgba"):
            raise ColorSyntaxError(
                f"{value!r} carries its own alpha; give an opaque colour and set the coefficient "
                "with alpha:"
            )
        channels = []
        for token in match.group(1, 2, 3):
            number = float(token.rstrip("%"))
            scaled = number / 100 if token.endswith("%") else number / 255
            if not 0.0 <= scaled <= 1.0:
                raise ColorSyntaxError(
                    f"{value!r} is outside sRGB; channels must be 0-255 or 0%-100%"
                )
            channels.append(scaled)
        return np.array(channels, dtype=np.float64)
    if lowered == "transparent":
        raise ColorSyntaxError("'transparent' has no colour; " + _ALLOWED)
    if lowered in ImageColor.colormap:  # CSS Color 4 named colours
        named = ImageColor.colormap[lowered]  # Pillow caches looked-up names as tuples
        if isinstance(named, str):
            return parse_color(named)
        return np.array(named[:3], dtype=np.float64) / 255
    raise ColorSyntaxError(f"{value!r} is not a colour; {_ALLOWED}")
