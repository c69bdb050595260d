"""The sRGB transfer functions of CSS Color 4 (section 10.2, ``lin_sRGB`` / ``gam_sRGB``).

Their own module so that every colour module can use them without importing
the parsers (:mod:`alpha_audit.color.srgb` imports :mod:`alpha_audit.color.css`).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = ["srgb_decode", "srgb_encode", "srgb_encode_unit"]

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
    # The curve of |v|, signed again: multiplying by the sign is exact, so these are
    # the formula's own bits (an extended value below -1 encodes below -1).
    out = srgb_encode_unit(np.abs(v))
    return np.copysign(out, v, out=out)


def srgb_encode_unit(linear: ArrayLike) -> NDArray[np.float64]:
    """:func:`srgb_encode` of non-negative values (bitwise the same), in a new array.

    For the 8-bit quantisation, which clips first: no sign to carry.  In place,
    because on large grids the temporaries, not the power, were most of the cost.

    >>> x = np.linspace(0.0, 1.0, 1001)
    >>> bool(np.array_equal(srgb_encode_unit(x), srgb_encode(x)))
    True
    """
    v = np.asarray(linear, dtype=np.float64)
    out = np.power(v, 1 / _GAMMA, out=np.empty_like(v))
    out *= 1 + _OFFSET
    out -= _OFFSET
    linear_part = v <= _ENCODE_BREAK
    out[linear_part] = v[linear_part] * _LINEAR_SLOPE
    return out
