"""The largest safe coefficient, exactly, over the audit's paint rows.

For a gate :class:`~alpha_audit.policy.Policy` ``P`` and an audit's rows the
largest safe alpha of a set of icons is

    a* = sup { a <= a_max : every a' in [1, a] satisfies P }

when those icons share the coefficient ``a'`` and every other icon keeps its
own; only objections involving a moved icon count (the others do not depend
on the coefficient being chosen).  The rows are the gate's: each paint of each
icon at its opacity under the audit's pipeline, so every rule means what
:mod:`alpha_audit.findings` means by it.

Exact, from events (:mod:`alpha_audit.suggest.events`):

* the contrast rules and ``thin-strokes`` per row: a paint's displayed
  luminance is ``o Y(clip(...)) + (1 - o) Yb`` (``q50 o`` at a size), so a
  contrast band on it is a luminance band on the clipped composite, piecewise
  linear in ``a``;
* 8-bit collisions: every track's codes are step functions of ``a`` known
  exactly (:func:`~alpha_audit.suggest.events.code_timelines`).

Bracketed on a grid of :data:`GRID_STEP` (plus every clip breakpoint), bisected
to :data:`~alpha_audit.suggest.events.BISECTION_TOLERANCE` and re-checked
(CIEDE2000 and the CVD simulation have no closed form in ``a``): separation,
drift and lock, confusion and cvd-confusion (pruned by the lightness bound of
:mod:`alpha_audit.color.nearest`), cvd-collision.  ``fixed-colour`` and
``not-audited`` do not depend on alpha: when one fails, not even 1 is safe.

The answer is ``a*`` rounded *down* to ``precision`` decimals and re-checked
there by direct compositing.  Under the ``css`` pipeline no coefficient above 1
can be drawn, so the question is alpha 1 itself.  Pure computation.
"""

from __future__ import annotations

import hashlib
import math
from collections.abc import Iterable, Iterator, Sequence
from dataclasses import dataclass, replace
from decimal import ROUND_FLOOR, Decimal
from typing import Any, NamedTuple

import numpy as np
from numpy.typing import NDArray

from alpha_audit.color import (
    DEFICIENCIES,
    Deficiency,
    composite_coverage,
    composite_paint,
    contrast_from_luminance,
    contrast_ratio,
    delta_e_2000,
    delta_e_2000_lab,
    linear_to_lab,
    pack_8bit,
    relative_luminance,
    shipped,
    simulate_cvd,
    to_8bit,
)
from alpha_audit.color.nearest import (
    delta_e_2000_lightness_key,
    iter_pairs,
    lightness_weight_max,
    pairs_below,
)
from alpha_audit.errors import UsageError
from alpha_audit.figures import ConfusionFigures
from alpha_audit.findings import (
    LOCK_TOLERANCE,
    cvd_collision_groups,
    findings_for,
    locked_rows,
)
from alpha_audit.policy import (
    Policy,
    confusion_possible,
    contrast_breaks,
    contrast_floor,
    drift_breaks,
    drift_ceiling,
    size_contrast_floor,
)
from alpha_audit.ranges import ALPHA_MAX, PRECISION
from alpha_audit.results import (
    CanvasLimit,
    ColorSuggestion,
    GroupSuggestion,
    IconSuggestion,
    Limit,
    Progress,
    SafeAlpha,
    SuggestResult,
)
from alpha_audit.rows import AuditResult
from alpha_audit.rules import RULES, Family, Rule
from alpha_audit.suggest.events import (
    clip_breakpoints,
    code_crossings,
    code_timelines,
    first_below,
    first_in_luminance_band,
    luminance_band,
    luminance_band_pieces,
)
from alpha_audit.suggest.scope import SCOPES

__all__ = [
    "GRID_STEP",
    "SafeAlphas",
    "confusion_groups",
    "connected",
    "largest_safe_alpha",
    "suggest",
]

# The bracketing grid for rules without a closed form in alpha; a dip below a
# limit narrower than this can be missed (the answer is re-checked directly).
GRID_STEP = 1e-3
# Item x grid-point evaluations held at once (~8 MB per float64 intermediate).
_CHUNK = 1 << 20
# Code timelines kept between questions (a few KB per paint and canvas).
_TIMELINE_CACHE_BYTES = 64 << 20
# A question moving few paints builds their timelines on every canvas in one batch.
_TIMELINES_AT_ONCE = 1024
ALPHA_LO = 1.0  # the reference coefficient; the safe interval starts here
_RULE_ORDER = {rule: k for k, rule in enumerate(Rule)}

# One paint's code timeline on one canvas: (points, packed codes of its elements).
_Timeline = tuple[NDArray[np.float64], NDArray[np.int64]]


class Found(NamedTuple):
    """A limit found: a rule broken on a canvas (-1: every canvas) by some icons."""

    rule: Rule
    canvas: int
    icons: tuple[int, ...]
    at: float  # the first unsafe alpha
    attained: bool
    roles: tuple[str, ...] = ()  # the two roles of a role rule (confusion, cvd-confusion)


class _TrackIcons:
    """Each track's icon indices, built when asked for (most tracks never are)."""

    def __init__(self, icons: NDArray[np.intp], bounds: NDArray[np.intp]) -> None:
        self._icons, self._bounds = icons, bounds  # track t: icons[bounds[t]:bounds[t + 1]]

    def __getitem__(self, t: int | np.integer[Any]) -> tuple[int, ...]:
        return tuple(self._icons[self._bounds[t] : self._bounds[t + 1]].tolist())

    def __len__(self) -> int:
        return len(self._bounds) - 1


@dataclass(frozen=True)
class _Tracks:
    """Rows grouped by what they show: moving ones by paint, fixed ones by (paint, alpha)."""

    source: NDArray[np.float64]  # (T, 3) linear
    opacity: NDArray[np.float64]  # (T,)
    alpha: NDArray[np.float64]  # (T,) nan when moving
    moving: NDArray[np.bool_]  # (T,)
    label: NDArray[np.intp]  # (T,) equal labels are never a pair (one paint, or one role)
    icons: _TrackIcons  # icon indices per track
    first: NDArray[np.intp]  # (T,) each track's first row: what it shows is that row's
    row_track: NDArray[np.intp]  # (rows,) each row's track, -1 for a row not chosen


def _round_down(value: float, precision: int) -> float:
    """``value`` rounded towards minus infinity to ``precision`` decimals, exactly."""
    step = Decimal(1).scaleb(-precision)
    return float(Decimal(repr(value)).quantize(step, rounding=ROUND_FLOOR))


def _grid(a_lo: float, a_hi: float, breaks: NDArray[np.float64]) -> NDArray[np.float64]:
    steps = max(1, math.ceil((a_hi - a_lo) / GRID_STEP))
    inner = breaks[(breaks > a_lo) & (breaks < a_hi)]
    return np.unique(np.concatenate([np.linspace(a_lo, a_hi, steps + 1), inner]))


def _shared_code_starts(
    lo: NDArray[np.int64], hi: NDArray[np.int64], code: NDArray[np.int64]
) -> NDArray[np.int64]:
    """Sorted elements where a code's set of overlapping segments changes and holds two or more.

    Segments are inclusive element ranges ``[lo, hi]`` with one code each.
    Between consecutive boundaries of one code the set of its segments is
    constant, so any collision verdict can only change at these elements.

    >>> _shared_code_starts(np.array([0, 2, 5]), np.array([4, 6, 5]), np.array([7, 7, 7])).tolist()
    [2, 5]
    """
    pos = np.concatenate([lo, hi + 1])
    delta = np.concatenate([np.ones(lo.size, np.int64), -np.ones(hi.size, np.int64)])
    codes = np.concatenate([code, code])
    order = np.lexsort((pos, codes))
    pos, delta, codes = pos[order], delta[order], codes[order]
    active = np.cumsum(delta)  # codes are contiguous and each returns to 0
    last_at = np.r_[(pos[1:] != pos[:-1]) | (codes[1:] != codes[:-1]), True]
    shared = last_at & (active >= 2)
    return np.unique(pos[shared])


# A search radius above 0, so pairs of paints shipping one colour (CIEDE2000 0) are found.
_SAME_COLOUR = 1e-9
# Moving tracks from which a collision check groups codes by one sort, not one scan each.
_SORT_FROM = 16


def _code_groups(
    moving: NDArray[np.bool_], subset: NDArray[np.intp], codes: NDArray[np.int64]
) -> Iterator[NDArray[np.intp]]:
    """The tracks of ``subset`` sharing a code with a moving one, group by group, each once,
    in order of its first moving track (``moving`` and ``codes`` are per ``subset`` entry).

    >>> [g.tolist() for g in _code_groups(np.array([1, 1, 0, 0], bool), np.arange(4) + 10,
    ...                                   np.array([5, 7, 5, 9]))]
    [[10, 12]]
    """
    if np.count_nonzero(moving) < _SORT_FROM:  # a few moving tracks: a scan for each
        seen: set[int] = set()
        for k in np.flatnonzero(moving).tolist():
            if int(codes[k]) not in seen:
                seen.add(int(codes[k]))
                members = subset[codes == codes[k]]
                if members.size > 1:
                    yield members
        return
    order = np.argsort(codes, kind="stable")
    ordered = codes[order]
    starts = np.flatnonzero(np.r_[True, ordered[1:] != ordered[:-1]])
    ends = np.r_[starts[1:], ordered.size]
    first = np.minimum.reduceat(np.where(moving[order], order, codes.size), starts)
    held = (first < codes.size) & (ends - starts > 1)
    for g in np.flatnonzero(held)[np.argsort(first[held], kind="stable")].tolist():
        yield subset[order[starts[g] : ends[g]]]


