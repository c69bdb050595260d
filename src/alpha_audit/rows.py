"""The one audit: every paint of every icon on every canvas, as a table of rows.

A *paint row* is one colour drawn on one canvas: an SVG element's own fill or
stroke (grouped by colour and opacity), or, when no SVG was read, the icon's
manifest colour as a ``currentColor`` paint at opacity 1.  For a paint of
source ``Cs`` at opacity ``o`` on canvas ``Cb`` with coefficient ``a`` under a
pipeline (:func:`~alpha_audit.color.composite.composite_paint`):

* ``output`` -- the colour shown (``linear``: ``o clip(Cb + a (Cs - Cb)) +
  (1 - o) Cb``; ``css``: the encoded blend with ``a o``, then 8-bit);
* ``reference`` -- the same paint at ``a = 1``; contrast at ``a`` against the
  contrast of the reference (WCAG 2.2, against the canvas);
* drift and hue shift between reference and output (CIEDE2000, OKLCH);
* per raster size, ``q50``, the full share and the size contrast
  (:mod:`alpha_audit.color.coverage`).

Everything a report says is computed from these arrays: the summary, the
per-canvas table, collisions (distinct paints whose outputs share an 8-bit
code) and separation (the closest pair of distinct paints, CIEDE2000), all under
the audit's pipeline.  Pure computation, nothing is printed.  Shapes: ``p``
paint rows, ``m`` canvases, ``k`` sizes.
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass, field, replace
from functools import cached_property
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from alpha_audit.color import (
    CONTRAST_TOLERANCE,
    DELTA_E_TOLERANCE,
    PIPELINES,
    Pipeline,
    composite_paint,
    contrast_ratio,
    delta_e_2000,
    delta_e_2000_lab,
    hex_to_linear,
    hue_shift,
    judged_contrast,
    linear_to_lab,
    pack_8bit,
    shipped,
    to_8bit,
)
from alpha_audit.color.nearest import (
    PAIR_CHUNK,
    ClosestPair,
    closest_pair_delta_e_2000,
    iter_pairs,
)
from alpha_audit.errors import InputError, UsageError
from alpha_audit.model import Icon, IconProblem, IconSet, Location, Theme
from alpha_audit.observed import MeasuredPaint
from alpha_audit.paints import CURRENT_COLOR, PaintSet
from alpha_audit.ranges import DEFAULT_COMBINATIONS

__all__ = [
    "MAX_COMBINATIONS",
    "MAX_SIZE_CELLS",
    "AuditResult",
    "CanvasSummary",
    "Collision",
    "PaintEntry",
    "Row",
    "RowColumns",
    "Separation",
    "SizeFigures",
    "Summary",
    "Unaudited",
    "audit",
    "check_combinations",
    "check_pipeline",
    "find_collisions",
    "observed_audit",
    "resolve_pipeline",
    "widest_delta_e",
    "widest_delta_e_many",
    "with_alphas",
]

# Paint rows x canvases in one check by default (all audits together): each is a
# JSON row of about 600 bytes and a few microseconds of work, so this bounds time
# and report size whatever a pull request puts in a theme or a manifest; a project
# raises it with max-combinations (ranges.DEFAULT_COMBINATIONS is this number).
MAX_COMBINATIONS = DEFAULT_COMBINATIONS
# Size figures hold a (rows, canvases, sizes, 3) float64 array and its
# temporaries, ~200 MB at the cap.
MAX_SIZE_CELLS = 2_000_000
# Counting the pairs that got closer needs every pair (no bound prunes it):
# above this many pair x canvas evaluations ``Separation.decreases`` is None.
# 10^6 CIEDE2000 evaluations take about a second (colour-science, one core).
DECREASES_BUDGET = 1_000_000


def resolve_pipeline(*choices: str | None) -> Pipeline:
    """The first pipeline given, in precedence order (``--pipeline``, config, icon set, theme).

    ``linear`` when none is given; unknown names raise :class:`UsageError`.

    >>> resolve_pipeline(None, "css", "linear")
    'css'
    """
    for choice in choices:
        if choice is None:
            continue
        name = choice.strip().lower()
        if name not in PIPELINES:
            raise UsageError(f"unknown pipeline {choice!r}; use one of: {', '.join(PIPELINES)}")
        return name
    return "linear"


_CSS_WAY_OUT = (
    "CSS opacity is limited to [0, 1]; use pipeline: linear (WebGL, an SVG filter in "
    "linearRGB) or export per-theme colours (docs/model.md, 'Pipelines')"
)


def check_pipeline(iconset: IconSet, pipeline: Pipeline, alpha: float | None = None) -> None:
    """Refuse coefficients ``pipeline`` cannot draw: under ``css``, alpha outside [0, 1].

    ``alpha`` is the override of every icon's (``--alpha``), a usage error; else the
    error names the icon and its manifest line.
    """
    if pipeline != "css":
        return
    if alpha is not None:
        if not 0.0 <= alpha <= 1.0:
            raise UsageError(f"`alpha` {alpha:g} cannot be drawn by pipeline css: {_CSS_WAY_OUT}")
        return
    for icon in iconset.icons:
        if not 0.0 <= icon.alpha <= 1.0:
            raise InputError(
                f"icon {icon.name!r} has alpha {icon.alpha:g}, which pipeline css cannot "
                f"draw: {_CSS_WAY_OUT}",
                path=iconset.path,
                line=icon.alpha_line,
            )


def _counted(n: int, noun: str, plural: str | None = None) -> str:
    """``1 size``, ``3 sizes``, ``1,200 paints``."""
    return f"{n:,} {noun if n == 1 else plural or noun + 's'}"


def check_combinations(
    rows: int,
    canvases: int,
    sizes: int = 1,
    path: Path | None = None,
    limit: int = MAX_COMBINATIONS,
) -> None:
    """Refuse an audit over ``limit`` paint rows (size figures: 8 per row) before the work.

    ``limit`` is the project's resource bound (``max-combinations``, default
    :data:`MAX_COMBINATIONS`); the size figures scale with it from
    :data:`MAX_SIZE_CELLS`.
    """
    cells = max(MAX_SIZE_CELLS, limit * (MAX_SIZE_CELLS // MAX_COMBINATIONS))
    if rows * canvases > limit or rows * canvases * sizes > cells:
        raise InputError(
            f"{_counted(rows, 'paint')} x {_counted(canvases, 'canvas', 'canvases')} x "
            f"{_counted(sizes, 'size')} is more than one check "
            f"audits ({limit:,} paint rows, {cells:,} paint x canvas x size figures); raise "
            "`max_combinations` if the memory is there (docs/ci.md), "
            "split the theme or the icon set, or give fewer sizes",
            path=path,
        )


@dataclass(frozen=True)
class SizeFigures:
    """One paint on one canvas at one raster size."""

    q50: float
    full_share: float
    contrast: float


@dataclass(frozen=True)
class Row:
    """One paint of one icon on one canvas (a row of JSON schema ``alpha-audit.check/3``)."""

    icon: str
    paint: str  # "currentColor" or the element's own "#rrggbb"
    kinds: tuple[str, ...]  # "fill", "stroke"
    source: str  # the colour drawn: the manifest's for currentColor
    opacity: float
    canvas: str
    background: str
    alpha: float
    pipeline: Pipeline
    output: str
    contrast_ref: float  # what ships: the 8-bit colours on the 8-bit canvas
    contrast: float
    gain: float
    drift: float
    hue_shift: float | None  # None where the hue is powerless (achromatic)
    sizes: Mapping[int, SizeFigures] = field(default_factory=dict)
    passes_ref: bool = False
    passes: bool = False
    loss: bool = False
    contrast_ref_float: float = math.nan  # the float colours' (the paper's maths)
    contrast_float: float = math.nan

    @property
    def fixed(self) -> bool:
        """Whether the paint is hard-coded in the SVG (it will not follow the theme)."""
        return self.paint != CURRENT_COLOR

    @property
    def newly_passes(self) -> bool:
        """Below the threshold at alpha = 1, at or above it at the icon's alpha."""
        return self.passes and not self.passes_ref

    @property
    def newly_fails(self) -> bool:
        """At or above the threshold at alpha = 1, below it at the icon's alpha."""
        return self.passes_ref and not self.passes


