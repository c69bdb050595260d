"""The broad-grid experiment: a source grid on a background grid (paper, Table 1, Section 4.2).

The counting kernel is :func:`alpha_audit.reproduce.broad.broad_counts`.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field

import numpy as np

from alpha_audit.color import CONTRAST_TOLERANCE, composite_extended, contrast_ratio, srgb_decode
from alpha_audit.reproduce.broad import broad_counts
from alpha_audit.reproduce.experiments.common import Progress, check_alphas, noop
from alpha_audit.reproduce.grids import encoded_levels

__all__ = ["BroadGridResult", "broad_grid"]


@dataclass(frozen=True)
class BroadGridResult:
    """``S**3`` sources on ``B**3`` backgrounds at one alpha (paper, Table 1 and Section 4.2).

    ``worst_source``/``worst_background`` are encoded sRGB of the combination
    with the largest loss; ``worst_contrast`` maps alpha (1.0 and every alpha
    of the run) to its contrast ratio there.
    """

    alpha: float
    source_levels: int
    background_levels: int
    combinations: int
    increase: int
    decrease: int
    loss_le_0_25: int
    max_loss: float
    worst_source: tuple[float, float, float]
    worst_background: tuple[float, float, float]
    worst_contrast: dict[float, float] = field(default_factory=dict)

    @property
    def unchanged(self) -> int:
        """Combinations whose change is within the tolerance."""
        return self.combinations - self.increase - self.decrease

    @property
    def increase_pct(self) -> float:
        """Percent of combinations whose contrast ratio increases."""
        return 100.0 * self.increase / self.combinations

    @property
    def decrease_pct(self) -> float:
        """Percent of combinations whose contrast ratio decreases."""
        return 100.0 * self.decrease / self.combinations

    @property
    def loss_le_0_25_pct(self) -> float:
        """Percent of the decreases whose loss is at most 0.25."""
        return 100.0 * self.loss_le_0_25 / self.decrease if self.decrease else 0.0


def broad_grid(
    alphas: Iterable[float] = (1.1, 1.4),
    *,
    source_levels: int = 17,
    background_levels: int = 33,
    tol: float = CONTRAST_TOLERANCE,
    progress: Progress = noop,
) -> tuple[BroadGridResult, ...]:
    """Every source-grid colour on every background-grid colour (paper: 17**3 x 33**3).

    Depends on nothing the paper leaves out, so at the defaults it reproduces
    the paper's printed figures exactly.
    """
    alphas = check_alphas(alphas)
    src_enc, bg_enc = encoded_levels(source_levels), encoded_levels(background_levels)
    counts = broad_counts(srgb_decode(src_enc), srgb_decode(bg_enc), np.array(alphas), tol=tol)
    progress(0.9)
    results = []
    for a, c in zip(alphas, counts, strict=True):
        i_r, i_g, i_b, j_r, j_g, j_b = c.worst
        source = (float(src_enc[i_r]), float(src_enc[i_g]), float(src_enc[i_b]))
        background = (float(bg_enc[j_r]), float(bg_enc[j_g]), float(bg_enc[j_b]))
        s_lin, b_lin = srgb_decode(source), srgb_decode(background)
        worst = {1.0: float(contrast_ratio(s_lin, b_lin))}
        worst |= {
            x: float(contrast_ratio(composite_extended(s_lin, b_lin, x), b_lin)) for x in alphas
        }
        results.append(
            BroadGridResult(
                alpha=a,
                source_levels=source_levels,
                background_levels=background_levels,
                combinations=source_levels**3 * background_levels**3,
                increase=c.increase,
                decrease=c.decrease,
                loss_le_0_25=c.loss_le_limit,
                max_loss=c.max_loss,
                worst_source=source,
                worst_background=background,
                worst_contrast=worst,
            )
        )
    progress(0.1)
    return tuple(results)
