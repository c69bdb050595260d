"""Composite every icon on every canvas and measure what the coefficient changes.

Pure computation: :func:`audit` returns an :class:`AuditResult` of numpy arrays
and findings; it never prints.  Shapes: ``n`` icons x ``m`` canvases.
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Sequence
from dataclasses import dataclass, replace
from functools import cached_property
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from alpha_audit.color import (
    CONTRAST_TOLERANCE,
    DELTA_E_TOLERANCE,
    composite_extended,
    contrast_from_luminance,
    delta_e_2000_lab,
    linear_to_lab,
    pack_8bit,
    relative_luminance,
    to_8bit,
)
from alpha_audit.color.nearest import (
    PAIR_CHUNK,
    ClosestPair,
    closest_pair_delta_e_2000,
    iter_pairs,
)
from alpha_audit.errors import InputError
from alpha_audit.load.svg import IconProblem
from alpha_audit.model import IconSet, Theme

if TYPE_CHECKING:
    from alpha_audit.paint_audit import PaintAudit

__all__ = [
    "AuditResult",
    "CanvasSummary",
    "Collision",
    "Row",
    "Separation",
    "Summary",
    "audit",
    "find_collisions",
]


@dataclass(frozen=True)
class Row:
    """One icon on one canvas."""

    icon: str
    canvas: str
    source: str
    background: str
    alpha: float
    output: str
    contrast_ref: float
    contrast: float
    gain: float
    passes_ref: bool
    passes: bool
    newly_passes: bool
    loss: bool
    newly_fails: bool


@dataclass(frozen=True)
class Collision:
    """Distinct source colours that give the same 8-bit output on one canvas."""

    canvas: str
    output: str
    sources: tuple[str, ...]
    icons: tuple[str, ...]
    new: bool = True  # False when the same sources already collide at alpha = 1


@dataclass(frozen=True)
class Separation:
    """The closest pair of distinct source colours on one canvas (CIEDE2000)."""

    canvas: str
    delta_e: float
    delta_e_ref: float
    icons: tuple[str, str]
    sources: tuple[str, str]
    # Pairs whose CIEDE2000 is smaller than at alpha = 1; None above DECREASES_BUDGET.
    decreases: int | None
    pairs: int
    # The set's own closest pair at alpha = 1 (the sources; the same on every
    # canvas), which need not be the pair closest at alpha.
    set_delta_e_ref: float = math.nan


@dataclass(frozen=True)
class CanvasSummary:
    """Per-canvas figures for the summary table."""

    canvas: str
    background: str
    mode: str
    icons: int
    mean_gain: float
    passing_ref: int
    passing: int
    newly_pass: int
    newly_fail: int
    losses: int
    max_loss: float
    worst_icon: str | None
    collisions: int
    separation: Separation | None


@dataclass(frozen=True)
class Summary:
    """Whole-audit figures (the JSON ``summary``)."""

    combinations: int
    increase_pct: float
    decrease_pct: float
    unchanged_pct: float
    mean_gain: float
    newly_pass: int
    newly_fail: int
    losses: int
    max_loss: float
    collisions: int
    new_collisions: int
    min_delta_e: float | None


def _hex(packed: int) -> str:
    return f"#{packed:06x}"


def find_collisions(
    output_codes: NDArray[np.uint8],
    source_keys: NDArray[np.int64],
) -> list[tuple[int, int, NDArray[np.intp]]]:
    """Groups of icons whose distinct sources share one 8-bit output, per canvas.

    ``output_codes`` is ``(n, m, 3)``, ``source_keys`` identifies each icon's
    source colour ``(n,)``.  Returns ``(canvas index, packed output, icon indices)``.
    """
    n, m = output_codes.shape[:2]
    if n == 0 or m == 0:
        return []
    packed = pack_8bit(output_codes)  # (n, m)
    # One sort of every (canvas, output, source) triple: O(nm log nm), no loop
    # over canvases or output groups; only real collisions reach Python.
    canvas = np.repeat(np.arange(m), n)
    icon = np.tile(np.arange(n), m)
    out = packed.T.reshape(-1)
    keys = np.asarray(source_keys).reshape(-1)[icon]
    order = np.lexsort((icon, keys, out, canvas))
    c, o, s = canvas[order], out[order], keys[order]
    new_group = np.r_[True, (c[1:] != c[:-1]) | (o[1:] != o[:-1])]
    starts = np.flatnonzero(new_group)
    ends = np.r_[starts[1:], order.size]
    # Sources are sorted within a group: distinct ones exist iff first != last.
    colliding = s[starts] != s[ends - 1]
    members = icon[order]
    return [
        (int(c[a]), int(o[a]), np.sort(members[a:b]))
        for a, b in zip(starts[colliding].tolist(), ends[colliding].tolist(), strict=True)
    ]


@dataclass(frozen=True)
class AuditResult:
    """Every number of one theme x icon-set audit; see :func:`audit`."""

    theme: Theme
    iconset: IconSet
    threshold: float
    alpha: NDArray[np.float64]  # (n,)
    output: NDArray[np.float64]  # (n, m, 3) linear, clipped
    output_codes: NDArray[np.uint8]  # (n, m, 3)
    contrast_ref: NDArray[np.float64]  # (n, m), alpha = 1
    contrast: NDArray[np.float64]  # (n, m)
    collisions: tuple[Collision, ...]
    problems: tuple[IconProblem, ...] = ()
    tolerance: float = CONTRAST_TOLERANCE
    # Per (icon, paint, canvas) figures when the icons' own paints were read
    # (alpha_audit.paint_audit); None for an audit of manifest colours only.
    paints: PaintAudit | None = None

    @cached_property
    def separations(self) -> tuple[Separation, ...]:
        """Closest pair of distinct colours per canvas, computed on first use only."""
        return tuple(_separations(self.theme, self.iconset, self.output))

    # Derived arrays are cached: per-canvas summaries read them once per canvas.
    @cached_property
    def gain(self) -> NDArray[np.float64]:
        """``contrast - contrast_ref``."""
        return self.contrast - self.contrast_ref

    @cached_property
    def loss(self) -> NDArray[np.bool_]:
        """Contrast decreased by more than the tolerance."""
        return self.gain < -self.tolerance

    @cached_property
    def increase(self) -> NDArray[np.bool_]:
        """Contrast increased by more than the tolerance."""
        return self.gain > self.tolerance

    @cached_property
    def passes_ref(self) -> NDArray[np.bool_]:
        """At or above the threshold at alpha = 1."""
        return self.contrast_ref >= self.threshold

    @cached_property
    def passes(self) -> NDArray[np.bool_]:
        """At or above the threshold at the icon's alpha."""
        return self.contrast >= self.threshold

    @cached_property
    def newly_passes(self) -> NDArray[np.bool_]:
        """Below the threshold at alpha = 1, at or above it at the icon's alpha."""
        return self.passes & ~self.passes_ref

    @cached_property
    def newly_fails(self) -> NDArray[np.bool_]:
        """At or above the threshold at alpha = 1, below it at the icon's alpha."""
        return self.passes_ref & ~self.passes

    def rows(self) -> Iterator[Row]:
        """Icon x canvas rows in stable order (canvas order, then icon order)."""
        icons, canvases = self.iconset.icons, self.theme.canvases
        # Python lists per column once: indexing numpy scalars per cell costs
        # ~50x more than the row itself (5,100 rows: 0.25 s).
        output = [[_hex(v) for v in col] for col in pack_8bit(self.output_codes).T.tolist()]
        contrast_ref, contrast = self.contrast_ref.T.tolist(), self.contrast.T.tolist()
        gain = self.gain.T.tolist()
        flags = [
            f.T.tolist()
            for f in (self.passes_ref, self.passes, self.newly_passes, self.loss, self.newly_fails)
        ]
        alphas = self.alpha.tolist()
        for j, canvas in enumerate(canvases):
            pr, p, npass, loss, nfail = (f[j] for f in flags)
            for i, icon in enumerate(icons):
                yield Row(
                    icon=icon.name,
                    canvas=canvas.name,
                    source=icon.color,
                    background=canvas.color,
                    alpha=alphas[i],
                    output=output[j][i],
                    contrast_ref=contrast_ref[j][i],
                    contrast=contrast[j][i],
                    gain=gain[j][i],
                    passes_ref=pr[i],
                    passes=p[i],
                    newly_passes=npass[i],
                    loss=loss[i],
                    newly_fails=nfail[i],
                )

    @cached_property
    def summary(self) -> Summary:
        """Whole-audit summary figures."""
        gain = self.gain
        total = gain.size
        losses = self.loss
        separations = [s.delta_e for s in self.separations]

        def pct(k: float) -> float:
            return 100.0 * float(k) / total if total else 0.0

        n_inc, n_dec = int(self.increase.sum()), int(losses.sum())
        return Summary(
            combinations=int(total),
            increase_pct=pct(n_inc),
            decrease_pct=pct(n_dec),
            unchanged_pct=pct(total - n_inc - n_dec),
            mean_gain=float(gain.mean()) if total else 0.0,
            newly_pass=int(self.newly_passes.sum()),
            newly_fail=int(self.newly_fails.sum()),
            losses=n_dec,
            max_loss=float(-gain[losses].min()) if n_dec else 0.0,
            collisions=len(self.collisions),
            new_collisions=sum(c.new for c in self.collisions),
            min_delta_e=min(separations) if separations else None,
        )

    def canvas_summaries(self) -> list[CanvasSummary]:
        """One :class:`CanvasSummary` per canvas, in theme order."""
        out = []
        gain = self.gain
        by_canvas = {s.canvas: s for s in self.separations}
        for j, canvas in enumerate(self.theme.canvases):
            g = gain[:, j]
            losses = self.loss[:, j]
            worst = int(np.argmin(g)) if losses.any() else None
            out.append(
                CanvasSummary(
                    canvas=canvas.name,
                    background=canvas.color,
                    mode=str(canvas.mode),
                    icons=int(g.size),
                    mean_gain=float(g.mean()) if g.size else 0.0,
                    passing_ref=int(self.passes_ref[:, j].sum()),
                    passing=int(self.passes[:, j].sum()),
                    newly_pass=int(self.newly_passes[:, j].sum()),
                    newly_fail=int(self.newly_fails[:, j].sum()),
                    losses=int(losses.sum()),
                    max_loss=float(-g[worst]) if worst is not None else 0.0,
                    worst_icon=self.iconset.icons[worst].name if worst is not None else None,
                    collisions=sum(c.canvas == canvas.name for c in self.collisions),
                    separation=by_canvas.get(canvas.name),
                )
            )
        return out