@dataclass(frozen=True)
class RowColumns:
    """The rows of :meth:`AuditResult.rows` as columns: one list per :class:`Row` field, in
    row order, and per raster size one list per size figure.

    For writers of every row (the JSON report): no object per row until they make one.
    """

    icon: list[str]
    paint: list[str]
    kinds: list[tuple[str, ...]]
    source: list[str]
    opacity: list[float]
    canvas: list[str]
    background: list[str]
    alpha: list[float]
    pipeline: Pipeline
    output: list[str]
    contrast_ref: list[float]
    contrast: list[float]
    gain: list[float]
    drift: list[float]
    hue_shift: list[float | None]
    passes_ref: list[bool]
    passes: list[bool]
    newly_passes: list[bool]
    newly_fails: list[bool]
    loss: list[bool]
    contrast_ref_float: list[float]
    contrast_float: list[float]
    sizes: tuple[int, ...]
    q50: list[list[float]]  # [size][row]
    full_share: list[list[float]]
    size_contrast: list[list[float]]

    def __len__(self) -> int:
        return len(self.icon)


@dataclass(frozen=True)
class PaintEntry:
    """What one row index draws: a paint group of an icon (the same on every canvas).

    ``element`` and ``line`` name the first element drawing a fixed paint
    (for the ``fixed-colour`` note); ``None`` for ``currentColor``.  ``where``
    are the places that set this paint where the rows know them better than
    the manifest does (a page's CSS declarations, its story file), most
    specific first; empty: the manifest's lines.
    """

    icon: Icon
    paint: str
    kinds: tuple[str, ...]
    source: str
    opacity: float
    element: str | None = None
    line: int | None = None
    where: tuple[Location, ...] = ()

    @property
    def fixed(self) -> bool:
        """Whether the paint is hard-coded in the SVG."""
        return self.paint != CURRENT_COLOR

    @property
    def role(self) -> str:
        """What this paint's colour is called: the palette name, else the colour itself."""
        if self.fixed:
            return self.source
        return self.icon.color_name or self.icon.color


