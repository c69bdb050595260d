"""Straightforward chunked float64 implementations of the experiments.

No tables, no bisection: every (source, background) combination goes through
``srgb_decode``, ``composite_extended``, ``relative_luminance`` and
``contrast_from_luminance`` exactly as an audit would.  They define what the
fast kernels must reproduce (identical counts, sums to 1e-12 relative) and are
the baseline of ``benchmarks/bench_reproduce.py``.  Slow on purpose.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from alpha_audit.color import (
    CONTRAST_TOLERANCE,
    NON_TEXT_THRESHOLD,
    composite_extended,
    contrast_from_luminance,
    difference_blend,
    exclusion_blend,
    relative_luminance,
    srgb_decode,
)

__all__ = ["reference_broad_grid", "reference_full_gamut", "source_grid"]

_CHUNK = 1 << 18


def source_grid(
    encoded_levels: NDArray[np.float64], start: int = 0, stop: int | None = None
) -> NDArray[np.float64]:
    """Encoded sources ``start:stop`` of the ``C**3`` grid of per-channel levels, B fastest."""
    levels = np.asarray(encoded_levels, dtype=np.float64)
    n = levels.size
    index = np.arange(start, n**3 if stop is None else min(stop, n**3))
    return np.stack([levels[index // (n * n)], levels[index // n % n], levels[index % n]], axis=-1)


def reference_full_gamut(
    encoded_levels: NDArray[np.float64],
    backgrounds: NDArray[np.float64],
    alpha: float,
    *,
    tol: float = CONTRAST_TOLERANCE,
    threshold: float = NON_TEXT_THRESHOLD,
    controls: bool = True,
) -> dict[str, NDArray[np.int64] | NDArray[np.float64]]:
    """Per-canvas counts and sums over the product source grid of ``encoded_levels``.

    Returns arrays over canvases: ``increase``, ``decrease``, ``newly_reach``
    (counts) and ``sum_change``, ``sum_difference``, ``sum_exclusion`` (sums of
    contrast change against the source's contrast).
    """
    n_sources = np.asarray(encoded_levels).size ** 3
    n = backgrounds.shape[0]
    out: dict[str, NDArray[np.int64] | NDArray[np.float64]]
    out = {key: np.zeros(n, dtype=np.int64) for key in ("increase", "decrease", "newly_reach")}
    out |= {key: np.zeros(n) for key in ("sum_change", "sum_difference", "sum_exclusion")}
    for i, background in enumerate(backgrounds):
        yb = relative_luminance(background)
        for start in range(0, n_sources, _CHUNK):
            source = srgb_decode(source_grid(encoded_levels, start, start + _CHUNK))
            cr_source = contrast_from_luminance(relative_luminance(source), yb)
            output = composite_extended(source, background, alpha)
            change = contrast_from_luminance(relative_luminance(output), yb) - cr_source
            out["increase"][i] += np.count_nonzero(change > tol)
            out["decrease"][i] += np.count_nonzero(change < -tol)
            out["newly_reach"][i] += np.count_nonzero(
                (cr_source < threshold) & (change + cr_source >= threshold)
            )
            out["sum_change"][i] += change.sum()
            if controls:
                for key, blend in (
                    ("sum_difference", difference_blend),
                    ("sum_exclusion", exclusion_blend),
                ):
                    cr = contrast_from_luminance(relative_luminance(blend(source, background)), yb)
                    out[key][i] += (cr - cr_source).sum()
    return out


def reference_broad_grid(
    source_levels: NDArray[np.float64],
    background_levels: NDArray[np.float64],
    alpha: float,
    *,
    tol: float = CONTRAST_TOLERANCE,
) -> dict[str, float | int]:
    """Counts, largest loss and losses <= 0.25 over all source x background grid pairs."""
    sources = srgb_decode(source_grid(np.asarray(source_levels, dtype=np.float64)))
    backgrounds = srgb_decode(source_grid(np.asarray(background_levels, dtype=np.float64)))
    y_source = relative_luminance(sources)
    per_chunk = max(1, _CHUNK // sources.shape[0])
    inc = dec = small = 0
    max_loss = 0.0
    for start in range(0, backgrounds.shape[0], per_chunk):
        bg = backgrounds[start : start + per_chunk, np.newaxis, :]
        yb = relative_luminance(bg)
        output = composite_extended(sources[np.newaxis], bg, alpha)
        change = contrast_from_luminance(relative_luminance(output), yb) - contrast_from_luminance(
            y_source[np.newaxis], yb
        )
        inc += int(np.count_nonzero(change > tol))
        decreased = change < -tol
        dec += int(np.count_nonzero(decreased))
        small += int(np.count_nonzero(decreased & (change >= -0.25)))
        max_loss = max(max_loss, float(-change.min()))
    return {"increase": inc, "decrease": dec, "loss_le_0_25": small, "max_loss": max_loss}