# Icon x canvas combinations in one check (all audits together): each is a
# JSON row of about 450 bytes and a few microseconds of work, so this bounds
# time (seconds) and report size (~110 MB) whatever a pull request puts in a
# theme (up to 4,096 canvases) or a manifest (up to 10,000 icons).
MAX_COMBINATIONS = 250_000


def check_combinations(themes: Sequence[Theme], iconsets: Sequence[IconSet]) -> None:
    """Refuse a check larger than :data:`MAX_COMBINATIONS` before any work is done."""
    total = sum(len(t.canvases) for t in themes) * sum(len(s.icons) for s in iconsets)
    if total > MAX_COMBINATIONS:
        icons = sum(len(s.icons) for s in iconsets)
        canvases = sum(len(t.canvases) for t in themes)
        raise InputError(
            f"{icons} icons x {canvases} canvases = {total:,} combinations; at most "
            f"{MAX_COMBINATIONS:,} per check (split the theme or the icon set)",
            path=themes[0].path if len(themes) == 1 else None,
        )


# Counting the pairs that got closer needs every pair (no bound prunes it):
# above this many pair x canvas evaluations ``Separation.decreases`` is None.
# 10^6 CIEDE2000 evaluations take about a second (colour-science, one core).
DECREASES_BUDGET = 1_000_000