@dataclass(frozen=True)
class Unaudited:
    """Something an icon's SVG draws that the audit cannot judge (gradient, text ...)."""

    icon: str
    element: str
    line: int | None
    reason: str


@dataclass(frozen=True)
class Collision:
    """Distinct paints that give the same 8-bit output on one canvas.

    ``delta_e_ref`` is the widest CIEDE2000 between two of them as they ship at
    alpha 1 on that canvas (:func:`widest_delta_e`): 0 when they already share
    the output there, below the policy's near-duplicate distance when they
    already look the same (:func:`~alpha_audit.policy.collision_rules`).
    """

    canvas: str
    output: str
    sources: tuple[str, ...]
    icons: tuple[str, ...]
    delta_e_ref: float = math.inf

    @property
    def new(self) -> bool:
        """Whether the paints told apart at alpha 1 (any two of them had distinct outputs)."""
        return self.delta_e_ref > 0.0


@dataclass(frozen=True)
class Separation:
    """The closest pair of distinct paints on one canvas (CIEDE2000).

    ``delta_e`` is that pair at its alpha, ``delta_e_ref`` the same pair at
    alpha 1; ``set_delta_e_ref`` the closest pair at alpha 1 (which need not
    be the same pair).
    """

    canvas: str
    delta_e: float
    delta_e_ref: float
    icons: tuple[str, str]
    sources: tuple[str, str]
    # Pairs whose CIEDE2000 is smaller than at alpha = 1; None above DECREASES_BUDGET.
    decreases: int | None
    pairs: int
    set_delta_e_ref: float = math.nan


@dataclass(frozen=True)
class CanvasSummary:
    """Per-canvas figures for the summary table, from the rows of that canvas."""

    canvas: str
    background: str
    mode: str
    rows: int
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
    max_drift: float | None


@dataclass(frozen=True)
class Summary:
    """Whole-audit figures (the JSON ``summary``), from the rows."""

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
    max_drift: float | None


def _hex(packed: int) -> str:
    return f"#{packed:06x}"


# Pairs measured exactly for the widest CIEDE2000 of one collision group: beyond
# 1,448 distinct colours in one 8-bit output (never seen in a real set; every colour
# clipping to white at an absurd alpha) the widest is estimated (widest_delta_e).
WIDEST_PAIRS = 1 << 20


def widest_delta_e(lab: NDArray[np.float64]) -> float:
    """The largest CIEDE2000 between two of the CIELAB colours ``lab`` ``(n, 3)``.

    :func:`widest_delta_e_many` of one group.

    >>> from alpha_audit.color import hex_to_linear, linear_to_lab
    >>> lab = linear_to_lab(np.array([hex_to_linear(c) for c in ("#00a4ff", "#01a4ff", "#000")]))
    >>> round(widest_delta_e(lab), 3), round(widest_delta_e(lab[:2]), 4)  # #01a4ff to black
    (57.125, 0.0169)
    """
    return float(widest_delta_e_many([lab])[0])


def widest_delta_e_many(labs: Sequence[NDArray[np.float64]]) -> NDArray[np.float64]:
    """The largest CIEDE2000 between two colours of each group of CIELAB colours ``(n, 3)``.

    Every pair of every group is measured, groups gathered until about
    :data:`~alpha_audit.color.nearest.PAIR_CHUNK` pairs (one CIEDE2000 call for the
    many small groups of an audit, bounded memory for big ones); a group of more
    than :data:`WIDEST_PAIRS` pairs gets the double-sweep estimate (the farthest
    colour from the first, then the farthest from that), a lower bound.  0 for a
    group of fewer than two colours.
    """
    out = np.zeros(len(labs))
    batch: list[int] = []
    pairs = 0

    def measure() -> None:
        every = np.concatenate([labs[g] for g in batch]).reshape(-1, 3)
        sizes = [len(labs[g]) for g in batch]
        starts = np.cumsum([0, *sizes[:-1]])
        parts = [np.triu_indices(n, 1) for n in sizes]
        first = np.concatenate([i + s for (i, _), s in zip(parts, starts, strict=True)])
        second = np.concatenate([k + s for (_, k), s in zip(parts, starts, strict=True)])
        owner = np.repeat(batch, [i.size for i, _ in parts])
        for lo in range(0, first.size, PAIR_CHUNK):
            at = slice(lo, lo + PAIR_CHUNK)
            np.maximum.at(out, owner[at], delta_e_2000_lab(every[first[at]], every[second[at]]))

    for g, lab in enumerate(labs):
        n = len(lab)
        if n * (n - 1) // 2 > WIDEST_PAIRS:
            far = int(np.argmax(delta_e_2000_lab(lab[0], lab)))
            out[g] = float(np.max(delta_e_2000_lab(lab[far], lab)))
        elif n > 1:
            batch.append(g)
            pairs += n * (n - 1) // 2
            if pairs >= PAIR_CHUNK:
                measure()
                batch, pairs = [], 0
    if batch:
        measure()
    return out


