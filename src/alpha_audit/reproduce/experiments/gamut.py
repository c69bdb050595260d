"""The full-gamut experiment: every 8-bit source on every canvas (paper, Section 4.2).

Nothing here prints; ``progress`` callbacks receive the fraction of the
experiment just completed (the CLI turns them into progress bars).
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from alpha_audit.color import CONTRAST_TOLERANCE, relative_luminance, srgb_decode
from alpha_audit.model import Theme
from alpha_audit.reproduce import kernels
from alpha_audit.reproduce.experiments.common import (
    Progress,
    check_alphas,
    coefficient_changes,
    noop,
    source_parts,
)
from alpha_audit.reproduce.grids import encoded_levels

__all__ = ["CanvasChange", "ContrastChange", "FullGamutResult", "full_gamut"]


@dataclass(frozen=True)
class ContrastChange:
    """Contrast-ratio changes of a set of source x canvas combinations against alpha = 1.

    Counts are exact; ``sum_*`` are sums of ``CR(output) - CR(source)`` for
    extended alpha, Difference and Exclusion.
    """

    combinations: int
    increase: int
    decrease: int
    newly_reach: int
    sum_change: float
    sum_difference: float
    sum_exclusion: float

    @property
    def unchanged(self) -> int:
        """Combinations whose change is within the tolerance."""
        return self.combinations - self.increase - self.decrease

    def _pct(self, count: int) -> float:
        return 100.0 * count / self.combinations

    @property
    def increase_pct(self) -> float:
        """Percent of combinations whose contrast ratio increases."""
        return self._pct(self.increase)

    @property
    def decrease_pct(self) -> float:
        """Percent of combinations whose contrast ratio decreases."""
        return self._pct(self.decrease)

    @property
    def unchanged_pct(self) -> float:
        """Percent of combinations unchanged within the tolerance."""
        return self._pct(self.unchanged)

    @property
    def newly_reach_pct(self) -> float:
        """Percent of all combinations below the threshold at alpha 1 and at or above it now."""
        return self._pct(self.newly_reach)

    @property
    def mean_change(self) -> float:
        """Mean contrast-ratio change."""
        return self.sum_change / self.combinations

    @property
    def mean_difference_change(self) -> float:
        """Mean change for the Difference blend mode (control)."""
        return self.sum_difference / self.combinations

    @property
    def mean_exclusion_change(self) -> float:
        """Mean change for the Exclusion blend mode (control)."""
        return self.sum_exclusion / self.combinations

    def __add__(self, other: ContrastChange) -> ContrastChange:
        return ContrastChange(
            *(getattr(self, f) + getattr(other, f) for f in self.__dataclass_fields__)
        )

    def as_dict(self) -> dict[str, float | int]:
        """Counts, sums and the derived percentages and means, unrounded."""
        names = [
            "unchanged",
            "increase_pct",
            "decrease_pct",
            "unchanged_pct",
            "newly_reach_pct",
            "mean_change",
            "mean_difference_change",
            "mean_exclusion_change",
        ]
        raw = {f: getattr(self, f) for f in self.__dataclass_fields__}
        return raw | {name: getattr(self, name) for name in names}


@dataclass(frozen=True)
class CanvasChange:
    """One canvas's :class:`ContrastChange`."""

    name: str
    color: str
    mode: str
    change: ContrastChange


@dataclass(frozen=True)
class FullGamutResult:
    """All ``levels**3`` sources on every canvas of a theme at one alpha."""

    theme: str
    alpha: float
    levels: int
    threshold: float
    canvases: tuple[CanvasChange, ...]

    def group(self, mode: str) -> ContrastChange | None:
        """Pooled changes over the canvases of one mode (``light``/``dark``), if any."""
        members = [c.change for c in self.canvases if c.mode == mode]
        return sum(members[1:], members[0]) if members else None

    @property
    def total(self) -> ContrastChange:
        """Pooled changes over all canvases."""
        changes = [c.change for c in self.canvases]
        return sum(changes[1:], changes[0])


def _blend_parts(
    levels: NDArray[np.float64], backgrounds: NDArray[np.float64], kind: str
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Luminance parts of Difference / Exclusion outputs (same expressions as color.composite)."""
    s = levels[np.newaxis, np.newaxis, :]
    b = backgrounds[:, :, np.newaxis]
    tables = np.abs(s - b) if kind == "difference" else s + b - 2.0 * s * b
    return kernels.luminance_parts(tables)


def full_gamut(
    theme: Theme,
    alphas: Iterable[float] = (1.1, 1.4),
    *,
    levels: int = 256,
    threshold: float | None = None,
    tol: float = CONTRAST_TOLERANCE,
    progress: Progress = noop,
) -> tuple[FullGamutResult, ...]:
    """Every source of a ``levels**3`` grid (256: all 8-bit colours) on every canvas.

    Per alpha and canvas: contrast increases / decreases / unchanged (``tol``),
    the sum of changes, how many newly reach ``threshold`` (default: the
    theme's, 3:1 for paper16), and the Difference and Exclusion controls.
    Paper, Section 4.2.  Exact: identical counts to the straightforward
    float64 evaluation (:mod:`alpha_audit.reproduce.reference`).
    """
    alphas = check_alphas(alphas)
    threshold = theme.threshold if threshold is None else float(threshold)
    encoded = encoded_levels(levels)
    lev = srgb_decode(encoded)
    backgrounds = theme.backgrounds
    m = backgrounds.shape[0]
    yb = relative_luminance(backgrounds)
    n_sources = levels**3
    ps, qs = source_parts(lev, m)
    sum_source = kernels.contrast_sums(ps, qs, yb)
    controls = {
        kind: kernels.contrast_sums(*_blend_parts(lev, backgrounds, kind), yb) - sum_source
        for kind in ("difference", "exclusion")
    }
    progress(0.1)

    # Coefficients >= 0 in one batch; a negative one reverses the tables (they fall
    # with the level), so each is counted alone, every combination from the tables.
    batches = [[a for a in alphas if a >= 0], *([a] for a in alphas if a < 0)]
    done: dict[float, FullGamutResult] = {}
    for batch in filter(None, batches):
        counts, sums = coefficient_changes(lev, backgrounds, batch, tol=tol, threshold=threshold)
        shape = (len(batch), m)
        inc, dec, reach = (c.reshape(shape) for c in (counts.increase, counts.decrease,
                                                       counts.newly_reach))  # fmt: skip
        for i, a in enumerate(batch):
            changes = tuple(
                CanvasChange(c.name, c.color, str(c.mode), ContrastChange(
                    n_sources, int(inc[i, j]), int(dec[i, j]), int(reach[i, j]),
                    float(sums[i, j] - sum_source[j]), float(controls["difference"][j]),
                    float(controls["exclusion"][j]),
                ))
                for j, c in enumerate(theme.canvases)
            )  # fmt: skip
            done[a] = FullGamutResult(theme.name, a, levels, threshold, changes)
        progress(0.8 * len(batch) / len(alphas))
    progress(0.1)
    return tuple(done[a] for a in alphas)
