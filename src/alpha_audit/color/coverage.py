"""Size metrics from a coverage mask: how much of a paint's ink is solid at a raster size.

WCAG judges the specified colour, not antialiased pixels (Understanding SC
1.4.11), so these figures are legibility beyond WCAG.  A mask holds coverage
``q`` in [0, 1] per pixel (uint8 codes / 255 or floats); only ``q > 0`` counts.
Of 8-bit codes every figure is exact (correctly rounded from integer sums of a
histogram), and many masks are reduced at once (:func:`coverage_stats_of`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from alpha_audit.color.composite import Pipeline, composite_paint
from alpha_audit.color.metrics import contrast_ratio

__all__ = [
    "CoverageStats",
    "coverage_stats",
    "coverage_stats_of",
    "full_share",
    "median_coverage",
    "size_contrast_float",
]


def _coverage(mask: ArrayLike) -> NDArray[np.float64]:
    """The covered pixels' coverages of a float mask."""
    q = np.asarray(mask, dtype=np.float64)
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
        return coverage_stats_of([m])[0].q50
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
    m = np.asarray(mask)
    if m.dtype == np.uint8:
        return coverage_stats_of([m])[0].full_share
    q = _coverage(m)
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
    m = np.asarray(mask)
    if m.dtype == np.uint8:
        return coverage_stats_of([m])[0]
    q = _coverage(m)
    return CoverageStats(median_coverage(m), full_share(m), float(q.sum()), int(q.size))


def coverage_stats_of(masks: Sequence[NDArray[np.uint8]]) -> list[CoverageStats]:
    """:func:`coverage_stats` of each 8-bit mask (any shapes), from one histogram of them all.

    Each figure is exact: the ink is ``sum(codes) / 255`` and the full share
    ``255 * solid pixels / sum(codes)``, each one division of integers; ``q50``
    the first code at which twice the running ink reaches the total.

    >>> masks = [np.zeros((2, 2), np.uint8), np.full((3, 3), 9, np.uint8)]
    >>> [s.pixels for s in coverage_stats_of(masks)]
    [0, 9]
    """
    if not masks:
        return []
    sizes = np.array([m.size for m in masks])
    label = np.repeat(np.arange(len(masks)) * 256, sizes)
    codes = np.concatenate([np.ravel(m) for m in masks]).astype(np.intp) + label
    counts = np.bincount(codes, minlength=256 * len(masks)).reshape(len(masks), 256)
    running = np.cumsum(counts * np.arange(256), axis=1)  # ink in codes, level by level
    total = running[:, -1]
    q50 = np.argmax(2 * running >= total[:, None], axis=1)
    out = []
    for k, ink in enumerate(total.tolist()):
        if ink == 0:
            out.append(CoverageStats(math.nan, math.nan, 0.0, 0))
            continue
        solid = int(counts[k, 255])
        pixels = int(sizes[k] - counts[k, 0])
        out.append(CoverageStats(int(q50[k]) / 255, 255 * solid / ink, ink / 255, pixels))
    return out


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