def find_collisions(
    output_codes: NDArray[np.uint8],
    source_keys: NDArray[np.int64],
) -> list[tuple[int, int, NDArray[np.intp]]]:
    """Groups of rows whose distinct sources share one 8-bit output, per canvas.

    ``output_codes`` is ``(p, m, 3)``, ``source_keys`` identifies each row's
    paint ``(p,)``.  Returns ``(canvas index, packed output, row indices)``.
    """
    n, m = output_codes.shape[:2]
    if n == 0 or m == 0:
        return []
    packed = pack_8bit(output_codes)  # (n, m)
    # One sort of every (canvas, output, source) triple: O(nm log nm), no loop
    # over canvases or output groups; only real collisions reach Python.
    canvas = np.repeat(np.arange(m), n)
    row = np.tile(np.arange(n), m)
    out = packed.T.reshape(-1)
    keys = np.asarray(source_keys).reshape(-1)[row]
    order = np.lexsort((row, keys, out, canvas))
    c, o, s = canvas[order], out[order], keys[order]
    new_group = np.r_[True, (c[1:] != c[:-1]) | (o[1:] != o[:-1])]
    starts = np.flatnonzero(new_group)
    ends = np.r_[starts[1:], order.size]
    # Sources are sorted within a group: distinct ones exist iff first != last.
    colliding = s[starts] != s[ends - 1]
    members = row[order]
    return [
        (int(c[a]), int(o[a]), np.sort(members[a:b]))
        for a, b in zip(starts[colliding].tolist(), ends[colliding].tolist(), strict=True)
    ]


