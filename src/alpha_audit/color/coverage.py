"""Size metrics from a coverage mask: how much of a paint's ink is solid at a raster size.

WCAG judges the specified colour, not antialiased pixels (Understanding SC
1.4.11), so these figures are legibility beyond WCAG.  A mask holds coverage
``q`` in [0, 1] per pixel (uint8 codes / 255 or floats); only ``q > 0`` counts.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from alpha_audit.color.composite import Pipeline, composite_paint
from alpha_audit.color.metrics import contrast_ratio

__all__ = [
    "CoverageStats",
    "coverage_stats",
    "full_share",
    "median_coverage",
    "size_contrast_float",
]


def _coverage(mask: ArrayLike) -> NDArray[np.float64]:
    m = np.asarray(mask)
    q = m.astype(np.float64) / 255.0 if m.dtype == np.uint8 else m.astype(np.float64)
    return q[q > 0.0]


def median_coverage(mask: ArrayLike) -> float:
    """Coverage-weighted median coverage ``q50`` of the covered pixels; NaN when none.

    The covered pixels' coverages sorted ascending, each weighted by itself;
    ``q50`` is the first coverage at which the cumulative weight reaches half
    the total ink.  A mask of one solid and two quarter-covered pixels gives 1:
    the solid pixel carries two thirds of the ink.

    >>> median_coverage([[1.0, 0.25, 0.25, 0.0]])
    1.0
    """
    m = np.asarray(mask)
    if m.dtype == np.uint8:  # 8-bit codes: exact integer sums, no rounding at the tie
        codes = np.sort(m[m > 0].astype(np.int64))
        if codes.size == 0:
            return float("nan")
        twice = 2 * np.cumsum(codes)  # reaches half: 2 * running >= total
        return float(codes[np.searchsorted(twice, twice[-1] // 2, side="left")]) / 255.0
    q = np.sort(_coverage(m))
    if q.size == 0:
        return float("nan")
    cumulative = np.cumsum(q)
    # Float sums round: "reaches half" within a relative 1e-12, far below the
    # smallest step between two cumulative sums of 8-bit-quantised coverages
    # (1/255 of a pixel in a million-pixel mask is 4e-9 of the total).
    target = 0.5 * cumulative[-1] * (1.0 - 1e-12)
    return float(q[np.searchsorted(cumulative, target, side="left")])


def full_share(mask: ArrayLike) -> float:
    """Share of the ink (sum of coverage) on fully covered pixels; NaN when none.

    >>> full_share([[1.0, 0.5, 0.5, 0.0]])
    0.5
    """
    q = _coverage(mask)
    if q.size == 0:
        return float("nan")
    return float(q[q >= 1.0].sum() / q.sum())


@dataclass(frozen=True)
class CoverageStats:
    """What a paint's mask says at one raster size."""

    q50: float
    full_share: float
    ink: float  # sum of coverage in pixels
    pixels: int  # covered pixels (q > 0)


def coverage_stats(mask: ArrayLike) -> CoverageStats:
    """:func:`median_coverage`, :func:`full_share`, ink and covered pixels of one mask."""
    q = _coverage(mask)
    return CoverageStats(median_coverage(mask), full_share(mask), float(q.sum()), int(q.size))


def size_contrast_float(
    source: ArrayLike,
    background: ArrayLike,
    alpha: ArrayLike,
    q50: ArrayLike,
    opacity: ArrayLike = 1.0,
    pipeline: Pipeline = "linear",
) -> NDArray[np.float64]:
    """Contrast against the canvas of the paint's float colour at coverage ``q50``.

    The pixel at coverage ``q`` of a paint at opacity ``o`` shows the paint at
    opacity ``q * o``; at ``q50 = 1`` this is the colour contrast.  The paper's
    maths on float colours; the audit judges the 8-bit colour that ships
    (:func:`~alpha_audit.color.metrics.judged_contrast` of the same composite).

    >>> round(float(size_contrast_float([0.0] * 3, [1.0] * 3, 1.0, 1.0)), 6)
    21.0
    """
    b = np.asarray(background, dtype=np.float64)
    q = np.asarray(q50, dtype=np.float64) * np.asarray(opacity, dtype=np.float64)
    return contrast_ratio(composite_paint(source, b, alpha, q, pipeline), b)
