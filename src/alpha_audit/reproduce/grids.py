"""Grids, palettes and random pairs the experiments enumerate.

Paper, Appendix A.1: "Grids are uniform in encoded sRGB with both endpoints
included, then decoded"; collisions use 8-bit outputs rounded half to even;
random pairs use NumPy's default generator with seed 20260913.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = [
    "PAPER_SEED",
    "VIBRANT",
    "encoded_levels",
    "random_source_pairs",
]

# Paper, Appendix A.1.
PAPER_SEED = 20260913
# Paul Tol's Vibrant palette (Tol 2021), in the paper's order (Section 4.1).
VIBRANT = ("#ee7733", "#0077bb", "#33bbee", "#ee3377", "#cc3311", "#009988", "#bbbbbb")


def encoded_levels(n: int) -> NDArray[np.float64]:
    """``n`` per-channel levels uniform in encoded sRGB, endpoints included.

    >>> float(encoded_levels(17)[13])
    0.8125
    """
    if n < 2:
        raise ValueError(f"a grid needs at least 2 levels per channel, got {n}")
    return np.arange(n) / (n - 1)


def random_source_pairs(n: int, seed: int = PAPER_SEED) -> NDArray[np.int64]:
    """``n`` distinct unordered pairs of distinct 8-bit sRGB colours, as 24-bit codes.

    The paper names only the generator and seed ("65,536 distinct
    source-color pairs", ``default_rng(20260913)``), so the construction is
    ours: draw ``(n, 2)`` codes uniform on ``[0, 2**24)`` from
    ``np.random.default_rng(seed)``, drop pairs of equal colours, order each
    pair (smaller code first), keep the first occurrence of each pair and
    draw again until ``n`` remain.  At the paper's seed the first draw has
    neither equal nor repeated pairs, and on the paper's canvases it gives
    exactly its printed 617 and 15,098 collisions (seeds 1 to 3 give 555 to
    644 and 14,834 to 15,008), so it is very likely the paper's draw.
    Returns shape ``(n, 2)``, first column the smaller code; a code
    ``0xRRGGBB`` holds the channels' bytes.

    >>> random_source_pairs(3).shape
    (3, 2)
    """
    rng = np.random.default_rng(seed)
    kept = np.empty((0, 2), dtype=np.int64)
    while kept.shape[0] < n:
        draw = rng.integers(0, 1 << 24, size=(n, 2), dtype=np.int64)
        draw = np.sort(draw[draw[:, 0] != draw[:, 1]], axis=1)
        kept = np.concatenate([kept, draw])
        _, first = np.unique(kept[:, 0] << 24 | kept[:, 1], return_index=True)
        kept = kept[np.sort(first)]
    return kept[:n]


def code_channels(codes: ArrayLike) -> NDArray[np.intp]:
    """24-bit ``0xRRGGBB`` codes -> (..., 3) channel bytes."""
    c = np.asarray(codes, dtype=np.int64)
    return np.stack([(c >> 16) & 0xFF, (c >> 8) & 0xFF, c & 0xFF], axis=-1).astype(np.intp)