@dataclass(frozen=True)
class AuditResult:
    """Every number of one theme x icon-set audit; see :func:`audit`.

    ``iconset`` holds the icons audited (those that could not be rendered are
    in ``problems``).  Arrays are per row ``(p, ...)``; ``entries[r]`` says
    what row ``r`` draws.  What ships is what is judged: contrast, drift, size
    contrast and separation are of the 8-bit colours a screen shows (the float
    contrast of the paper's maths is kept beside it, ``contrast_float``).
    """

    theme: Theme
    iconset: IconSet
    pipeline: Pipeline
    threshold: float
    entries: tuple[PaintEntry, ...]
    sizes: tuple[int, ...]
    sources: NDArray[np.float64]  # (p, 3) linear
    opacity: NDArray[np.float64]  # (p,)
    alpha: NDArray[np.float64]  # (p,)
    output: NDArray[np.float64]  # (p, m, 3) linear, displayed (float, before 8 bits)
    reference: NDArray[np.float64]  # (p, m, 3) displayed at a = 1 (float)
    contrast_ref: NDArray[np.float64]  # (p, m) of what ships: 8-bit colours on the 8-bit canvas
    contrast: NDArray[np.float64]  # (p, m) likewise
    contrast_ref_float: NDArray[np.float64]  # (p, m) of the float colours (the paper's maths)
    contrast_float: NDArray[np.float64]  # (p, m)
    drift: NDArray[np.float64]  # (p, m)
    hue_shift: NDArray[np.float64]  # (p, m), NaN where achromatic
    q50: NDArray[np.float64]  # (p, k)
    full_share: NDArray[np.float64]  # (p, k)
    size_contrast: NDArray[np.float64]  # (p, m, k)
    collisions: tuple[Collision, ...] = ()
    problems: tuple[IconProblem, ...] = ()
    unaudited: tuple[Unaudited, ...] = ()
    tolerance: float = CONTRAST_TOLERANCE
    observed: tuple[MeasuredPaint, ...] = ()

    @cached_property
    def gain(self) -> NDArray[np.float64]:
        """``contrast - contrast_ref``, ``(p, m)``."""
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

    @cached_property
    def output_codes(self) -> NDArray[np.uint8]:
        """8-bit sRGB codes of the displayed colours, ``(p, m, 3)``."""
        return to_8bit(self.output)

    @cached_property
    def shown(self) -> NDArray[np.float64]:
        """The 8-bit colours a screen shows, decoded again, ``(p, m, 3)``."""
        return shipped(self.output)

    @cached_property
    def separations(self) -> tuple[Separation, ...]:
        """Closest pair of distinct paints per canvas, computed on first use only."""
        return tuple(_separations(self))

    def columns(self) -> RowColumns:
        """Every row's figures, column by column, in :meth:`rows` order."""
        m, p = len(self.theme.canvases), len(self.entries)

        def by_row(a: NDArray[Any]) -> list[Any]:  # (p, m) -> canvas-major, as rows()
            return np.asarray(a).T.reshape(-1).tolist()

        def per_entry(values: list[Any]) -> list[Any]:
            return values * m

        def per_canvas(values: list[Any]) -> list[Any]:
            return [v for v in values for _ in range(p)]

        entries = self.entries
        hue = by_row(self.hue_shift)
        return RowColumns(
            icon=per_entry([e.icon.name for e in entries]),
            paint=per_entry([e.paint for e in entries]),
            kinds=per_entry([e.kinds for e in entries]),
            source=per_entry([e.source for e in entries]),
            opacity=per_entry([e.opacity for e in entries]),
            canvas=per_canvas([c.name for c in self.theme.canvases]),
            background=per_canvas([c.color for c in self.theme.canvases]),
            alpha=per_entry(self.alpha.tolist()),
            pipeline=self.pipeline,
            output=[_hex(c) for c in by_row(pack_8bit(self.output_codes))],
            contrast_ref=by_row(self.contrast_ref),
            contrast=by_row(self.contrast),
            gain=by_row(self.gain),
            drift=by_row(self.drift),
            hue_shift=[None if math.isnan(h) else h for h in hue],
            passes_ref=by_row(self.passes_ref),
            passes=by_row(self.passes),
            newly_passes=by_row(self.newly_passes),
            newly_fails=by_row(self.newly_fails),
            loss=by_row(self.loss),
            contrast_ref_float=by_row(self.contrast_ref_float),
            contrast_float=by_row(self.contrast_float),
            sizes=tuple(self.sizes),
            q50=[per_entry(self.q50[:, k].tolist()) for k in range(len(self.sizes))],
            full_share=[per_entry(self.full_share[:, k].tolist()) for k in range(len(self.sizes))],
            size_contrast=[by_row(self.size_contrast[:, :, k]) for k in range(len(self.sizes))],
        )

    def rows(self) -> Iterator[Row]:
        """Rows in stable order: canvas order, then icon order, then paint order."""
        c = self.columns()
        for n in range(len(c)):
            yield Row(
                icon=c.icon[n],
                paint=c.paint[n],
                kinds=c.kinds[n],
                source=c.source[n],
                opacity=c.opacity[n],
                canvas=c.canvas[n],
                background=c.background[n],
                alpha=c.alpha[n],
                pipeline=c.pipeline,
                output=c.output[n],
                contrast_ref=c.contrast_ref[n],
                contrast=c.contrast[n],
                gain=c.gain[n],
                drift=c.drift[n],
                hue_shift=c.hue_shift[n],
                sizes={
                    s: SizeFigures(c.q50[k][n], c.full_share[k][n], c.size_contrast[k][n])
                    for k, s in enumerate(c.sizes)
                },
                passes_ref=c.passes_ref[n],
                passes=c.passes[n],
                loss=c.loss[n],
                contrast_ref_float=c.contrast_ref_float[n],
                contrast_float=c.contrast_float[n],
            )

    @cached_property
    def summary(self) -> Summary:
        """Whole-audit summary figures, from the rows."""
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
            max_drift=float(self.drift.max()) if total else None,
        )

    def canvas_summaries(self) -> list[CanvasSummary]:
        """One :class:`CanvasSummary` per canvas, in theme order."""
        out = []
        by_canvas = {s.canvas: s for s in self.separations}
        collisions: dict[str, int] = {}
        for c in self.collisions:
            collisions[c.canvas] = collisions.get(c.canvas, 0) + 1
        for j, canvas in enumerate(self.theme.canvases):
            g = self.gain[:, j]
            losses = self.loss[:, j]
            worst = int(np.argmin(g)) if losses.any() else None
            out.append(
                CanvasSummary(
                    canvas=canvas.name,
                    background=canvas.color,
                    mode=str(canvas.mode),
                    rows=int(g.size),
                    mean_gain=float(g.mean()) if g.size else 0.0,
                    passing_ref=int(self.passes_ref[:, j].sum()),
                    passing=int(self.passes[:, j].sum()),
                    newly_pass=int(self.newly_passes[:, j].sum()),
                    newly_fail=int(self.newly_fails[:, j].sum()),
                    losses=int(losses.sum()),
                    max_loss=float(-g[worst]) if worst is not None else 0.0,
                    worst_icon=self.entries[worst].icon.name if worst is not None else None,
                    collisions=collisions.get(canvas.name, 0),
                    separation=by_canvas.get(canvas.name),
                    max_drift=float(self.drift[:, j].max()) if g.size else None,
                )
            )
        return out

    @cached_property
    def paint_keys(self) -> NDArray[np.intp]:
        """Which rows draw the same paint (source at full precision and opacity), ``(p,)``."""
        if not self.entries:
            return np.zeros(0, dtype=np.intp)
        both = np.concatenate([self.sources, self.opacity[:, np.newaxis]], axis=1)
        return np.unique(both, axis=0, return_inverse=True)[1].reshape(-1)


