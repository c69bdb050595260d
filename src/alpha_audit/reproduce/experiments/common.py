"""What the experiments share: progress callbacks, alpha checks, source luminance parts."""

from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence

import numpy as np
from numpy.typing import NDArray

from alpha_audit.color import LUMINANCE_WEIGHTS, relative_luminance
from alpha_audit.errors import UsageError
from alpha_audit.reproduce import kernels

__all__ = ["Progress", "check_alphas", "coefficient_changes", "noop", "source_parts"]

Progress = Callable[[float], None]
_WR, _WG, _WB = LUMINANCE_WEIGHTS


def noop(_: float) -> None:
    """The default progress callback: report nothing."""
    return None


def check_alphas(alphas: Iterable[float]) -> tuple[float, ...]:
    """``alphas`` as floats; at least one, all finite."""
    values = tuple(float(a) for a in alphas)
    if not values:
        raise UsageError("give at least one alpha")
    bad = [a for a in values if not np.isfinite(a)]
    if bad:
        raise UsageError(f"alpha must be a finite number, got {bad[0]!r}")
    return values


def source_parts(
    levels: NDArray[np.float64], m: int
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Source luminance parts, canvas-independent, broadcast to m canvases."""
    p = (_WR * levels[:, np.newaxis] + _WG * levels[np.newaxis, :]).ravel()
    return np.broadcast_to(p, (m, p.size)), np.broadcast_to(_WB * levels, (m, levels.size))


def coefficient_changes(
    levels: NDArray[np.float64],
    backgrounds: NDArray[np.float64],
    alphas: Sequence[float],
    *,
    tol: float,
    threshold: float | None,
) -> tuple[kernels.ChangeCounts, NDArray[np.float64]]:
    """Counts of contrast changes and sums of contrast over the product grid of ``levels``
    on every canvas, per (alpha, canvas): alphas all ``>= 0``, or one below 0 (its tables
    fall with the level, so every combination is formed from them)."""
    m, n = backgrounds.shape[0], len(alphas)
    yb = relative_luminance(backgrounds)
    ps, qs = source_parts(levels, m)
    po, qo = kernels.luminance_parts(
        kernels.channel_tables(levels, np.tile(backgrounds, (n, 1)), np.repeat(alphas, m))
    )
    if alphas[0] >= 0:
        shape = (n, m, -1)
        counts = kernels.change_counts(
            ps, qs, po.reshape(shape), qo.reshape(shape), yb, tol=tol, threshold=threshold
        )
    else:
        assert n == 1 and threshold is not None
        counts = kernels.change_counts_any_order(ps, qs, po, qo, yb, tol=tol, threshold=threshold)
    return counts, kernels.contrast_sums(po, qo, np.tile(yb, n)).reshape(n, m)
