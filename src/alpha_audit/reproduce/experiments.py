"""The paper's four numerical experiments as a library API (Section 4, Appendix A).

Each function returns frozen dataclasses of *unrounded* counts and sums;
percentages and means are derived properties.  They work on any theme, so a
design-system team can ask "which share of all colours gains contrast on our
canvases at 1.2?" with ``full_gamut(load_theme("ours.yaml"), [1.2])``.

Nothing here prints; ``progress`` callbacks receive the fraction of the
experiment just completed (the CLI turns them into progress bars).
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field
from itertools import combinations

import numpy as np
from numpy.typing import NDArray

from alpha_audit.color import (
    CONTRAST_TOLERANCE,
    DELTA_E_TOLERANCE,
    LUMINANCE_WEIGHTS,
    composite_extended,
    contrast_ratio,
    delta_e_2000,
    hex_to_linear,
    relative_luminance,
    srgb_decode,
    to_8bit,
)
from alpha_audit.errors import UsageError
from alpha_audit.model import Theme
from alpha_audit.reproduce import kernels
from alpha_audit.reproduce.broad import broad_counts
from alpha_audit.reproduce.grids import (
    PAPER_SEED,
    VIBRANT,
    code_channels,
    encoded_levels,
    random_source_pairs,
)

__all__ = [
    "BroadGridResult",
    "CanvasChange",
    "ContrastChange",
    "FullGamutResult",
    "PaletteResult",
    "SweepResult",
    "broad_grid",
    "full_gamut",
    "palette_separation",
    "sweep",
    "sweep_alphas",
]

Progress = Callable[[float], None]
_WR, _WG, _WB = LUMINANCE_WEIGHTS


def _noop(_: float) -> None:
    return None


def _check_alphas(alphas: Iterable[float]) -> tuple[float, ...]:
    values = tuple(float(a) for a in alphas)
    if not values:
        raise UsageError("give at least one alpha")
    bad = [a for a in values if not np.isfinite(a)]
    if bad:
        raise UsageError(f"alpha must be a finite number, got {bad[0]!r}")
    return values


# --------------------------------------------------------------------------- full gamut


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


def _source_parts(levels: NDArray, m: int) -> tuple[NDArray, NDArray]:
    """Source luminance parts, canvas-independent, broadcast to m canvases."""
    p = (_WR * levels[:, np.newaxis] + _WG * levels[np.newaxis, :]).ravel()
    return np.broadcast_to(p, (m, p.size)), np.broadcast_to(_WB * levels, (m, levels.size))


def _blend_parts(levels: NDArray, backgrounds: NDArray, kind: str) -> tuple[NDArray, NDArray]:
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
    progress: Progress = _noop,
) -> tuple[FullGamutResult, ...]:
    """Every source of a ``levels**3`` grid (256: all 8-bit colours) on every canvas.

    Per alpha and canvas: contrast increases / decreases / unchanged (``tol``),
    the sum of changes, how many newly reach ``threshold`` (default: the
    theme's, 3:1 for paper16), and the Difference and Exclusion controls.
    Paper, Section 4.2.  Exact: identical counts to the straightforward
    float64 evaluation (:mod:`alpha_audit.reproduce.reference`).
    """
    alphas = _check_alphas(alphas)
    threshold = theme.threshold if threshold is None else float(threshold)
    encoded = encoded_levels(levels)
    lev = srgb_decode(encoded)
    backgrounds = theme.backgrounds
    m = backgrounds.shape[0]
    yb = relative_luminance(backgrounds)
    n_sources = levels**3
    ps, qs = _source_parts(lev, m)
    sum_source = kernels.contrast_sums(ps, qs, yb)
    controls = {
        kind: kernels.contrast_sums(*_blend_parts(lev, backgrounds, kind), yb) - sum_source
        for kind in ("difference", "exclusion")
    }
    progress(0.1)

    fast = [a for a in alphas if a >= 0]
    stats: dict[float, dict[str, NDArray]] = {}
    if fast:
        tables = kernels.channel_tables(
            lev, np.tile(backgrounds, (len(fast), 1)), np.repeat(fast, m)
        )
        po, qo = kernels.luminance_parts(tables)
        counts = kernels.change_counts(
            ps,
            qs,
            po.reshape(len(fast), m, -1),
            qo.reshape(len(fast), m, -1),
            yb,
            tol=tol,
            threshold=threshold,
        )
        sums = kernels.contrast_sums(po, qo, np.tile(yb, len(fast))).reshape(len(fast), m)
        for i, a in enumerate(fast):
            stats[a] = {
                "increase": counts.increase[i],
                "decrease": counts.decrease[i],
                "newly_reach": counts.newly_reach[i],
                "sum_change": sums[i] - sum_source,
            }
    progress(0.8 * len(fast) / len(alphas))
    for a in alphas:
        if a < 0:  # reverse scaling: tables fall with the level; every combination from them
            po, qo = kernels.luminance_parts(
                kernels.channel_tables(lev, backgrounds, np.full(m, a))
            )
            counts = kernels.change_counts_any_order(
                ps, qs, po, qo, yb, tol=tol, threshold=threshold
            )
            stats[a] = {
                "increase": counts.increase,
                "decrease": counts.decrease,
                "newly_reach": counts.newly_reach,
                "sum_change": kernels.contrast_sums(po, qo, yb) - sum_source,
            }
            progress(0.8 / len(alphas))
    results = []
    for a in alphas:
        s = stats[a]
        canvases = tuple(
            CanvasChange(
                c.name,
                c.color,
                str(c.mode),
                ContrastChange(
                    combinations=n_sources,
                    increase=int(s["increase"][i]),
                    decrease=int(s["decrease"][i]),
                    newly_reach=int(s["newly_reach"][i]),
                    sum_change=float(s["sum_change"][i]),
                    sum_difference=float(controls["difference"][i]),
                    sum_exclusion=float(controls["exclusion"][i]),
                ),
            )
            for i, c in enumerate(theme.canvases)
        )
        results.append(FullGamutResult(theme.name, a, levels, threshold, canvases))
    progress(0.1)
    return tuple(results)


# --------------------------------------------------------------------------- broad grid


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
    progress: Progress = _noop,
) -> tuple[BroadGridResult, ...]:
    """Every source-grid colour on every background-grid colour (paper: 17**3 x 33**3).

    Depends on nothing the paper leaves out, so at the defaults it reproduces
    the paper's printed figures exactly.
    """
    alphas = _check_alphas(alphas)
    src_enc, bg_enc = encoded_levels(source_levels), encoded_levels(background_levels)
    counts = broad_counts(srgb_decode(src_enc), srgb_decode(bg_enc), np.array(alphas), tol=tol)
    progress(0.9)
    results = []
    for a, c in zip(alphas, counts, strict=True):
        source = tuple(float(src_enc[i]) for i in c.worst[:3])
        background = tuple(float(bg_enc[j]) for j in c.worst[3:])
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
                worst_source=source,  # type: ignore[arg-type]
                worst_background=background,  # type: ignore[arg-type]
                worst_contrast=worst,
            )
        )
    progress(0.1)
    return tuple(results)


# --------------------------------------------------------------------------- collisions


def _byte_tables(backgrounds: NDArray, alphas: NDArray) -> NDArray[np.uint8]:
    """8-bit output code per (alpha, canvas, channel, source byte): (A, m, 3, 256)."""
    lev = srgb_decode(np.arange(256) / 255)
    m = backgrounds.shape[0]
    tables = kernels.channel_tables(
        lev, np.tile(backgrounds, (alphas.size, 1)), np.repeat(alphas, m)
    )
    return to_8bit(tables).reshape(alphas.size, m, 3, 256)


def pair_collisions(backgrounds: NDArray, alphas: NDArray, pairs: NDArray) -> NDArray[np.int64]:
    """Per (alpha, canvas), how many source pairs get identical 8-bit outputs.

    ``pairs`` (n, 2) holds 24-bit ``0xRRGGBB`` codes.  A clipped channel
    depends only on its source byte, so each channel is a 256-entry table
    lookup; a pair collides when all three channels' codes agree.
    """
    codes = _byte_tables(backgrounds, np.asarray(alphas, dtype=np.float64))
    channels = code_channels(pairs)  # (n, 2, 3)
    out = np.zeros(codes.shape[:2], dtype=np.int64)
    for a in range(codes.shape[0]):
        same = None
        for k in range(3):
            table = codes[a, :, k, :]
            eq = np.take(table, channels[:, 0, k], axis=1) == np.take(
                table, channels[:, 1, k], axis=1
            )
            same = eq if same is None else same & eq
        out[a] = np.count_nonzero(same, axis=1)
    return out


# --------------------------------------------------------------------------- sweep


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


def _group_means(theme: Theme, per_canvas: NDArray) -> dict[str, tuple[float, ...]]:
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
    progress: Progress = _noop,
) -> SweepResult:
    """Mean change, share of decreases and collision rate over a range of alphas.

    Defaults follow the paper: alpha in [0, 2] step 0.025 on a 65**3 source
    grid, 65,536 distinct random source pairs (:func:`random_source_pairs`).
    """
    alphas = sweep_alphas() if alphas is None else _check_alphas(alphas)
    if min(alphas) < 0:
        raise UsageError("the sweep covers alpha >= 0 (transparency and expansion)")
    lev = srgb_decode(encoded_levels(levels))
    backgrounds = theme.backgrounds
    m = backgrounds.shape[0]
    yb = relative_luminance(backgrounds)
    ps, qs = _source_parts(lev, m)
    sum_source = kernels.contrast_sums(ps, qs, yb)
    n_alpha = len(alphas)
    a = np.asarray(alphas)
    po, qo = kernels.luminance_parts(
        kernels.channel_tables(lev, np.tile(backgrounds, (n_alpha, 1)), np.repeat(a, m))
    )
    progress(0.05)
    counts = kernels.change_counts(
        ps,
        qs,
        po.reshape(n_alpha, m, -1),
        qo.reshape(n_alpha, m, -1),
        yb,
        tol=tol,
        threshold=None,  # the sweep reports no threshold counts
    )
    progress(0.45)
    sums = kernels.contrast_sums(po, qo, np.tile(yb, n_alpha)).reshape(n_alpha, m)
    progress(0.2)
    n_sources = levels**3
    collisions = pair_collisions(backgrounds, a, random_source_pairs(pairs, seed))
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


# --------------------------------------------------------------------------- palette


@dataclass(frozen=True)
class PaletteResult:
    """Separation of palette pairs and of random pairs (paper, Section 4.3).

    ``smaller[a]``: palette pair x canvas combinations whose CIEDE2000 at
    alpha ``a`` is below that at alpha 1 by more than the tolerance;
    ``collisions[a]``: those with identical 8-bit outputs.  The per-canvas
    tuples follow the theme's canvas order.  ``random_collisions[a]`` counts
    colliding random pair x canvas combinations.
    """

    theme: str
    palette: tuple[str, ...]
    alphas: tuple[float, ...]
    combinations: int
    smaller: dict[float, int]
    collisions: dict[float, int]
    smaller_per_canvas: dict[float, tuple[int, ...]]
    collisions_per_canvas: dict[float, tuple[int, ...]]
    random_pairs: int
    seed: int
    random_combinations: int
    random_alphas: tuple[float, ...]
    random_collisions: dict[float, int]


def palette_separation(
    theme: Theme,
    alphas: Iterable[float] = (1.1, 1.4),
    *,
    palette: Sequence[str] = VIBRANT,
    pairs: int = 65536,
    seed: int = PAPER_SEED,
    random_alphas: Iterable[float] = (1.0, 1.1, 1.4),
    progress: Progress = _noop,
) -> PaletteResult:
    """CIEDE2000 and 8-bit collisions of palette pairs on every canvas, and of random pairs."""
    alphas = _check_alphas(alphas)
    random_alphas = _check_alphas(random_alphas)
    colours = np.array([hex_to_linear(c) for c in palette])
    first, second = (np.array(ix) for ix in zip(*combinations(range(len(palette)), 2), strict=True))
    backgrounds = theme.backgrounds
    bg = backgrounds[:, np.newaxis, :]
    base = delta_e_2000(colours[first], colours[second])[np.newaxis, :]
    smaller, collide = {}, {}
    for a in alphas:
        out_1 = composite_extended(colours[first][np.newaxis], bg, a)
        out_2 = composite_extended(colours[second][np.newaxis], bg, a)
        smaller[a] = np.count_nonzero(delta_e_2000(out_1, out_2) < base - DELTA_E_TOLERANCE, axis=1)
        collide[a] = np.all(to_8bit(out_1) == to_8bit(out_2), axis=-1).sum(axis=1)
    progress(0.2)
    random = pair_collisions(backgrounds, np.array(random_alphas), random_source_pairs(pairs, seed))
    progress(0.8)
    return PaletteResult(
        theme=theme.name,
        palette=tuple(palette),
        alphas=alphas,
        combinations=first.size * backgrounds.shape[0],
        smaller={a: int(v.sum()) for a, v in smaller.items()},
        collisions={a: int(v.sum()) for a, v in collide.items()},
        smaller_per_canvas={a: tuple(int(x) for x in v) for a, v in smaller.items()},
        collisions_per_canvas={a: tuple(int(x) for x in v) for a, v in collide.items()},
        random_pairs=pairs,
        seed=seed,
        random_combinations=pairs * backgrounds.shape[0],
        random_alphas=random_alphas,
        random_collisions={a: int(random[i].sum()) for i, a in enumerate(random_alphas)},
    )