def _separations(
    theme: Theme,
    iconset: IconSet,
    output: NDArray[np.float64],
) -> list[Separation]:
    """Closest pair of distinct source colours per canvas, at alpha and at 1.

    Exact and in bounded memory: :func:`~alpha_audit.color.nearest.closest_pair`
    prunes by lightness instead of holding every pair.
    """
    icons = iconset.icons
    # One representative icon per distinct (source colour, alpha) style.
    styles: dict[tuple[str, float], int] = {}
    for i, icon in enumerate(icons):
        styles.setdefault((icon.color, icon.alpha), i)
    reps = np.array(sorted(styles.values()), dtype=np.intp)
    colors = [icons[i].color for i in reps]
    labels = np.unique(np.array(colors, dtype=object), return_inverse=True)[1].reshape(-1)
    k, m = reps.size, len(theme.canvases)
    group_sizes = np.bincount(labels) if k else np.zeros(0, dtype=np.intp)
    pairs = k * (k - 1) // 2 - int(np.sum(group_sizes * (group_sizes - 1) // 2))
    if pairs == 0:
        return []
    lab_ref = linear_to_lab(iconset.sources[reps])  # (k, 3)
    lab_out = linear_to_lab(output[reps])  # (k, m, 3)
    decreases: list[int | None] = [None] * m
    closest: list[ClosestPair | None] = [None] * m
    if pairs * m <= DECREASES_BUDGET:
        # Few pairs: every pair on every canvas at once, in triu order (argmin
        # ties go to the first pair, as in the pruned search).
        counts = np.zeros(m, dtype=np.int64)
        best = np.full(m, np.inf)
        best_pair = np.zeros((m, 2), dtype=np.intp)
        for first, second in iter_pairs(k, labels, chunk=max(1, PAIR_CHUNK // max(1, m))):
            de_ref = delta_e_2000_lab(lab_ref[first], lab_ref[second])  # (p,)
            de = delta_e_2000_lab(lab_out[first], lab_out[second]).reshape(first.size, m)
            counts += np.sum(de < (de_ref - DELTA_E_TOLERANCE)[:, np.newaxis], axis=0)
            t = np.argmin(de, axis=0)
            value = de[t, np.arange(m)]
            better = value < best
            best = np.where(better, value, best)
            best_pair[better] = np.stack([first[t], second[t]], axis=1)[better]
        decreases = [int(c) for c in counts]
        closest = [
            ClosestPair(int(a), int(b), float(v)) for (a, b), v in zip(best_pair, best, strict=True)
        ]
    else:
        closest = [closest_pair_delta_e_2000(lab_out[:, j], labels) for j in range(m)]
    at_one = closest_pair_delta_e_2000(lab_ref, labels)  # canvas-independent: the sources
    set_ref = math.nan if at_one is None else at_one.distance
    result = []
    for j, canvas in enumerate(theme.canvases):
        pair = closest[j]
        assert pair is not None  # pairs > 0
        a, b = int(reps[pair.first]), int(reps[pair.second])
        de_ref = delta_e_2000_lab(lab_ref[pair.first], lab_ref[pair.second])
        result.append(
            Separation(
                canvas=canvas.name,
                delta_e=pair.distance,
                delta_e_ref=float(de_ref),
                icons=(icons[a].name, icons[b].name),
                sources=(icons[a].color, icons[b].color),
                decreases=decreases[j],
                pairs=pairs,
                set_delta_e_ref=set_ref,
            )
        )
    return result


def audit(
    theme: Theme,
    iconset: IconSet,
    *,
    alpha: float | None = None,
    threshold: float | None = None,
    problems: tuple[IconProblem, ...] = (),
) -> AuditResult:
    """Composite every icon of ``iconset`` on every canvas of ``theme``.

    ``alpha`` overrides every icon's coefficient; ``threshold`` the theme's.
    Icons listed in ``problems`` (failed rasterisation) are left out.

    >>> from alpha_audit.model import Canvas, Icon, IconSet, Theme
    >>> theme = Theme("t", (Canvas("paper", "#ffffff"),))
    >>> icons = IconSet("s", (Icon("alert", "alert.svg", "#ee7733", 1.1),))
    >>> next(audit(theme, icons).rows()).output
    '#ec5a00'
    """
    check_combinations([theme], [iconset])
    if alpha is not None:
        iconset = iconset.with_alpha(alpha)
    broken = {p.icon for p in problems}
    if broken:
        iconset = replace(iconset, icons=tuple(i for i in iconset.icons if i.name not in broken))
    threshold = theme.threshold if threshold is None else float(threshold)
    sources = iconset.sources[:, np.newaxis, :]  # (n, 1, 3)
    backgrounds = theme.backgrounds[np.newaxis, :, :]  # (1, m, 3)
    alphas = iconset.alphas
    output = composite_extended(sources, backgrounds, alphas[:, np.newaxis])
    y_bg = relative_luminance(backgrounds)
    contrast_ref = contrast_from_luminance(relative_luminance(sources), y_bg)
    contrast = contrast_from_luminance(relative_luminance(output), y_bg)
    codes = to_8bit(output)

    # Distinct sources at full precision: two rgb() colours may share an 8-bit code.
    source_keys = np.unique(iconset.sources, axis=0, return_inverse=True)[1].reshape(-1)
    ref_codes = to_8bit(np.broadcast_to(sources, output.shape))
    ref_pairs = {
        (j, frozenset(source_keys[g].tolist()))
        for j, _, g in find_collisions(ref_codes, source_keys)
    }
    collisions = []
    for j, packed, group in find_collisions(codes, source_keys):
        icons = [iconset.icons[i] for i in group]
        collisions.append(
            Collision(
                canvas=theme.canvases[j].name,
                output=_hex(packed),
                sources=tuple(sorted({i.color for i in icons})),
                icons=tuple(i.name for i in icons),
                new=(j, frozenset(source_keys[group].tolist())) not in ref_pairs,
            )
        )
    return AuditResult(
        theme=theme,
        iconset=iconset,
        threshold=threshold,
        alpha=alphas,
        output=output,
        output_codes=codes,
        contrast_ref=contrast_ref,
        contrast=contrast,
        collisions=tuple(collisions),
        problems=tuple(problems),
    )
