"""What the experiments share: progress callbacks, alpha checks, source luminance parts."""

from __future__ import annotations

from collections.abc import Callable, Iterable

import numpy as np
from numpy.typing import NDArray

from alpha_audit.color import LUMINANCE_WEIGHTS
from alpha_audit.errors import UsageError

__all__ = ["Progress", "check_alphas", "noop", "source_parts"]

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
