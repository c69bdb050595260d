"""Extended-coefficient compositing in linear sRGB (paper, Section 3).

``raw = Cb + a (Cs - Cb)`` is ordinary source-over on an opaque canvas written
as a scaling of the object-background difference; any finite real ``a`` is
allowed and the result is clipped per channel to [0, 1].  Antialiased coverage
``q`` stays separate from ``a`` (paper, Appendix A.2).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = [
    "composite_coverage",
    "composite_extended",
    "composite_raw",
    "difference_blend",
    "exclusion_blend",
]


def composite_raw(source: ArrayLike, background: ArrayLike, alpha: ArrayLike) -> NDArray:
    """Unclipped ``Cb + a (Cs - Cb)``; ``alpha`` broadcasts against the leading shape.

    >>> composite_raw([1.0, 0.5, 0.0], [0.5, 0.5, 0.5], 2.0).tolist()
    [1.5, 0.5, -0.5]
    """
    s = np.asarray(source, dtype=np.float64)
    b = np.asarray(background, dtype=np.float64)
    a = np.asarray(alpha, dtype=np.float64)[..., np.newaxis]
    return b + a * (s - b)


def composite_extended(source: ArrayLike, background: ArrayLike, alpha: ArrayLike) -> NDArray:
    """``clip(Cb + a (Cs - Cb), 0, 1)`` per channel, the paper's displayed output.

    ``source`` and ``background`` are linear sRGB in [0, 1] with channels last;
    ``alpha`` has the leading shape (or broadcasts to it).

    >>> composite_extended([1.0, 0.5, 0.0], [0.5, 0.5, 0.5], 2.0).tolist()
    [1.0, 0.5, 0.0]
    """
    return np.clip(composite_raw(source, background, alpha), 0.0, 1.0)


def composite_coverage(
    source: ArrayLike, background: ArrayLike, alpha: ArrayLike, coverage: ArrayLike
) -> NDArray:
    """``q * clip(Cb + a (Cs - Cb)) + (1 - q) * Cb`` for an antialiased mask ``q``.

    ``coverage`` has the leading (pixel) shape; the coefficient scales the colour
    difference, coverage only mixes the clipped output with the canvas.
    """
    b = np.asarray(background, dtype=np.float64)
    q = np.asarray(coverage, dtype=np.float64)[..., np.newaxis]
    out = composite_extended(source, b, alpha)
    return q * out + (1.0 - q) * b


def difference_blend(source: ArrayLike, background: ArrayLike) -> NDArray:
    """W3C Compositing ``difference``: ``|Cs - Cb|`` (the paper's control)."""
    return np.abs(np.asarray(source, dtype=np.float64) - np.asarray(background, dtype=np.float64))


def exclusion_blend(source: ArrayLike, background: ArrayLike) -> NDArray:
    """W3C Compositing ``exclusion``: ``Cs + Cb - 2 Cs Cb`` (the paper's control)."""
    s = np.asarray(source, dtype=np.float64)
    b = np.asarray(background, dtype=np.float64)
    return s + b - 2.0 * s * b
