"""The coefficient sweep: mean change, decreases and collisions over alpha (Figures 3, 6)."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from alpha_audit.color import CONTRAST_TOLERANCE, relative_luminance, srgb_decode
from alpha_audit.errors import UsageError
from alpha_audit.model import Theme
from alpha_audit.reproduce import kernels
from alpha_audit.reproduce.experiments.collisions import pair_collisions
from alpha_audit.reproduce.experiments.common import (
    Progress,
    check_alphas,
    coefficient_changes,
    noop,
    source_parts,
)
from alpha_audit.reproduce.grids import PAPER_SEED, encoded_levels, random_source_pairs

__all__ = ["SweepResult", "sweep", "sweep_alphas"]


def sweep_alphas(start: float = 0.0, stop: float = 2.0, step: float = 0.025) -> tuple[float, ...]:
    """``start, start + step, ..., stop`` as the nearest doubles of the decimal values.

    >>> sweep_alphas()[44], len(sweep_alphas())
    (1.1, 81)
    """
    if step <= 0 or stop < start:
        raise UsageError(f"bad sweep range {start}..{stop} step {step}")
    n = round((stop - start) / step) + 1
    return tuple(float(f"{start + step * i:.12g}") for i in range(n))


@dataclass(frozen=True)
class SweepResult:
    """Coefficient sweep (paper, Figures 3 and 6).

    Per group (``light``, ``dark`` and ``all``, the latter weighting the two
    groups equally) a tuple over ``alphas`` of the mean contrast change, the
    share of decreases and the 8-bit collision rate of the random pairs.
    """

    theme: str
    levels: int
    pairs: int
    seed: int
    alphas: tuple[float, ...]
    mean_change: dict[str, tuple[float, ...]]
    decrease_share: dict[str, tuple[float, ...]]
    collision_rate: dict[str, tuple[float, ...]]


def _group_means(theme: Theme, per_canvas: NDArray[np.float64]) -> dict[str, tuple[float, ...]]:
    """Mean over each mode's canvases (equal weights), then over the groups."""
    modes = np.array([c.mode for c in theme.canvases])
    groups = {
        mode: per_canvas[:, modes == mode].mean(axis=1)
        for mode in ("light", "dark")
        if np.any(modes == mode)
    }
    groups["all"] = np.mean(list(groups.values()), axis=0)
    return {k: tuple(float(x) for x in v) for k, v in groups.items()}


def sweep(
    theme: Theme,
    alphas: Sequence[float] | None = None,
    *,
    levels: int = 65,
    pairs: int = 65536,
    seed: int = PAPER_SEED,
    tol: float = CONTRAST_TOLERANCE,
    progress: Progress = noop,
) -> SweepResult:
    """Mean change, share of decreases and collision rate over a range of alphas.

    Defaults follow the paper: alpha in [0, 2] step 0.025 on a 65**3 source
    grid, 65,536 distinct random source pairs (:func:`random_source_pairs`).
    """
    alphas = sweep_alphas() if alphas is None else check_alphas(alphas)
    if min(alphas) < 0:
        raise UsageError("the sweep covers alpha >= 0 (transparency and expansion)")
    lev = srgb_decode(encoded_levels(levels))
    backgrounds = theme.backgrounds
    ps, qs = source_parts(lev, backgrounds.shape[0])
    sum_source = kernels.contrast_sums(ps, qs, relative_luminance(backgrounds))
    # The sweep reports no threshold counts.
    counts, sums = coefficient_changes(lev, backgrounds, alphas, tol=tol, threshold=None)
    progress(0.7)
    n_sources = levels**3
    collisions = pair_collisions(backgrounds, np.asarray(alphas), random_source_pairs(pairs, seed))
    progress(0.3)
    return SweepResult(
        theme=theme.name,
        levels=levels,
        pairs=pairs,
        seed=seed,
        alphas=tuple(alphas),
        mean_change=_group_means(theme, (sums - sum_source) / n_sources),
        decrease_share=_group_means(theme, counts.decrease / n_sources),
        collision_rate=_group_means(theme, collisions / pairs),
    )