# The most an 8-bit screen moves a linear channel, so a luminance: half the widest gap
# between decoded codes (next to white: (1 - decode(254/255)) / 2 = 0.004449), rounded up.
SHIPPED_Y_ERROR = 0.0045
# Candidates judged at once by _first_unsafe_code (each up to ~1,500 elements).
_CANDIDATES = 512


def _first_unsafe_code(
    source: NDArray[np.float64],
    background: NDArray[np.float64],
    coverage: NDArray[np.float64],
    a_lo: NDArray[np.float64],
    a_hi: float,
    y_screen: NDArray[np.float64],
    floor: NDArray[np.float64],
    windows: NDArray[np.float64],
) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
    """For each candidate, the first ``a`` in ``[a_lo, a_hi]`` where what ships is below ``floor``.

    ``(start, attained)``, ``nan`` where none: every code crossing of the
    displayed channels and every gap between two is judged once (the codes are
    constant on a gap), in order.  A gap's start is its left end, not attained.
    ``windows`` ``(K, W, 2)`` are closed intervals outside which what ships
    cannot be below ``floor`` (the float luminance is outside the widened band
    there): only the crossings and gaps meeting one are computed.
    """
    crossings = code_crossings(source, background, coverage[:, None]).reshape(len(source), -1)
    inside = (crossings > a_lo[:, None]) & (crossings < a_hi)
    ends = np.full((len(source), 1), a_hi)  # before the padding (inf) once sorted
    points = np.sort(np.concatenate([np.where(inside, crossings, np.inf), ends], axis=1), axis=1)
    points = np.concatenate([a_lo[:, None], points], axis=1)
    points = np.where(np.isfinite(points), points, np.nan)
    n = points.shape[1]
    elements = np.empty((len(source), 2 * n - 1))
    elements[:, 0::2] = points
    elements[:, 1::2] = 0.5 * (points[:, :-1] + points[:, 1:])
    valid = np.isfinite(elements)  # the rest is padding
    w_lo, w_hi = windows[:, None, :, 0], windows[:, None, :, 1]  # (K, 1, W)
    at_point = (w_lo <= points[:, :, None]) & (points[:, :, None] <= w_hi)
    on_gap = (w_lo < points[:, 1:, None]) & (w_hi > points[:, :-1, None])
    near = np.empty(elements.shape, dtype=bool)
    near[:, 0::2] = at_point.any(axis=2)
    near[:, 1::2] = on_gap.any(axis=2)
    k, e = np.nonzero(valid & near)  # NaN padding compares False: never judged
    shown = composite_coverage(source[k], background[k], elements[k, e], coverage[k])
    y = relative_luminance(shipped(shown))
    unsafe = np.zeros(elements.shape, dtype=bool)
    unsafe[k, e] = contrast_from_luminance(y, y_screen[k]) < floor[k]
    hit = unsafe.any(axis=1)
    k = np.argmax(unsafe, axis=1)
    is_point = k % 2 == 0
    left = points[np.arange(len(source)), k // 2]
    return np.where(hit, left, np.nan), hit & is_point


class _Engine:
    """Everything shared by the questions of one audit: per-row limits, timelines, exemptions."""

    def __init__(self, result: AuditResult, policy: Policy, alpha_max: float) -> None:
        r = result
        self.result, self.policy = r, policy
        self.threshold = r.threshold
        self.pipeline = r.pipeline
        # CSS opacity cannot exceed 1 (CSS Color 4 clamps alpha): the only
        # coefficient above the reference is none, so the question is alpha 1.
        self.a_hi = ALPHA_LO if r.pipeline == "css" else float(alpha_max)
        self.names = tuple(i.name for i in r.iconset.icons)
        index = {name: n for n, name in enumerate(self.names)}
        self.row_icon = np.array([index[e.icon.name] for e in r.entries], dtype=np.intp)
        self.canvases = tuple(c.name for c in r.theme.canvases)
        self.backgrounds = r.theme.backgrounds
        self.y_bg = relative_luminance(self.backgrounds)
        self.y_screen = relative_luminance(shipped(self.backgrounds))  # the canvas as shipped
        self.keys = r.paint_keys
        self.locked = locked_rows(r)
        rules = policy.rules
        # Whether any failing rule objects to a collision (which one depends on how far
        # apart its colours were at alpha 1: Policy.collision_rule).
        self.collides = any(RULES[r].family is Family.COLLISION for r in rules)
        self._near_pairs: dict[int, dict[tuple[int, int], float]] = {}
        self._ref_lab: NDArray[np.float64] | None = None
        # What an SVG draws objects whatever the alpha (an unrenderable icon is in no row).
        static = {r for r in rules if RULES[r].family is Family.SVG}
        self.static: list[tuple[Rule, tuple[int, ...]]] = []
        if static:
            only = Policy(
                rules=frozenset(static), warnings=frozenset(), exemptions=policy.exemptions
            )
            for f in findings_for(r, only):
                if f.exemption is None:
                    self.static.append((f.rule, tuple(index[i] for i in f.icons if i in index)))
        # Palette roles: currentColor paints of named colours, compared as solid colours.
        roles = [e.role for e in r.entries]
        self.role_row = np.array(
            [not e.fixed and e.icon.color_name is not None for e in r.entries], dtype=bool
        ).reshape(-1)
        names, label = np.unique(np.array(roles or [""], dtype=object), return_inverse=True)
        self.role_names = tuple(str(n) for n in names.tolist())
        self.role_label = label.reshape(-1)[: len(roles)]
        # The colours suggest and the fixes name: a palette name, else the colour itself.
        self.colour_of = tuple(i.color_name or i.color for i in r.iconset.icons)
        self.colours = tuple(dict.fromkeys([*r.iconset.palette, *self.colour_of]))
        self._per_row: list[Found] | None = None
        self._fixed_codes: NDArray[np.int32] | None = None
        self._code_index: tuple[NDArray[np.int32], NDArray[np.int32]] | None = None
        self._last_tracks: dict[bool, tuple[bytes, _Tracks]] = {}
        self._answers: dict[tuple[bytes, int, bool], SafeAlpha] = {}
        self._group_ids: dict[bool, tuple[NDArray[np.intp], ...]] = {}
        self._timelines: dict[tuple[bytes, int, float, float], _Timeline] = {}
        self._timeline_bytes = 0

    # -- helpers -----------------------------------------------------------------

    def exempt(self, rule: Rule, canvas: str, icons: tuple[int, ...]) -> bool:
        names = tuple(sorted(self.names[i] for i in icons))
        return self.policy.exempt(rule, canvas, names) is not None

    def icon_names(self, icons: Iterable[int]) -> tuple[str, ...]:
        return tuple(sorted({self.names[i] for i in icons}))

    def role_pair(self, roles: _Tracks, f: int, g: int) -> tuple[str, str]:
        """The names of the roles of role tracks ``f`` and ``g``, sorted."""
        one, two = (self.role_names[int(roles.label[t])] for t in (f, g))
        return (one, two) if one <= two else (two, one)

    def tracks(self, moving_icons: NDArray[np.bool_], roles: bool = False) -> _Tracks:
        """Rows grouped: moving rows by paint, fixed rows by (paint, alpha); moving first.

        With ``roles``, the roles' rows for the role rules, grouped by role as
        well, drawn solid.  A question asks for the same grouping again when it
        re-checks its answer, so the last one of each kind is kept.
        """
        key = moving_icons.tobytes()
        kept = self._last_tracks.get(roles)
        if kept is None or kept[0] != key:
            kept = (key, self._group(moving_icons, roles))
            self._last_tracks[roles] = kept
        return kept[1]

    def _ids(self, roles: bool) -> tuple[NDArray[np.intp], ...]:
        """The chosen rows and, per row, its (role, paint) and (role, paint, alpha) group ids.

        The same for every question (only which rows move changes), so computed once.
        """
        found = self._group_ids.get(roles)
        if found is None:
            r = self.result
            chosen = np.flatnonzero(self.role_row) if roles else np.arange(len(r.entries))
            role = self.role_label[chosen] if roles else np.full(chosen.size, -1)
            columns = np.stack([role, self.keys[chosen]]).astype(np.float64)
            by_paint = np.unique(columns.T, axis=0, return_inverse=True)[1].reshape(-1)
            with_alpha = np.vstack([columns, r.alpha[chosen]]).T
            by_alpha = np.unique(with_alpha, axis=0, return_inverse=True)[1].reshape(-1)
            found = (chosen, by_paint, by_alpha)
            self._group_ids[roles] = found
        return found

    def _group(self, moving_icons: NDArray[np.bool_], roles: bool) -> _Tracks:
        r = self.result
        chosen, by_paint, by_alpha = self._ids(roles)
        moving = moving_icons[self.row_icon[chosen]]
        role = self.role_label[chosen] if roles else np.full(chosen.size, -1)
        alpha = np.where(moving, -math.inf, r.alpha[chosen])
        # One group per moving (role, paint) and per fixed (role, paint, alpha); ``first``
        # is each group's first row in order.
        ids = np.where(moving, by_paint, by_paint.size + by_alpha)
        _, first_at, group = np.unique(ids, return_index=True, return_inverse=True)
        group = group.reshape(-1)
        is_moving = moving[first_at]
        order = np.lexsort((first_at, ~is_moving))  # moving groups first, then by first row
        rank = np.empty_like(order)
        rank[order] = np.arange(order.size)
        track = rank[group]  # each chosen row's track
        first = chosen[first_at[order]]
        row_track = np.full(len(r.entries), -1, dtype=np.intp)
        row_track[chosen] = track
        n_icons = len(self.names)
        pairs = np.unique(track * n_icons + self.row_icon[chosen])  # sorted (track, icon)
        bounds = np.searchsorted(pairs // n_icons, np.arange(order.size + 1))
        return _Tracks(
            source=r.sources[first].reshape(-1, 3),
            opacity=np.ones(first.size) if roles else r.opacity[first],
            alpha=np.where(is_moving[order], math.nan, alpha[first_at[order]]),
            moving=is_moving[order],
            label=(role if roles else self.keys[chosen])[first_at[order]].astype(np.intp),
            icons=_TrackIcons(pairs % n_icons, bounds),
            first=first,
            row_track=row_track,
        )

    def shown(
        self, tracks: _Tracks, t: NDArray[np.intp], a: NDArray[np.float64], j: int
    ) -> NDArray[np.float64]:
        """What tracks ``t`` ship on canvas ``j`` at coefficients ``a`` (moving), (len(t), N, 3)."""
        coef = np.where(tracks.moving[t][:, np.newaxis], a, tracks.alpha[t][:, np.newaxis])
        return self.ship(
            tracks.source[t][:, np.newaxis, :],
            self.backgrounds[j],
            coef,
            tracks.opacity[t][:, np.newaxis],
        )

    def shown_at(
        self, tracks: _Tracks, t: NDArray[np.intp], a: NDArray[np.float64], j: int
    ) -> NDArray[np.float64]:
        """What track ``t[k]`` ships at coefficient ``a[k]`` on canvas ``j``: (K, 3)."""
        coef = np.where(tracks.moving[t], a, tracks.alpha[t])
        return self.ship(tracks.source[t], self.backgrounds[j], coef, tracks.opacity[t])

    def ship(
        self,
        source: NDArray[np.float64],
        background: NDArray[np.float64],
        alpha: NDArray[np.float64] | float,
        opacity: NDArray[np.float64] | float,
    ) -> NDArray[np.float64]:
        """The 8-bit colour a paint ships at ``alpha`` (what the gate judges), as linear light."""
        return shipped(composite_paint(source, background, alpha, opacity, self.pipeline))

    # -- per row: independent of every other icon, computed once ----------------

    def per_row(self) -> list[Found]:
        """First unsafe alpha of every per-row rule, each row moving from 1 to ``a_hi``."""
        if self._per_row is None:
            found: list[Found] = []
            if self.a_hi > ALPHA_LO and len(self.row_icon):
                found += self._contrast()
                rules = self.policy.rules
                if Rule.THIN_STROKES in rules:
                    found += self._thin_strokes()
                if Rule.DRIFT in rules:
                    every = np.ones(len(self.row_icon), dtype=bool)
                    found += self._drift(Rule.DRIFT, self.policy.max_drift, every)
                if Rule.LOCK in rules:
                    found += self._drift(Rule.LOCK, LOCK_TOLERANCE, self.locked)
            self._per_row = found
        return self._per_row

    def _band_starts(
        self, floor: NDArray[np.float64], coverage: NDArray[np.float64]
    ) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
        """Where the contrast of what ships first drops below ``floor``, (p, m[, k]), exactly.

        What ships is the 8-bit colour (:func:`~alpha_audit.color.shipped`), a step
        function of ``a`` that changes only where a displayed channel crosses a code
        threshold (:func:`~alpha_audit.suggest.events.code_crossings`).  Its luminance
        lies within :data:`SHIPPED_Y_ERROR` of the float one, so the float luminance
        entering the band widened by that much is a lower bound on the start, found
        exactly (:func:`first_in_luminance_band` on ``o Y(clip) + (1 - o) Yb``).  From
        there each candidate is judged at every crossing and on every gap between
        crossings, which is every value it takes: the first unsafe element is the answer.
        """
        extra = floor.ndim - 2
        shape_bg = (1, -1, *([1] * extra))
        lo, hi = luminance_band(floor, self.y_screen.reshape(shape_bg))
        lo, hi = lo - SHIPPED_Y_ERROR, hi + SHIPPED_Y_ERROR
        y_bg = self.y_bg.reshape(shape_bg)
        o = coverage
        with np.errstate(divide="ignore", invalid="ignore"):
            lo_c = np.where(o > 0, (lo - (1.0 - o) * y_bg) / o, np.inf)
            hi_c = np.where(o > 0, (hi - (1.0 - o) * y_bg) / o, -np.inf)
        p, m = len(self.row_icon), len(self.canvases)
        shape = (*floor.shape, 3)  # cells index every axis, sizes included
        s = np.broadcast_to(self.result.sources.reshape(p, 1, *([1] * extra), 3), shape)
        b = np.broadcast_to(self.backgrounds.reshape(1, m, *([1] * extra), 3), shape)
        pieces = luminance_band_pieces(s, b, lo_c, hi_c, ALPHA_LO, self.a_hi)
        bound, _ = first_in_luminance_band(s, b, lo_c, hi_c, ALPHA_LO, self.a_hi, pieces=pieces)
        # Where the float luminance is in the widened band at all: at most one interval
        # per linear piece of Y(a); what ships can be unsafe nowhere else.
        windows = np.full((*floor.shape, 4, 2), [np.inf, -np.inf])
        for w, (p_, q_, lower, upper) in enumerate(pieces):
            start_w, end_w = np.maximum(lower, p_), np.minimum(upper, q_)
            meets = (q_ >= p_) & (start_w <= end_w)
            windows[..., w, 0] = np.where(meets, start_w, np.inf)
            windows[..., w, 1] = np.where(meets, end_w, -np.inf)
        start = np.full(floor.shape, np.nan)
        attained = np.zeros(floor.shape, dtype=bool)
        y_screen = np.broadcast_to(self.y_screen.reshape(shape_bg), floor.shape)
        cells = np.argwhere(np.isfinite(bound))
        for chunk in range(0, len(cells), _CANDIDATES):
            at = tuple(cells[chunk : chunk + _CANDIDATES].T)
            first, point = _first_unsafe_code(
                s[at], b[at], np.broadcast_to(o, floor.shape)[at], bound[at], self.a_hi,
                y_screen[at], floor[at], windows[at],
            )  # fmt: skip
            start[at], attained[at] = first, point
        return start, attained

    def _contrast(self) -> list[Found]:
        out: list[Found] = []
        r = self.result
        o = np.broadcast_to(r.opacity[:, np.newaxis], r.contrast_ref.shape)
        for rule in self.policy.contrast_rules:
            floor = contrast_floor(rule, self.policy, r.contrast_ref, self.threshold)
            start, attained = self._band_starts(floor, o)
            out += self._collect(rule, start, attained)
        return out

    def _thin_strokes(self) -> list[Found]:
        r = self.result
        if not r.sizes:
            return []
        limit = self.threshold
        if self.policy.min_size_contrast is not None:
            limit = self.policy.min_size_contrast
        p, m, k = len(self.row_icon), len(self.canvases), len(r.sizes)
        coverage = (np.nan_to_num(r.q50, nan=0.0) * r.opacity[:, np.newaxis])[:, None, :]
        floor = np.full((p, m, k), size_contrast_floor(limit))
        start, attained = self._band_starts(floor, np.broadcast_to(coverage, (p, m, k)))
        start = np.where(np.isnan(r.q50)[:, np.newaxis, :], np.nan, start)  # no ink
        first = np.nanmin(np.where(np.isnan(start), np.inf, start), axis=2)
        hit = np.isfinite(first)
        att = np.any(attained & (start == first[..., np.newaxis]), axis=2)
        return self._collect(Rule.THIN_STROKES, np.where(hit, first, np.nan), att)

    def _drift(self, rule: Rule, limit: float, selected: NDArray[np.bool_]) -> list[Found]:
        r = self.result
        rows = np.flatnonzero(selected)
        m = len(self.canvases)
        start = np.full((len(self.row_icon), m), np.nan)
        if rows.size == 0:
            return []
        breaks = clip_breakpoints(
            r.sources[rows][:, np.newaxis, :], self.backgrounds[np.newaxis]
        ).reshape(-1)
        grid = _grid(ALPHA_LO, self.a_hi, breaks)
        per = max(1, _CHUNK // (grid.size * m))
        bg = self.backgrounds[np.newaxis, :, np.newaxis, :]
        for lo in range(0, rows.size, per):
            sel = rows[lo : lo + per]
            s = r.sources[sel][:, np.newaxis, np.newaxis, :]
            o = r.opacity[sel][:, np.newaxis, np.newaxis]
            ref = self.ship(s, bg, 1.0, o)  # (q, m, 1, 3)

            def minus_drift(
                a: NDArray[np.float64],
                s: NDArray[np.float64] = s,
                o: NDArray[np.float64] = o,
                ref: NDArray[np.float64] = ref,
            ) -> NDArray[np.float64]:
                a = a.reshape(1, 1, -1) if a.ndim == 1 else a.reshape(len(s), m, -1)
                return -delta_e_2000(ref, self.ship(s, bg, a, o))

            # drift_breaks(d, limit) is d > drift_ceiling(limit), i.e. -d < -ceiling.
            _, unsafe = first_below(minus_drift, grid, -drift_ceiling(limit))
            start[sel] = unsafe
        return self._collect(rule, start, np.isfinite(start))

    def _collect(
        self, rule: Rule, start: NDArray[np.float64], attained: NDArray[np.bool_]
    ) -> list[Found]:
        out: list[Found] = []
        for p, j in zip(*np.nonzero(np.isfinite(start)), strict=True):
            icon = (int(self.row_icon[p]),)
            if not self.exempt(rule, self.canvases[j], icon):
                out.append(Found(rule, int(j), icon, float(start[p, j]), bool(attained[p, j])))
        return out

    # -- 8-bit collisions, exactly ----------------------------------------------

    def fixed_codes(self) -> NDArray[np.int32]:
        """Every row's packed 8-bit output on every canvas at its own alpha: (rows, canvases).

        What a track that does not move ships never depends on the question:
        it is the row's own output (:attr:`~alpha_audit.rows.AuditResult.output_codes`).
        """
        if self._fixed_codes is None:
            self._fixed_codes = pack_8bit(self.result.output_codes).astype(np.int32)
        return self._fixed_codes

    def _near(
        self, tracks: _Tracks, moving_codes: NDArray[np.int64], j: int
    ) -> tuple[NDArray[np.intp], NDArray[np.int64]]:
        """The fixed tracks whose code on canvas ``j`` is one of ``moving_codes``, and
        those codes: no other fixed track can share a code with a moving one.

        Found through each canvas's rows sorted by code, so a question costs what its
        own codes match, not the number of rows (rows of one fixed track ship one code).
        """
        if tracks.moving.all():  # a set-wide question: nothing stays
            return np.zeros(0, dtype=np.intp), np.zeros(0, dtype=np.int64)
        if self._code_index is None:
            codes = self.fixed_codes().T  # (canvases, rows)
            order = np.argsort(codes, axis=1, kind="stable").astype(np.int32)
            self._code_index = (np.take_along_axis(codes, order, axis=1), order)
        ordered, order = self._code_index[0][j], self._code_index[1][j]
        want = np.unique(moving_codes)
        lo = np.searchsorted(ordered, want, side="left")
        count = np.searchsorted(ordered, want, side="right") - lo
        at = np.repeat(lo - np.cumsum(count) + count, count) + np.arange(count.sum())
        track = tracks.row_track[order[at]]
        track = track[track >= 0]
        near = np.unique(track[~tracks.moving[track]])
        return near, self.fixed_codes()[tracks.first[near], j].astype(np.int64)

    def near_pairs(self, j: int) -> dict[tuple[int, int], float]:
        """The paints already closer than the near-duplicate distance at alpha 1 on canvas
        ``j`` (CIEDE2000 of what they ship there), by pair of paint keys: found once per
        canvas by the lightness-pruned pair search (:func:`~alpha_audit.color.nearest.pairs_below`),
        so judging a collision is a look-up."""
        found = self._near_pairs.get(j)
        if found is None:
            if self._ref_lab is None:
                _, first = np.unique(self.keys, return_index=True)  # a row of each paint
                self._ref_lab = linear_to_lab(shipped(self.result.reference[first]))
            lab = self._ref_lab[:, j]

            def distance(f: NDArray[np.intp], g: NDArray[np.intp]) -> NDArray[np.float64]:
                return delta_e_2000_lab(lab[f], lab[g])

            # Paints shipping one colour at alpha 1 (0 apart) are found whatever the distance.
            near = max(self.policy.near_duplicate_delta_e, _SAME_COLOUR)
            a, b, d = pairs_below(delta_e_2000_lightness_key(lab), distance, near)
            found = dict(zip(zip(a.tolist(), b.tolist(), strict=True), d.tolist(), strict=True))
            self._near_pairs[j] = found
        return found

    def widest_at_reference(self, j: int, keys: frozenset[int]) -> float:
        """How far apart paints ``keys`` were at alpha 1 on canvas ``j``, as far as the
        collision rules need: the widest CIEDE2000 between two of them as they ship there
        when every two are near duplicates (:meth:`near_pairs`; as the audit's collisions
        have it, :func:`~alpha_audit.rows.widest_delta_e`), else infinity (told apart)."""
        widest = 0.0
        near = self.near_pairs(j)
        at = sorted(keys)
        for k, a in enumerate(at):
            for b in at[k + 1 :]:
                d = near.get((a, b))
                if d is None:
                    return math.inf
                widest = max(widest, d)
        return widest

    def collision_group(
        self, tracks: _Tracks, subset: NDArray[np.intp], codes: NDArray[np.int64], j: int
    ) -> tuple[Rule, tuple[int, ...]] | None:
        """The rule and icons of the first unsafe collision group (holding a moving track).

        ``codes`` are the packed 8-bit outputs of tracks ``subset`` (ascending,
        every moving track and at least every fixed one sharing a code with
        one) on canvas ``j`` at one coefficient; the verdict is
        :mod:`alpha_audit.findings`' (:meth:`~alpha_audit.policy.Policy.collision_rule`
        of the failing rules), group by group.
        """
        for members in _code_groups(tracks.moving[subset], subset, codes):
            keys = frozenset(tracks.label[members].tolist())
            if len(keys) < 2:
                continue
            widest = self.widest_at_reference(j, keys)
            rule = self.policy.collision_rule(widest, self.policy.rules)
            if rule is None:
                continue
            icons = tuple(sorted({i for m in members for i in tracks.icons[m]}))
            if not self.exempt(rule, self.canvases[j], icons):
                return rule, icons
        return None

    def track_segments(
        self,
        tracks: _Tracks,
        moving: NDArray[np.intp],
        canvases: Sequence[int],
        a_lo: float,
        a_hi: float,
    ) -> list[_Timeline]:
        """The moving tracks' own timelines over ``[a_lo, a_hi]`` on each of ``canvases``
        (canvas by canvas, tracks in order): (points, packed element codes) each.

        Cached per (paint, canvas, window): the set-wide, per-colour and per-icon
        questions move the same paints again and again.  The ones not cached are
        computed together (:func:`~alpha_audit.suggest.events.code_timelines`).
        """
        paint = [
            tracks.source[t].tobytes() + np.float64(tracks.opacity[t]).tobytes()
            for t in moving.tolist()
        ]
        keys = [(p, j, a_lo, a_hi) for j in canvases for p in paint]
        found = [self._timelines.get(key) for key in keys]
        missing = [k for k, f in enumerate(found) if f is None]
        if missing:
            at = np.asarray(missing)
            t = moving[at % moving.size]
            j = np.asarray(canvases)[at // moving.size]
            fresh = code_timelines(
                tracks.source[t], self.backgrounds[j], a_lo, a_hi, tracks.opacity[t]
            )
            for k, timeline in zip(missing, fresh, strict=True):
                found[k] = timeline
                size = timeline[0].nbytes + timeline[1].nbytes
                if self._timeline_bytes + size > _TIMELINE_CACHE_BYTES:
                    self._timelines.clear()  # memory stays bounded; recomputing is exact
                    self._timeline_bytes = 0
                self._timelines[keys[k]] = timeline
                self._timeline_bytes += size
        return [f for f in found if f is not None]

    def collision_limits(self, tracks: _Tracks) -> list[Found]:
        """Per canvas, where the first unsafe 8-bit collision starts (exact).

        Each track's code is a step function of alpha: a list of segments (a
        point or an open gap, each one code).  A collision needs two segments
        with one code overlapping, so one sort of all segments by code finds
        every place where two or more share a code; only those places are
        judged, in order, by :meth:`collision_group`.  Cost and memory are linear
        in the number of segments, never tracks x tracks x events.

        The coefficients up to the moving icons' own alpha come first: where they
        already collide there (a failing check's fixes ask exactly that), the
        rest of the range up to ``alpha_max`` is never built.  Both windows share
        their end point, whose codes are those of the gap around it, so the first
        unsafe element is the one a single window finds.
        """
        out: list[Found] = []
        mv = np.flatnonzero(tracks.moving)
        if not self.collides or mv.size == 0 or len(tracks.label) < 2 or self.a_hi <= ALPHA_LO:
            return out
        chosen = tracks.row_track >= 0
        rows = np.flatnonzero(chosen)[tracks.moving[tracks.row_track[chosen]]]
        own_alpha = float(self.result.alpha[rows].max()) if rows.size else self.a_hi
        windows = [(ALPHA_LO, self.a_hi)]
        if ALPHA_LO < own_alpha < self.a_hi:
            windows = [(ALPHA_LO, own_alpha), (own_alpha, self.a_hi)]
        pending = list(range(len(self.canvases)))
        for a_lo, a_hi in windows:
            if mv.size * len(pending) <= _TIMELINES_AT_ONCE:  # one batch for every canvas
                self.track_segments(tracks, mv, pending, a_lo, a_hi)
            left = []
            for j in pending:
                found = self._first_collision(tracks, mv, j, a_lo, a_hi)
                if found is None:
                    left.append(j)
                else:
                    out.append(found)
            pending = left
        return sorted(out, key=lambda f: f.canvas)

    def _first_collision(
        self, tracks: _Tracks, mv: NDArray[np.intp], j: int, a_lo: float, a_hi: float
    ) -> Found | None:
        """The first unsafe collision on canvas ``j`` with ``a`` in ``[a_lo, a_hi]``, if any."""
        own = self.track_segments(tracks, mv, [j], a_lo, a_hi)
        fixed, fixed_codes = self._near(tracks, np.concatenate([c for _, c in own]), j)
        labels = tracks.label[mv]
        if fixed.size == 0 and bool((labels == labels[0]).all()):
            return None  # one paint alone never collides (most per-colour questions, canvases)
        own_points = np.concatenate([p for p, _ in own])  # track by track
        points = np.unique(own_points)  # every event of canvas j
        last = 2 * (points.size - 1)  # global elements 0..last: point, gap, point, ...
        # Each track's elements alternate point, gap, point ...: a point is one global
        # element, a gap the elements strictly between its two points.
        n_points = np.array([p.size for p, _ in own])
        n_codes = 2 * n_points - 1
        g = 2 * np.searchsorted(points, own_points)  # the tracks' points as global elements
        track_start = np.cumsum(n_codes) - n_codes  # each track's first code
        point_start = np.cumsum(n_points) - n_points  # each track's first point
        at = np.repeat(track_start - 2 * point_start, n_points) + 2 * np.arange(g.size)
        lo = np.empty(int(n_codes.sum()), dtype=np.int64)
        hi = np.empty_like(lo)
        lo[at], hi[at] = g, g
        inner = np.ones(g.size, dtype=bool)
        inner[np.cumsum(n_points) - 1] = False  # a track's last point has no gap after it
        lo[at[inner] + 1], hi[at[inner] + 1] = g[inner] + 1, g[1:][inner[:-1]] - 1
        track = np.concatenate([np.repeat(mv, n_codes), fixed])
        lo = np.concatenate([lo, np.zeros(fixed.size, dtype=np.int64)])
        hi = np.concatenate([hi, np.full(fixed.size, last, dtype=np.int64)])
        code = np.concatenate([*(c for _, c in own), fixed_codes])
        candidates = _shared_code_starts(lo, hi, code)
        if candidates.size == 0:
            return None
        # Every track's code at a candidate element: its segment by track then start.
        order = np.lexsort((lo, track))
        sorted_key = track[order] * (last + 2) + lo[order]
        subset = np.concatenate([mv, fixed])  # ascending: moving tracks come first
        everyone = subset * (last + 2)
        for e in candidates.tolist():
            at = order[np.searchsorted(sorted_key, everyone + e, side="right") - 1]
            group = self.collision_group(tracks, subset, code[at], j)
            if group is not None:
                return Found(group[0], j, group[1], float(points[e // 2]), e % 2 == 0)
        return None

    # -- pairs: separation and the role rules, bracketed --------------------------

    def separation_limits(self, tracks: _Tracks, caps: NDArray[np.float64]) -> list[Found]:
        """Per canvas, where CIEDE2000 between two paints first drops below the minimum.

        Canvas by canvas and a chunk of pairs at a time (bounded memory for any
        number of colours).  A pair whose lightness bound (``dE00 >= |dL| /
        S_L,max``) keeps it at or above the minimum at every grid point cannot
        be found below it by the grid search either, so it is skipped.
        """
        out: list[Found] = []
        if Rule.SEPARATION not in self.policy.rules or len(tracks.label) < 2:
            return out
        level = self.policy.min_delta_e
        moving = np.flatnonzero(tracks.moving)
        if moving.size == 0:
            return out
        breaks = clip_breakpoints(
            tracks.source[moving][:, np.newaxis, :], self.backgrounds[np.newaxis]
        ).reshape(-1)
        every = np.arange(len(tracks.label))
        for j in range(len(self.canvases)):
            if caps[j] <= ALPHA_LO:
                continue
            grid = _grid(ALPHA_LO, float(caps[j]), breaks)
            lightness = linear_to_lab(self.shown(tracks, every, grid, j))[..., 0]  # (T, N)
            s_l = lightness_weight_max(lightness)
            chunk = max(1, _CHUNK // grid.size)
            for first, second in iter_pairs(len(tracks.label), tracks.label, chunk=chunk):
                moved = tracks.moving[first] | tracks.moving[second]
                first, second = first[moved], second[moved]
                near = np.min(np.abs(lightness[first] - lightness[second]), axis=1) / s_l
                keep = near < level * (1.0 + 1e-9)
                first, second = first[keep], second[keep]
                if first.size == 0:
                    continue

                def delta_e(
                    a: NDArray[np.float64],
                    f: NDArray[np.intp] = first,
                    g: NDArray[np.intp] = second,
                    j: int = j,
                ) -> NDArray[np.float64]:
                    if a.ndim > 1:  # bisecting: every pair at its own points
                        fa = self.shown_at(tracks, np.repeat(f, a.shape[1]), a.reshape(-1), j)
                        ga = self.shown_at(tracks, np.repeat(g, a.shape[1]), a.reshape(-1), j)
                        return delta_e_2000(fa, ga).reshape(a.shape)
                    return delta_e_2000(self.shown(tracks, f, a, j), self.shown(tracks, g, a, j))

                _, unsafe = first_below(delta_e, grid, level)
                for p in np.flatnonzero(np.isfinite(unsafe)).tolist():
                    icons = tuple(sorted({*tracks.icons[first[p]], *tracks.icons[second[p]]}))
                    if not self.exempt(Rule.SEPARATION, self.canvases[j], icons):
                        out.append(Found(Rule.SEPARATION, j, icons, float(unsafe[p]), True))
        return out

    def confusion_limits(
        self,
        roles: _Tracks,
        caps: NDArray[np.float64],
        deficiency: Deficiency | None,
        shrink: bool,
    ) -> list[Found]:
        """Per canvas, where two roles told apart at alpha 1 first drop below the minimum."""
        rule = Rule.CONFUSION if deficiency is None else Rule.CVD_CONFUSION
        n = len(roles.label)
        if n < 2 or not roles.moving.any():
            return []
        level = self.policy.min_delta_e
        breaks = clip_breakpoints(
            roles.source[:, np.newaxis, :], self.backgrounds[np.newaxis]
        ).reshape(-1)
        full = _grid(ALPHA_LO, float(caps.max()), breaks)

        def view(c: NDArray[np.float64]) -> NDArray[np.float64]:
            return c if deficiency is None else simulate_cvd(c, deficiency)

        every = np.arange(n)
        out: list[Found] = []
        for j in range(len(self.canvases)):
            if caps[j] <= ALPHA_LO:
                continue
            grid = full[full <= caps[j]]
            chunk = max(1, _CHUNK // grid.size)
            # The rule's reference is every role at alpha 1, as the gate has it, not the
            # others at their configured alpha: a pair the others confuse is this one's too.
            solid = self.ship(roles.source, self.backgrounds[j], 1.0, 1.0)
            lab_ref = linear_to_lab(view(solid))
            lightness = linear_to_lab(view(self.shown(roles, every, grid, j)))[..., 0]
            s_l = lightness_weight_max(lightness)
            for first, second in iter_pairs(n, roles.label, chunk=chunk):
                moved = roles.moving[first] | roles.moving[second]
                first, second = first[moved], second[moved]
                keep = confusion_possible(delta_e_2000_lab(lab_ref[first], lab_ref[second]), level)
                first, second = first[keep], second[keep]
                if first.size == 0:
                    continue
                # dE00 >= |dL| / S_L,max: only grid points where the bound cannot rule
                # the pair out are evaluated; elsewhere the distance is >= the level.
                close = np.abs(lightness[first] - lightness[second]) / s_l < level * (1 + 1e-9)
                near = close.any(axis=1)
                first, second, close = first[near], second[near], close[near]
                if first.size == 0:
                    continue

                def delta_e(
                    a: NDArray[np.float64],
                    f: NDArray[np.intp] = first,
                    g: NDArray[np.intp] = second,
                    j: int = j,
                    close: NDArray[np.bool_] = close,
                ) -> NDArray[np.float64]:
                    if a.ndim > 1:  # bisecting: every pair at its own points
                        ff, gg = np.repeat(f, a.shape[1]), np.repeat(g, a.shape[1])
                        fa = view(self.shown_at(roles, ff, a.reshape(-1), j))
                        ga = view(self.shown_at(roles, gg, a.reshape(-1), j))
                        return delta_e_2000(fa, ga).reshape(a.shape)
                    values = np.full(close.shape, np.inf)
                    p, k = np.nonzero(close)
                    values[p, k] = delta_e_2000(
                        view(self.shown_at(roles, f[p], a[k], j)),
                        view(self.shown_at(roles, g[p], a[k], j)),
                    )
                    return values

                _, unsafe = first_below(delta_e, grid, level)
                for p in np.flatnonzero(np.isfinite(unsafe)).tolist():
                    icons = tuple(sorted({*roles.icons[first[p]], *roles.icons[second[p]]}))
                    if not self.exempt(rule, self.canvases[j], icons):
                        pair = self.role_pair(roles, first[p], second[p])
                        out.append(Found(rule, j, icons, float(unsafe[p]), True, pair))
                        if shrink:
                            caps = np.minimum(caps, float(unsafe[p]))
        return out

    def cvd_collision_limits(self, roles: _Tracks, cap: float) -> list[Found]:
        n = len(roles.label)
        if n < 2 or not roles.moving.any():
            return []
        sources = [roles.source[t].tobytes().hex() for t in range(n)]
        breaks = clip_breakpoints(
            roles.source[:, np.newaxis, :], self.backgrounds[np.newaxis]
        ).reshape(-1)
        grid = _grid(ALPHA_LO, cap, breaks)
        every = np.arange(n)
        out: list[Found] = []
        for deficiency in DEFICIENCIES:
            for j in range(len(self.canvases)):
                ref = to_8bit(
                    simulate_cvd(
                        self.shown(roles, every, np.array([ALPHA_LO]), j)[:, 0], deficiency
                    )
                )

                def unsafe(
                    a: float, j: int = j, ref: NDArray[np.uint8] = ref, d: Deficiency = deficiency
                ) -> tuple[int, ...] | None:
                    seen = to_8bit(
                        simulate_cvd(self.shown(roles, every, np.array([a]), j)[:, 0], d)
                    )
                    return self._cvd_group(roles, seen, ref, sources, j)

                codes = to_8bit(simulate_cvd(self.shown(roles, every, grid, j), deficiency))
                packed = pack_8bit(codes)  # (T, N)
                ordered = np.sort(packed, axis=0)
                shared = np.flatnonzero((ordered[1:] == ordered[:-1]).any(axis=0))
                for k in shared.tolist():
                    icons = unsafe(float(grid[k]))
                    if icons is None:
                        continue
                    lo, hi = (float(grid[k - 1]), float(grid[k])) if k > 0 else (ALPHA_LO, ALPHA_LO)
                    while hi - lo > 1e-9:
                        mid = 0.5 * (lo + hi)
                        if unsafe(mid) is None:
                            lo = mid
                        else:
                            hi = mid
                    out.append(Found(Rule.CVD_COLLISION, j, icons, hi, True))
                    break
        return out

    def _cvd_group(
        self,
        roles: _Tracks,
        seen: NDArray[np.uint8],
        ref: NDArray[np.uint8],
        sources: Sequence[str],
        j: int,
    ) -> tuple[int, ...] | None:
        for _, members in cvd_collision_groups(seen, ref, sources):
            if not any(roles.moving[m] for m in members):
                continue
            icons = tuple(sorted({i for m in members for i in roles.icons[m]}))
            if not self.exempt(Rule.CVD_COLLISION, self.canvases[j], icons):
                return icons
        return None

    # -- the direct check of one coefficient -------------------------------------

    def objection_at(self, moving_icons: NDArray[np.bool_], a: float) -> Found | None:
        """An objection at exactly ``a`` involving a moving icon (the re-check of an answer)."""
        for rule, icons in self.static:
            if any(moving_icons[i] for i in icons):
                return Found(rule, -1, icons, a, True)
        r, rules = self.result, self.policy.rules
        rows = np.flatnonzero(moving_icons[self.row_icon])
        bg = self.backgrounds[np.newaxis]
        if rows.size:
            s = r.sources[rows][:, np.newaxis, :]
            o = r.opacity[rows][:, np.newaxis]
            shown = self.ship(s, bg, a, o)
            c_now = contrast_ratio(shown, shipped(bg))
            checks: list[tuple[Rule, NDArray[np.bool_]]] = [
                (
                    rule,
                    contrast_breaks(rule, self.policy, r.contrast_ref[rows], c_now, self.threshold),
                )
                for rule in self.policy.contrast_rules
            ]
            if Rule.DRIFT in rules or Rule.LOCK in rules:
                d = delta_e_2000(shipped(r.reference[rows]), shown)
                if Rule.DRIFT in rules:
                    checks.append((Rule.DRIFT, drift_breaks(d, self.policy.max_drift)))
                if Rule.LOCK in rules:
                    lock = drift_breaks(d, LOCK_TOLERANCE) & self.locked[rows][:, np.newaxis]
                    checks.append((Rule.LOCK, lock))
            if Rule.THIN_STROKES in rules and r.sizes:
                limit = self.policy.min_size_contrast or self.threshold
                q = (np.nan_to_num(r.q50[rows]) * r.opacity[rows][:, np.newaxis])[:, np.newaxis, :]
                at = self.ship(s[:, :, None], bg[..., None, :], a, q)
                sc = contrast_ratio(at, shipped(bg)[..., np.newaxis, :])
                sc = np.where(np.isnan(r.q50[rows])[:, np.newaxis, :], np.nan, sc)
                thin = np.asarray((sc < size_contrast_floor(limit)).any(axis=2))
                checks.append((Rule.THIN_STROKES, thin))
            for rule, broken in checks:
                for k, j in zip(*np.nonzero(broken), strict=True):
                    icon = (int(self.row_icon[rows[k]]),)
                    if not self.exempt(rule, self.canvases[j], icon):
                        return Found(rule, int(j), icon, a, True)
        tracks = self.tracks(moving_icons)
        if self.collides and tracks.moving.any():
            mv = np.flatnonzero(tracks.moving)
            for j in range(len(self.canvases)):
                codes = pack_8bit(to_8bit(self.shown(tracks, mv, np.array([a]), j)[:, 0]))
                fixed, fixed_codes = self._near(tracks, codes, j)
                subset, codes = np.concatenate([mv, fixed]), np.concatenate([codes, fixed_codes])
                group = self.collision_group(tracks, subset, codes, j)
                if group is not None:
                    return Found(group[0], j, group[1], a, True)
        if Rule.SEPARATION in rules:
            found = self._pairs_below_at(tracks, a, None, Rule.SEPARATION)
            if found is not None:
                return found
        roles = self.tracks(moving_icons, roles=True)
        if Rule.CONFUSION in rules:
            found = self._pairs_below_at(roles, a, None, Rule.CONFUSION)
            if found is not None:
                return found
        if Rule.CVD_CONFUSION in rules:
            for deficiency in DEFICIENCIES:
                found = self._pairs_below_at(roles, a, deficiency, Rule.CVD_CONFUSION)
                if found is not None:
                    return found
        if Rule.CVD_COLLISION in rules and len(roles.label) > 1 and roles.moving.any():
            sources = [roles.source[t].tobytes().hex() for t in range(len(roles.label))]
            every = np.arange(len(roles.label))
            for deficiency in DEFICIENCIES:
                for j in range(len(self.canvases)):
                    shown = self.shown(roles, every, np.array([a, ALPHA_LO]), j)
                    seen = to_8bit(simulate_cvd(shown[:, 0], deficiency))
                    ref = to_8bit(simulate_cvd(shown[:, 1], deficiency))
                    cvd = self._cvd_group(roles, seen, ref, sources, j)
                    if cvd is not None:
                        return Found(Rule.CVD_COLLISION, j, cvd, a, True)
        return None

    def _pairs_below_at(
        self, tracks: _Tracks, a: float, deficiency: Deficiency | None, rule: Rule
    ) -> Found | None:
        """A pair involving a moving track below ``min_delta_e`` at ``a`` (confusion: and
        told apart at alpha 1), found by the pruned pair search."""
        n = len(tracks.label)
        if n < 2 or not tracks.moving.any():
            return None
        level = self.policy.min_delta_e
        every = np.arange(n)

        def view(c: NDArray[np.float64]) -> NDArray[np.float64]:
            return c if deficiency is None else simulate_cvd(c, deficiency)

        for j in range(len(self.canvases)):
            both = self.shown(tracks, every, np.array([a, ALPHA_LO]), j)
            lab = linear_to_lab(view(both[:, 0]))

            def distance(
                f: NDArray[np.intp], g: NDArray[np.intp], lab: NDArray[np.float64] = lab
            ) -> NDArray[np.float64]:
                return delta_e_2000_lab(lab[f], lab[g])

            first, second, _ = pairs_below(
                delta_e_2000_lightness_key(lab), distance, level, tracks.label
            )
            keep = tracks.moving[first] | tracks.moving[second]
            if rule is not Rule.SEPARATION:
                solid = self.ship(tracks.source, self.backgrounds[j], 1.0, 1.0)
                lab_ref = linear_to_lab(view(solid))
                keep &= confusion_possible(delta_e_2000_lab(lab_ref[first], lab_ref[second]), level)
            for f, g in zip(first[keep].tolist(), second[keep].tolist(), strict=True):
                icons = tuple(sorted({*tracks.icons[f], *tracks.icons[g]}))
                if not self.exempt(rule, self.canvases[j], icons):
                    pair = () if rule is Rule.SEPARATION else self.role_pair(tracks, f, g)
                    return Found(rule, j, icons, a, True, pair)
        return None

    # -- one question ------------------------------------------------------------

    def answer(
        self, moving_icons: NDArray[np.bool_], precision: int, per_canvas_needed: bool = True
    ) -> SafeAlpha:
        """Largest safe alpha when the icons in ``moving_icons`` share one coefficient.

        The same question is answered once: a colour with one icon asks what
        that icon asks (most brand colours have one logo).
        """
        moving = hashlib.blake2b(np.packbits(moving_icons).tobytes(), digest_size=16).digest()
        key = (moving, precision, per_canvas_needed)  # 16 bytes a question, whatever the set
        found = self._answers.get(key)
        if found is None:
            found = self._answer(moving_icons, precision, per_canvas_needed)
            self._answers[key] = found
        return found

    def _answer(
        self, moving_icons: NDArray[np.bool_], precision: int, per_canvas_needed: bool
    ) -> SafeAlpha:
        m = len(self.canvases)
        found: list[Found] = []
        for rule, icons in self.static:
            if any(moving_icons[i] for i in icons):
                found.append(Found(rule, -1, icons, ALPHA_LO, True))
        found += [f for f in self.per_row() if moving_icons[f.icons[0]]]
        tracks = self.tracks(moving_icons)
        found += self.collision_limits(tracks)
        caps = np.full(m, self.a_hi)
        for f in found:
            if f.canvas < 0 or not per_canvas_needed:
                caps = np.minimum(caps, f.at)
            else:
                caps[f.canvas] = min(caps[f.canvas], f.at)
        rules = self.policy.rules
        if self.a_hi > ALPHA_LO:
            found += self.separation_limits(tracks, caps)
            roles = self.tracks(moving_icons, roles=True)
            shrink = not per_canvas_needed
            if Rule.CONFUSION in rules:
                found += self.confusion_limits(roles, caps, None, shrink)
            if Rule.CVD_CONFUSION in rules:
                for deficiency in DEFICIENCIES:
                    found += self.confusion_limits(roles, caps, deficiency, shrink)
            if Rule.CVD_COLLISION in rules:
                found += self.cvd_collision_limits(roles, float(caps.max()))
        limits = [self._limit(f) for f in found]
        per_canvas_limit: list[Limit | None] = []
        for j in range(len(self.canvases)):
            here = [lim for f, lim in zip(found, limits, strict=True) if f.canvas in (j, -1)]
            per_canvas_limit.append(min(here, key=_limit_order) if here else None)
        per_canvas = tuple(
            CanvasLimit(name, self.rounded(limit, precision), limit)
            for name, limit in zip(self.canvases, per_canvas_limit, strict=True)
        )
        limit = min(limits, key=_limit_order) if limits else None
        alpha = self.rounded(limit, precision)
        unit = 10.0**-precision
        while alpha is not None and self.objection_at(moving_icons, alpha) is not None:
            # Only a float disagreement exactly at the rounded point gets here.
            stepped = _round_down(alpha - unit + unit / 2, precision)
            alpha = stepped if stepped >= ALPHA_LO else None
        if limit is None:
            exact: float | None = self.a_hi
        elif limit.attained and limit.at <= ALPHA_LO:
            exact = None
        else:
            exact = limit.at
        return SafeAlpha(alpha=alpha, exact=exact, limit=limit, per_canvas=per_canvas)

    def joint(
        self,
        colours: Iterable[str],
        precision: int,
        held: Iterable[str] = (),
        *,
        grow: bool = True,
    ) -> tuple[tuple[str, ...], SafeAlpha]:
        """The joint answer of a group of colours, and the group it has to grow into.

        Every icon of the group's colours moves (but those named in ``held``); the
        others keep their alpha.  What limits the answer may lie outside the group:
        a role the group pulls under the separation floor (the two roles of a
        ``confusion`` or ``cvd-confusion`` limit), or, when not even alpha 1 is safe,
        the colours of the icons that stop it there (a collision with a colour held
        at its own alpha).  Those colours join the group and the grown group is
        asked again, until its limit lies inside it.  So a group's answer names the
        pair that really limits it, and "no safe alpha" means alpha 1 itself fails
        for its icons.  Without ``grow`` only a group with no safe alpha grows, and
        one that has none after growing gives the last answer a smaller group had
        (``--apply``: every answer holds with the others at their alpha).  The
        group comes back in palette order.
        """
        group = set(colours)
        keep = set(held)
        index = {name: i for i, name in enumerate(self.names)}
        order = {c: k for k, c in enumerate(self.colours)}
        last: tuple[tuple[str, ...], SafeAlpha] | None = None
        while True:
            moving = np.zeros(len(self.names), dtype=bool)
            for i, colour in enumerate(self.colour_of):
                moving[i] = colour in group and self.names[i] not in keep
            safe = self.answer(moving, precision, per_canvas_needed=False)
            answer = tuple(sorted(group, key=lambda c: order.get(c, len(order)))), safe
            limit = safe.limit
            joins: set[str] = set()
            if limit is not None and safe.alpha is None:
                joins = set(limit.roles) or {self.colour_of[index[n]] for n in limit.icons}
            elif limit is not None and grow:
                joins = set(limit.roles)
            if joins <= group:
                return last if safe.alpha is None and last is not None else answer
            if safe.alpha is not None and not grow:
                last = answer
            group |= joins

    def joint_groups(
        self, seeds: Iterable[Iterable[str]], precision: int
    ) -> list[tuple[tuple[str, ...], SafeAlpha, tuple[str, ...]]]:
        """Disjoint groups grown from ``seeds`` (:meth:`joint`), with their answers and seeds.

        Two groups that grow into each other are one group: their seeds are joined
        and asked again, until no two share a colour.  Each comes with the seed
        colours it grew from, in palette order; groups in order of their first seed.
        """
        order = {c: k for k, c in enumerate(self.colours)}
        pending = [set(seed) for seed in seeds]
        while True:
            grown = [self.joint(seed, precision) for seed in pending]
            for k, (colours, _) in enumerate(grown):
                other = next((h for h in range(k) if set(grown[h][0]) & set(colours)), None)
                if other is not None:
                    pending[other] |= pending.pop(k)
                    break
            else:
                return [
                    (colours, safe, tuple(sorted(seed, key=lambda c: order.get(c, len(order)))))
                    for (colours, safe), seed in zip(grown, pending, strict=True)
                ]

    def _limit(self, found: Found) -> Limit:
        canvas = "(every canvas)" if found.canvas < 0 else self.canvases[found.canvas]
        grid = None if RULES[found.rule].closed_form else GRID_STEP
        icons = self.icon_names(found.icons)
        return Limit(found.rule, canvas, icons, found.at, found.attained, grid, found.roles)

    def rounded(self, limit: Limit | None, precision: int) -> float | None:
        """``limit.at`` (or alpha_max) rounded down, stepping off an unsafe point."""
        if limit is None:
            return _round_down(self.a_hi, precision)
        if limit.attained and limit.at <= ALPHA_LO:
            return None
        alpha = _round_down(limit.at, precision)
        if limit.attained and alpha >= limit.at:
            alpha = _round_down(limit.at - 10.0**-precision, precision)
        return alpha if alpha >= ALPHA_LO else None


def _limit_order(limit: Limit) -> tuple[float, bool, int, str, tuple[str, ...]]:
    """Earliest first; at a tie an unsafe point before an open interval; then rule, canvas."""
    return (limit.at, not limit.attained, _RULE_ORDER[limit.rule], limit.canvas, limit.icons)


def _swap_names(safe: SafeAlpha, old: str, new: str) -> SafeAlpha:
    """The same answer for another icon of the same style: swap the two names."""
    if old == new:
        return safe

    def swap(limit: Limit | None) -> Limit | None:
        if limit is None:
            return None
        names = {old: new, new: old}
        return replace(limit, icons=tuple(sorted(names.get(i, i) for i in limit.icons)))

    return replace(
        safe,
        limit=swap(safe.limit),
        per_canvas=tuple(replace(c, limit=swap(c.limit)) for c in safe.per_canvas),
    )


def _engine(result: AuditResult, policy: Policy, alpha_max: float, precision: int) -> _Engine:
    if not ALPHA_MAX.allows(alpha_max):
        raise UsageError(ALPHA_MAX.refusal(f"alpha_max {alpha_max:g}"))
    if isinstance(precision, bool) or not isinstance(precision, int) or precision not in PRECISION:
        raise UsageError(PRECISION.refusal(f"precision {precision!r}"))
    if not result.iconset.icons:
        why = "could be rendered" if result.problems else "is in it"
        raise UsageError(f"no icon of {result.iconset.name!r} {why}: nothing to suggest for")
    if not result.theme.canvases:
        raise UsageError(f"theme {result.theme.name!r} has no canvases")
    return _Engine(result, policy, alpha_max)


class SafeAlphas:
    """Largest-safe-alpha questions on one audit, sharing their work (per-row limits, timelines).

    ``answers(icons)`` is :func:`largest_safe_alpha` for those icons (all when ``None``).
    """

    def __init__(
        self, result: AuditResult, policy: Policy, *, alpha_max: float = 2.0, precision: int = 3
    ) -> None:
        self._engine = _engine(result, policy, alpha_max, precision)
        self._precision = precision

    def __call__(self, icons: Iterable[str] | None = None) -> SafeAlpha:
        per_canvas = icons is None
        moving = _moving(self._engine, icons)
        return self._engine.answer(moving, self._precision, per_canvas_needed=per_canvas)

    def joint(
        self, colours: Iterable[str], held: Iterable[str] = (), *, grow: bool = True
    ) -> tuple[tuple[str, ...], SafeAlpha]:
        """The group ``colours`` grow into and its joint answer (:meth:`_Engine.joint`).

        ``held`` names icons that keep their alpha although their colour moves.
        """
        return self._engine.joint(colours, self._precision, held, grow=grow)

    def joint_groups(
        self, seeds: Iterable[Iterable[str]]
    ) -> list[tuple[tuple[str, ...], SafeAlpha, tuple[str, ...]]]:
        """Disjoint groups grown from ``seeds`` and their answers (:meth:`_Engine.joint_groups`)."""
        return self._engine.joint_groups(seeds, self._precision)


def largest_safe_alpha(
    result: AuditResult,
    policy: Policy,
    *,
    icons: Sequence[str] | None = None,
    alpha_max: float = 2.0,
    precision: int = 3,
) -> SafeAlpha:
    """The largest safe alpha when ``icons`` (default: all) share one coefficient.

    The other icons keep their alpha in ``result``.

    >>> from alpha_audit.model import Canvas, Icon, IconSet, Theme
    >>> from alpha_audit.rows import audit
    >>> theme = Theme("t", (Canvas("yellow", "#ffff00"),))
    >>> dots = IconSet("s", (Icon("dot", "dot.svg", "#0000d0", 1.0),))
    >>> largest_safe_alpha(audit(theme, dots), Policy()).limit.rule.value  # dark blue on yellow
    'loss'
    """
    engine = _engine(result, policy, alpha_max, precision)
    return engine.answer(_moving(engine, icons), precision)


def _moving(engine: _Engine, icons: Iterable[str] | None) -> NDArray[np.bool_]:
    if icons is None:
        return np.ones(len(engine.names), dtype=bool)
    wanted = set(icons)
    unknown = sorted(wanted - set(engine.names))
    if unknown:
        raise UsageError(f"no icon named {unknown[0]!r} in {engine.result.iconset.name}")
    return np.isin(np.array(engine.names), sorted(wanted)).reshape(-1)


def connected(groups: Iterable[Iterable[str]]) -> list[tuple[str, ...]]:
    """The connected components of colours joined by ``groups`` (each sorted), in order
    of first appearance; a colour alone is no group.

    >>> connected([("red", "orange"), ("amber", "yellow"), ("orange", "amber"), ("blue",)])
    [('amber', 'orange', 'red', 'yellow')]
    """
    parent: dict[str, str] = {}

    def find(x: str) -> str:
        parent.setdefault(x, x)
        while parent[x] != x:
            parent[x] = parent[parent[x]]
            x = parent[x]
        return x

    for group in groups:
        colours = list(group)
        for other in colours:
            parent[find(other)] = find(colours[0])
    out: dict[str, list[str]] = {}
    for colour in parent:
        out.setdefault(find(colour), []).append(colour)
    return [tuple(sorted(g)) for g in out.values() if len(g) > 1]


def confusion_groups(
    result: AuditResult, policy: Policy, extra: Iterable[Iterable[str]] = ()
) -> list[tuple[str, ...]]:
    """The roles the gate finds confused at their alphas, as connected groups.

    Two roles a failing ``confusion`` or ``cvd-confusion`` finding names are
    joined (on any canvas), and so are the colours of each of ``extra``
    (:func:`connected`).

    >>> from alpha_audit.model import Canvas, Icon, IconSet, Theme
    >>> from alpha_audit.rows import audit
    >>> pal = {"a": "#ee7733", "b": "#ee3377", "c": "#0077bb"}
    >>> icons = IconSet("s", tuple(Icon(k, f"{k}.svg", v, 1.5, k) for k, v in pal.items()), pal)
    >>> confusion_groups(audit(Theme("t", (Canvas("w", "#ffffff"),)), icons), Policy())
    [('a', 'b')]
    """
    role_rules = frozenset(r for r in policy.rules if RULES[r].family is Family.CONFUSION)
    pairs: list[Iterable[str]] = []
    if role_rules:
        only = Policy(
            rules=role_rules,
            warnings=frozenset(),
            min_delta_e=policy.min_delta_e,
            exemptions=policy.exemptions,
        )
        for f in findings_for(result, only):
            if f.exemption is None and isinstance(f.figures, ConfusionFigures):
                pairs.append(f.figures.roles)
    return connected([*pairs, *extra])


def suggest(
    result: AuditResult,
    policy: Policy,
    *,
    alpha_max: float = 2.0,
    precision: int = 3,
    scopes: Iterable[str] = SCOPES,
    groups: Iterable[Iterable[str]] = (),
    progress: Progress | None = None,
) -> SuggestResult:
    """The largest safe alpha for the whole set, per colour, per group of roles and per icon.

    Set-wide, every icon takes the same coefficient; per colour, the icons of
    that colour (palette name, else the colour) move together; per group, the
    roles the gate finds confused at their alphas, connected through confusion
    (:func:`confusion_groups`; ``groups`` adds more), move together and take in
    every role their joint answer finds pulled under the floor
    (:meth:`_Engine.joint`); per icon, one icon moves.  Others keep their alpha.
    ``policy`` is the gate's.  Icons that could not be rendered are left out, as
    ``check`` leaves them out (``left_out``).  ``progress`` is told how many
    questions there are, then each one answered.

    >>> from alpha_audit.model import Canvas, Icon, IconSet, Theme
    >>> from alpha_audit.rows import audit
    >>> theme = Theme("t", (Canvas("ink", "#0d1117"),))
    >>> orange, other = Icon("o", "o.svg", "#ee7733", 1.0), Icon("x", "x.svg", "#ff7f36", 1.0)
    >>> result = suggest(audit(theme, IconSet("s", (orange, other))), Policy())
    >>> result.alpha  # together, the two never share an 8-bit output up to 2
    2.0
    >>> alone = result.per_icon[0].safe  # orange alone passes through #ff7f36
    >>> alone.alpha, alone.limit.rule.value, alone.limit.icons, round(alone.limit.at, 6)
    (1.165, 'new-collision', ('o', 'x'), 1.165168)
    """
    engine = _engine(result, policy, alpha_max, precision)
    wanted = set(scopes)
    unknown = wanted - set(SCOPES)
    if unknown:
        raise UsageError(f"unknown scope {sorted(unknown)[0]!r}; use one of: {', '.join(SCOPES)}")
    iconset = result.iconset
    n = len(engine.names)
    start, tick = progress or ((lambda total: None), (lambda: None))
    members: dict[str, list[int]] = {name: [] for name in engine.colours}
    for i, colour in enumerate(engine.colour_of):
        members[colour].append(i)
    seeds = confusion_groups(result, policy, groups) if "group" in wanted else []
    start(
        ("set" in wanted)
        + len(members) * ("colour" in wanted)
        + len(seeds)
        + n * ("icon" in wanted)
    )
    overall = engine.answer(np.ones(n, dtype=bool), precision) if "set" in wanted else None
    tick()

    per_color = []
    for name, icons in members.items() if "colour" in wanted else ():
        if not icons:
            tick()
            continue
        moving = np.zeros(n, dtype=bool)
        moving[icons] = True
        per_color.append(
            ColorSuggestion(
                color=name,
                source=iconset.icons[icons[0]].color,
                icons=tuple(engine.names[i] for i in icons),
                safe=engine.answer(moving, precision, per_canvas_needed=False),
            )
        )
        tick()

    per_group = []
    for colours, safe, seed in engine.joint_groups(seeds, precision):
        icons = sorted(i for c in colours for i in members.get(c, []))
        per_group.append(
            GroupSuggestion(colours, tuple(engine.names[i] for i in icons), safe, seed)
        )
    for _ in seeds:
        tick()

    # Icons of one style (the same paints at the same alpha) get the same answer,
    # unless an exemption names an icon; then every icon is asked on its own.
    share = not any(e.icon is not None for e in policy.exemptions)
    styles: dict[int, list[tuple[int, float]]] = {}
    for p, i in enumerate(engine.row_icon.tolist()):
        styles.setdefault(i, []).append((int(engine.keys[p]), float(result.alpha[p])))
    cache: dict[tuple[tuple[int, float], ...], tuple[str, SafeAlpha]] = {}
    per_icon = []
    for i, icon in enumerate(iconset.icons if "icon" in wanted else ()):
        style = tuple(sorted(styles.get(i, [])))
        if share and style in cache:
            rep, safe = cache[style]
            safe = _swap_names(safe, rep, icon.name)
        else:
            moving = np.zeros(n, dtype=bool)
            moving[i] = True
            safe = engine.answer(moving, precision, per_canvas_needed=False)
            cache[style] = (icon.name, safe)
        per_icon.append(IconSuggestion(icon.name, icon.color_name or icon.color, icon.alpha, safe))
        tick()
    empty = SafeAlpha(None, None, None, ())
    return SuggestResult(
        audit=result,
        policy=policy,
        alpha_max=engine.a_hi,
        precision=precision,
        overall=overall if overall is not None else empty,
        per_color=tuple(per_color),
        per_icon=tuple(per_icon),
        per_group=tuple(per_group),
        left_out=tuple(p.icon for p in result.problems),
    )
