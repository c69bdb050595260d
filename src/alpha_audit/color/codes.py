"""8-bit sRGB codes: what a screen shows for a linear colour, and back.

Their own module (beside :mod:`~alpha_audit.color.transfer`, below the parsers and
the metrics), so that :func:`~alpha_audit.color.metrics.judged_contrast` can judge
what ships without importing the colour parsers.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from alpha_audit.color.transfer import srgb_decode, srgb_encode_unit

__all__ = ["from_8bit", "pack_8bit", "shipped", "to_8bit"]


def to_8bit(linear: ArrayLike) -> NDArray[np.uint8]:
    """Linear colour to 8-bit sRGB codes: clip, encode, x255, round half to even.

    The paper (Appendix A.1) counts collisions on these codes.

    >>> to_8bit([1.0, 0.21404114048223255, 0.0]).tolist()
    [255, 128, 0]
    """
    encoded = srgb_encode_unit(np.clip(np.asarray(linear, dtype=np.float64), 0.0, 1.0))
    encoded *= 255.0
    return np.rint(encoded, out=encoded).astype(np.uint8)  # np.rint rounds half to even


def pack_8bit(codes: ArrayLike) -> NDArray[np.int64]:
    """8-bit RGB codes ``(..., 3)`` to one 24-bit integer ``0xRRGGBB`` per colour.

    The key every 8-bit collision is decided on (audit, gate and suggest alike):
    two outputs collide exactly when their packed codes are equal.

    >>> int(pack_8bit([255, 128, 0]))
    16744448
    """
    c = np.asarray(codes).astype(np.int64)
    return (c[..., 0] << 16) | (c[..., 1] << 8) | c[..., 2]


# The 256 linear values an 8-bit channel can show, decoded once by the same formula.
_DECODED: NDArray[np.float64] = srgb_decode(np.arange(256, dtype=np.float64) / 255.0)


def from_8bit(codes: ArrayLike) -> NDArray[np.float64]:
    """8-bit sRGB codes to linear colour (``uint8`` codes, as :func:`to_8bit` gives: a
    lookup of the decoded values).

    >>> every = np.arange(256)
    >>> bool(np.array_equal(from_8bit(every.astype(np.uint8)), srgb_decode(every / 255.0)))
    True
    """
    c = np.asarray(codes)
    if c.dtype == np.uint8:
        return np.asarray(_DECODED[c], dtype=np.float64)
    return srgb_decode(c.astype(np.float64) / 255.0)


def shipped(linear: ArrayLike) -> NDArray[np.float64]:
    """What an 8-bit screen shows for a linear colour: :func:`to_8bit`, decoded again.

    The gate judges these (docs/model.md, "What ships is what is judged"); the
    float colour stays in the JSON rows.

    >>> shipped([0.5, 0.0, 1.0]).round(6).tolist()
    [0.502886, 0.0, 1.0]
    """
    return from_8bit(to_8bit(linear))