def _entries(
    iconset: IconSet, paints: PaintSet | None
) -> tuple[list[PaintEntry], list[NDArray[np.float64]], list[list[float]], list[list[float]]]:
    """Every paint row of the icons ``paints`` measured (each icon's colour when None)."""
    sizes = iconset.sizes
    entries: list[PaintEntry] = []
    linear: list[NDArray[np.float64]] = []  # the exact source (a token's oklch is not its hex)
    q50_rows: list[list[float]] = []
    share_rows: list[list[float]] = []
    for icon in iconset.icons:
        if paints is None:
            # No SVG read: the manifest colour, drawn by currentColor at full opacity.
            entries.append(PaintEntry(icon, CURRENT_COLOR, ("fill",), icon.color, 1.0))
            linear.append(np.array(icon.linear))
            q50_rows.append([math.nan] * len(sizes))
            share_rows.append([math.nan] * len(sizes))
            continue
        measured = paints.icons.get(icon.name)
        if measured is None:
            continue
        for cov in measured.coverage:
            g = cov.group
            kinds = tuple(sorted({p.kind for p in g.paints}))
            own = g.color == CURRENT_COLOR
            first = g.paints[0] if g.paints and not own else None
            entries.append(
                PaintEntry(
                    icon,
                    g.color,
                    kinds,
                    icon.color if own else g.color,
                    g.opacity,
                    None if first is None else first.element,
                    None if first is None else first.line,
                )
            )
            linear.append(np.array(icon.linear) if own else hex_to_linear(g.color))
            q50_rows.append([cov.sizes[s].q50 if s in cov.sizes else math.nan for s in sizes])
            share_rows.append(
                [cov.sizes[s].full_share if s in cov.sizes else math.nan for s in sizes]
            )
    return entries, linear, q50_rows, share_rows


def audit(
    theme: Theme,
    iconset: IconSet,
    paints: PaintSet | None = None,
    *,
    alpha: float | None = None,
    threshold: float | None = None,
    pipeline: Pipeline = "linear",
    max_combinations: int = MAX_COMBINATIONS,
) -> AuditResult:
    """Composite every paint of every icon on every canvas of ``theme`` under ``pipeline``.

    ``paints`` are the icons' own paints, read and rasterised
    (:func:`~alpha_audit.load.paint_masks.measure_paints`); ``currentColor``
    paints take the icon's manifest colour, fixed colours are audited as
    themselves, icons in ``paints.problems`` are left out.  Without ``paints``
    every icon is its manifest colour as one ``currentColor`` paint at opacity 1
    (no size figures).  ``alpha`` overrides every icon's coefficient,
    ``threshold`` the theme's.  Under ``css`` an alpha outside [0, 1] raises;
    more than ``max_combinations`` paint rows x canvases too (:func:`check_combinations`).

    >>> from alpha_audit.model import Canvas, Icon, IconSet, Theme
    >>> theme = Theme("t", (Canvas("paper", "#ffffff"),))
    >>> icons = IconSet("s", (Icon("alert", "alert.svg", "#ee7733", 1.1),))
    >>> next(audit(theme, icons).rows()).output
    '#ec5a00'
    """
    check_pipeline(iconset, pipeline, alpha)
    theme = theme.flattened(pipeline)  # translucent layers composited as the pipeline draws
    if alpha is not None:
        iconset = iconset.with_alpha(alpha)
    problems = () if paints is None else paints.problems
    if problems:
        broken = {p.icon for p in problems}
        iconset = iconset.without(broken)
    threshold = theme.threshold if threshold is None else float(threshold)
    sizes = tuple(iconset.sizes)
    p, m, k = 0, len(theme.canvases), len(sizes)
    if paints is None:
        p = len(iconset.icons)
    else:
        p = sum(len(paints.icons[i.name].coverage) for i in iconset.icons if i.name in paints.icons)
    check_combinations(p, m, k, iconset.path, max_combinations)
    entries, linear, q50_rows, share_rows = _entries(iconset, paints)
    unaudited: tuple[Unaudited, ...] = ()
    if paints is not None:
        unaudited = tuple(
            Unaudited(i.name, u.element, u.line, u.reason)
            for i in iconset.icons
            if i.name in paints.icons
            for u in paints.icons[i.name].paints.unaudited
        )
    return _compose(
        theme,
        iconset,
        tuple(entries),
        np.array(linear, dtype=np.float64).reshape(p, 3),
        np.array([e.opacity for e in entries], dtype=np.float64).reshape(p),
        np.array([e.icon.alpha for e in entries], dtype=np.float64).reshape(p),
        np.array(q50_rows, dtype=np.float64).reshape(p, k),
        np.array(share_rows, dtype=np.float64).reshape(p, k),
        pipeline=pipeline,
        threshold=threshold,
        problems=tuple(problems),
        unaudited=unaudited,
    )


def _compose(
    theme: Theme,
    iconset: IconSet,
    entries: tuple[PaintEntry, ...],
    sources: NDArray[np.float64],
    opacity: NDArray[np.float64],
    alphas: NDArray[np.float64],
    q50: NDArray[np.float64],
    full: NDArray[np.float64],
    *,
    pipeline: Pipeline,
    threshold: float,
    problems: tuple[IconProblem, ...],
    unaudited: tuple[Unaudited, ...],
) -> AuditResult:
    """Every figure of the rows ``entries`` draw (:func:`audit` without the reading)."""
    p, m, k = len(entries), len(theme.canvases), q50.shape[1]
    bg = theme.backgrounds[np.newaxis, :, :]  # (1, m, 3)
    s3 = sources[:, np.newaxis, :]
    output = composite_paint(s3, bg, alphas[:, None], opacity[:, None], pipeline)
    reference = composite_paint(s3, bg, np.ones((p, 1)), opacity[:, None], pipeline)
    shown, shown_ref = shipped(output), shipped(reference)  # for drift and hue shift
    # Size contrast: the paint at opacity o * q50, sizes on the last axis.
    q = np.nan_to_num(q50, nan=0.0)[:, np.newaxis, :] * opacity[:, None, None]  # (p, 1, k)
    at_size = composite_paint(
        s3[:, :, np.newaxis, :], bg[:, :, np.newaxis, :], alphas[:, None, None], q, pipeline
    )  # (p, m, k, 3)
    size_contrast = judged_contrast(at_size, bg[:, :, np.newaxis, :]).reshape(p, m, k)
    size_contrast = np.where(np.isnan(q50)[:, np.newaxis, :], np.nan, size_contrast)
    result = AuditResult(
        theme=theme,
        iconset=iconset,
        pipeline=pipeline,
        threshold=threshold,
        entries=entries,
        sizes=tuple(iconset.sizes),
        sources=sources,
        opacity=opacity,
        alpha=alphas,
        output=output,
        reference=reference,
        contrast_ref=judged_contrast(reference, bg),
        contrast=judged_contrast(output, bg),
        contrast_ref_float=contrast_ratio(reference, bg),
        contrast_float=contrast_ratio(output, bg),
        drift=delta_e_2000(shown_ref, shown).reshape(p, m),
        hue_shift=hue_shift(shown_ref, shown).reshape(p, m),
        q50=q50,
        full_share=full,
        size_contrast=size_contrast,
        problems=problems,
        unaudited=unaudited,
    )
    object.__setattr__(result, "collisions", _collisions(result))
    return result


def observed_audit(
    theme: Theme,
    iconset: IconSet,
    entries: Sequence[PaintEntry],
    alphas: Sequence[float],
    shown: NDArray[np.float64],
    observed: Sequence[MeasuredPaint],
    *,
    pipeline: Pipeline,
    threshold: float,
    unaudited: Sequence[Unaudited] = (),
) -> AuditResult:
    """Paint rows a browser drew: ``entries`` on ``theme``'s canvases, as measured.

    ``shown`` ``(p, m, 3)`` are the colours the screen showed (linear, from
    8-bit pixels), ``observed[r]`` the measured paint row ``r`` carries.  The
    row's paint (``entries``' sources and opacities, ``alphas``) is the model
    of what drew it; its output is what was measured, judged by
    :func:`~alpha_audit.color.judged_contrast` as every row is, and its
    reference (alpha 1) the model's own where ``alphas`` is not 1.
    """
    p, m = len(entries), len(theme.canvases)
    sources = np.array(
        [e.icon.linear if not e.fixed else hex_to_linear(e.source) for e in entries],
        dtype=np.float64,
    ).reshape(p, 3)
    opacity = np.array([e.opacity for e in entries], dtype=np.float64).reshape(p)
    alpha = np.asarray(alphas, dtype=np.float64).reshape(p)
    bg = theme.backgrounds[np.newaxis, :, :]
    output = np.asarray(shown, dtype=np.float64).reshape(p, m, 3)
    model_ref = composite_paint(
        sources[:, None, :], bg, np.ones((p, 1)), opacity[:, None], pipeline
    )
    reference = np.where((alpha == 1.0)[:, None, None], output, model_ref)
    shown_out, shown_ref = shipped(output), shipped(reference)
    return AuditResult(
        theme=theme,
        iconset=iconset,
        pipeline=pipeline,
        threshold=threshold,
        entries=tuple(entries),
        sizes=(),
        sources=sources,
        opacity=opacity,
        alpha=alpha,
        output=output,
        reference=reference,
        contrast_ref=judged_contrast(reference, bg),
        contrast=judged_contrast(output, bg),
        contrast_ref_float=contrast_ratio(reference, bg),
        contrast_float=contrast_ratio(output, bg),
        drift=delta_e_2000(shown_ref, shown_out).reshape(p, m),
        hue_shift=hue_shift(shown_ref, shown_out).reshape(p, m),
        q50=np.zeros((p, 0)),
        full_share=np.zeros((p, 0)),
        size_contrast=np.zeros((p, m, 0)),
        unaudited=tuple(unaudited),
        observed=tuple(observed),
    )


def with_alphas(result: AuditResult, alphas: Mapping[str, float]) -> AuditResult:
    """The same rows with some icons' coefficients changed (``{icon name: alpha}``).

    Exactly the audit of the same files with those alphas written in the
    manifest: the paints, their opacities and coverage are the icons' own.
    """
    icons = tuple(
        replace(i, alpha=float(alphas[i.name]), alpha_span=None) if i.name in alphas else i
        for i in result.iconset.icons
    )
    iconset = replace(result.iconset, icons=icons)
    check_pipeline(iconset, result.pipeline)
    by_name = {i.name: i for i in icons}
    entries = tuple(replace(e, icon=by_name[e.icon.name]) for e in result.entries)
    return _compose(
        result.theme,
        iconset,
        entries,
        result.sources,
        result.opacity,
        np.array([e.icon.alpha for e in entries], dtype=np.float64).reshape(len(entries)),
        result.q50,
        result.full_share,
        pipeline=result.pipeline,
        threshold=result.threshold,
        problems=result.problems,
        unaudited=result.unaudited,
    )


def _collisions(result: AuditResult) -> tuple[Collision, ...]:
    """Distinct paints sharing an 8-bit output per canvas, with how far apart they were at 1.

    How far: the widest CIEDE2000 between two of the group's paints as they ship
    at alpha 1 on that canvas (one row per paint: its rows all show one colour).
    """
    keys = result.paint_keys
    found = find_collisions(result.output_codes, keys)
    if not found:
        return ()
    # A row of each paint of each group, on its canvas: every group's colours at alpha 1
    # in one CIELAB conversion (colour-science costs about 0.5 ms a call, whatever its size).
    rows_of = [group[np.unique(keys[group], return_index=True)[1]] for _, _, group in found]
    sizes = [r.size for r in rows_of]
    canvas = np.repeat([j for j, _, _ in found], sizes)
    lab = linear_to_lab(shipped(result.reference[np.concatenate(rows_of), canvas]))
    widest = widest_delta_e_many(np.split(lab, np.cumsum(sizes)[:-1]))
    out = []
    for (j, packed, group), delta_e_ref in zip(found, widest.tolist(), strict=True):
        rows = [result.entries[r] for r in group]
        out.append(
            Collision(
                canvas=result.theme.canvases[j].name,
                output=_hex(packed),
                sources=tuple(sorted({_paint_label(e) for e in rows})),
                icons=tuple(sorted({e.icon.name for e in rows})),
                delta_e_ref=delta_e_ref,
            )
        )
    return tuple(out)


def _paint_label(entry: PaintEntry) -> str:
    """A paint as reports name it: its colour, with its opacity when translucent."""
    return entry.source if entry.opacity == 1.0 else f"{entry.source}@{entry.opacity:g}"


def _separations(result: AuditResult) -> list[Separation]:
    """Closest pair of distinct paints per canvas, at alpha and at 1, exactly.

    Rows drawing the same paint at the same alpha look the same on every
    canvas: one represents them.  Rows of one paint are never paired.
    """
    entries = result.entries
    styles: dict[tuple[int, float], int] = {}
    for r, (key, a) in enumerate(
        zip(result.paint_keys.tolist(), result.alpha.tolist(), strict=True)
    ):
        styles.setdefault((key, a), r)
    reps = np.array(sorted(styles.values()), dtype=np.intp)
    labels = result.paint_keys[reps]
    k, m = reps.size, len(result.theme.canvases)
    group_sizes = np.bincount(labels) if k else np.zeros(0, dtype=np.intp)
    pairs = k * (k - 1) // 2 - int(np.sum(group_sizes * (group_sizes - 1) // 2))
    if pairs == 0:
        return []
    lab_ref = linear_to_lab(shipped(result.reference[reps]))  # (k, m, 3), as screens show them
    lab_out = linear_to_lab(result.shown[reps])  # (k, m, 3)
    decreases: list[int | None] = [None] * m
    closest: list[ClosestPair | None] = [None] * m
    if pairs * m <= DECREASES_BUDGET:
        # Few pairs: every pair on every canvas at once, in triu order (argmin
        # ties go to the first pair, as in the pruned search).
        counts = np.zeros(m, dtype=np.int64)
        best = np.full(m, np.inf)
        best_pair = np.zeros((m, 2), dtype=np.intp)
        for first, second in iter_pairs(k, labels, chunk=max(1, PAIR_CHUNK // max(1, m))):
            de_ref = delta_e_2000_lab(lab_ref[first], lab_ref[second]).reshape(first.size, m)
            de = delta_e_2000_lab(lab_out[first], lab_out[second]).reshape(first.size, m)
            counts += np.sum(de < de_ref - DELTA_E_TOLERANCE, axis=0)
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
    # At alpha 1 an opaque paint is its own colour on every canvas: one search serves all.
    opaque = bool(np.all(result.opacity[reps] == 1.0))
    set_ref: list[float] = []
    for j in range(m):
        if opaque and j > 0:
            set_ref.append(set_ref[0])
            continue
        at_one = closest_pair_delta_e_2000(lab_ref[:, j], labels)
        set_ref.append(math.nan if at_one is None else at_one.distance)
    out = []
    for j, canvas in enumerate(result.theme.canvases):
        pair = closest[j]
        assert pair is not None  # pairs > 0
        a, b = int(reps[pair.first]), int(reps[pair.second])
        de_ref = delta_e_2000_lab(lab_ref[pair.first, j], lab_ref[pair.second, j])
        out.append(
            Separation(
                canvas=canvas.name,
                delta_e=pair.distance,
                delta_e_ref=float(de_ref),
                icons=(entries[a].icon.name, entries[b].icon.name),
                sources=(_paint_label(entries[a]), _paint_label(entries[b])),
                decreases=decreases[j],
                pairs=pairs,
                set_delta_e_ref=set_ref[j],
            )
        )
    return out
