"""The largest safe coefficient, exactly: set-wide, per palette colour and per icon.

For a gate :class:`~alpha_audit.policy.Policy` ``P`` the largest safe alpha is

    a* = sup { a <= a_max : every a' in [1, a] satisfies P }

(issue 4).  It is computed from *events*, not a sweep (see
:mod:`alpha_audit.suggest.events`): contrast rules cross their thresholds at
closed-form points of a piecewise-linear luminance, 8-bit collisions live on
intervals between code changes known exactly, and only CIEDE2000 separation
is bracketed and bisected to 1e-9.  The reported value is ``a*`` rounded
*down* to ``precision`` decimals and re-checked at that point by direct
compositing.

Rules mean what :mod:`alpha_audit.gate` means by them on an
:func:`~alpha_audit.audit.audit` result.  Per colour and per icon, the chosen
icons move together while every other icon keeps its configured alpha, and
only findings involving a moved icon count (the others do not depend on the
coefficient being chosen).  Pure computation: nothing is printed.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from decimal import ROUND_FLOOR, Decimal

import numpy as np
from numpy.typing import NDArray

from alpha_audit.color import (
    Pipeline,
    composite_extended,
    contrast_from_luminance,
    delta_e_2000,
    delta_e_2000_lab,
    linear_to_lab,
    pack_8bit,
    relative_luminance,
    to_8bit,
)
from alpha_audit.color.nearest import (
    delta_e_2000_lightness_key,
    iter_pairs,
    lightness_weight_max,
    pairs_below,
)
from alpha_audit.errors import UsageError
from alpha_audit.load.paint_masks import PaintSet
from alpha_audit.model import IconSet, Theme
from alpha_audit.policy import Policy, Rule, contrast_breaks, contrast_floor
from alpha_audit.ranges import ALPHA_MAX, PRECISION
from alpha_audit.suggest.events import (
    clip_breakpoints,
    code_timeline,
    first_below,
    first_in_luminance_band,
    luminance_band,
)
from alpha_audit.suggest.paint_rules import BRACKETED_RULES, GRID_STEP, PaintRules, PaintScenario

__all__ = [
    "SEPARATION_GRID_STEP",
    "CanvasLimit",
    "ColorSuggestion",
    "IconSuggestion",
    "Limit",
    "SafeAlpha",
    "SuggestResult",
    "largest_safe_alpha",
    "suggest",
]

# CIEDE2000 has no closed form in a: its crossings are bracketed on this grid
# (plus every clip breakpoint) and bisected to events.BISECTION_TOLERANCE.
SEPARATION_GRID_STEP = GRID_STEP
# Pair x grid-point evaluations held at once by the separation search (~10 MB
# per float64 intermediate of colour-science's CIEDE2000).
_SEPARATION_CHUNK = 1 << 20
# Code timelines kept between questions (a few KB per colour and canvas).
_TIMELINE_CACHE_BYTES = 64 << 20
ALPHA_LO = 1.0  # the reference coefficient; the safe interval starts here
_RULE_ORDER = {rule: k for k, rule in enumerate(Rule)}


@dataclass(frozen=True)
class Limit:
    """What stops a coefficient: a rule broken on a canvas by some icons.

    ``at`` is the first unsafe alpha, the infimum of the unsafe coefficients.
    When ``attained`` it is itself unsafe; otherwise it is the last safe one
    and every coefficient just above it is unsafe.
    """

    rule: Rule
    canvas: str
    icons: tuple[str, ...]
    at: float
    attained: bool
    # None: found exactly from events; else the bracketing grid step (then
    # bisected to 1e-9): a dip narrower than this could be missed.
    grid: float | None = None


@dataclass(frozen=True)
class CanvasLimit:
    """The largest safe alpha if this canvas were the only one."""

    canvas: str
    alpha: float | None
    limit: Limit | None


@dataclass(frozen=True)
class SafeAlpha:
    """A largest safe alpha with what limits it.

    ``alpha`` is rounded down to the precision and re-checked (``None``: not
    even alpha = 1 is safe); ``exact`` is the unrounded supremum; ``limit``
    is ``None`` when nothing breaks up to ``alpha_max``.
    """

    alpha: float | None
    exact: float | None
    limit: Limit | None
    per_canvas: tuple[CanvasLimit, ...]


@dataclass(frozen=True)
class ColorSuggestion:
    """Every icon of one palette colour moving together."""

    color: str  # palette name (or the colour itself when it has none)
    source: str
    icons: tuple[str, ...]
    safe: SafeAlpha


@dataclass(frozen=True)
class IconSuggestion:
    """One icon moving alone."""

    icon: str
    color: str
    configured: float
    safe: SafeAlpha


@dataclass(frozen=True)
class SuggestResult:
    """Set-wide, per-colour and per-icon largest safe alphas; see :func:`suggest`."""

    theme: Theme
    iconset: IconSet
    policy: Policy
    threshold: float
    alpha_max: float
    precision: int
    overall: SafeAlpha
    per_color: tuple[ColorSuggestion, ...]
    per_icon: tuple[IconSuggestion, ...]

    @property
    def alpha(self) -> float | None:
        """The set-wide suggestion (one coefficient for every icon)."""
        return self.overall.alpha


@dataclass(frozen=True)
class _Tracks:
    """Icons grouped by what they show: moving ones by source, fixed ones by (source, alpha)."""

    source: NDArray[np.float64]  # (T, 3) linear
    alpha: NDArray[np.float64]  # (T,) nan when moving
    moving: NDArray[np.bool_]  # (T,), moving tracks first
    key: NDArray[np.intp]  # (T,) distinct source at full precision
    ref: NDArray[np.intp]  # (T,) 8-bit class of the source (alpha = 1)
    color: tuple[str, ...]  # (T,) hex, as audit's separation compares colours
    icons: tuple[tuple[int, ...], ...]


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
    # The count after the last event at each (code, element).
    last_at = np.r_[(pos[1:] != pos[:-1]) | (codes[1:] != codes[:-1]), True]
    shared = last_at & (active >= 2)
    return np.unique(pos[shared])


def _round_down(value: float, precision: int) -> float:
    """``value`` rounded towards minus infinity to ``precision`` decimals, exactly."""
    step = Decimal(1).scaleb(-precision)
    return float(Decimal(repr(value)).quantize(step, rounding=ROUND_FLOOR))


class _Suggester:
    """Everything shared by the set-wide, per-colour and per-icon questions."""

    def __init__(
        self,
        theme: Theme,
        iconset: IconSet,
        policy: Policy,
        threshold: float,
        alpha_max: float,
        paints: PaintSet | None = None,
        pipeline: Pipeline = "linear",
    ) -> None:
        self.policy = policy
        self._timelines: dict[tuple[bytes, int], tuple[NDArray[np.float64], NDArray[np.int64]]] = {}
        self._timeline_bytes = 0
        self.threshold = threshold
        self.a_hi = alpha_max
        self.names = tuple(i.name for i in iconset.icons)
        self.canvases = tuple(c.name for c in theme.canvases)
        self.colors = tuple(i.color for i in iconset.icons)
        self.sources = iconset.sources
        self.alphas = iconset.alphas
        self.backgrounds = theme.backgrounds
        self.y_bg = relative_luminance(self.backgrounds)
        n = len(self.names)
        self.keys = np.unique(self.sources, axis=0, return_inverse=True)[1].reshape(n)
        ref_codes = pack_8bit(to_8bit(self.sources))
        self.refs = np.unique(ref_codes, return_inverse=True)[1].reshape(n)
        # audit.py: collisions already present at alpha = 1 (source keys sharing a code).
        groups: dict[int, set[int]] = {}
        for k, r in zip(self.keys.tolist(), self.refs.tolist(), strict=True):
            groups.setdefault(r, set()).add(k)
        self.ref_groups = {frozenset(g) for g in groups.values() if len(g) > 1}
        # With the SVGs' paints read, the gate judges contrast per paint row (its
        # own colour and opacity): PaintRules answers those, exactly.
        self.contrast_rules = policy.contrast_rules if paints is None else ()
        self.paint_rules = PaintRules(
            theme, iconset, paints, policy, threshold, alpha_max, self.exempt, pipeline
        )
        self.collision_rule = policy.collision_rule
        self.separation = Rule.SEPARATION in policy.rules
        # Exemptions or multi-source 8-bit classes need the group-by-group verdict.
        self.slow_collisions = bool(policy.exemptions) or (
            self.collision_rule is Rule.NEW_COLLISION and bool(self.ref_groups)
        )

    # -- scenario set-up --------------------------------------------------

    def tracks(self, moving: NDArray[np.bool_]) -> _Tracks:
        """Group icons: moving ones by source key, fixed ones by (source key, alpha)."""
        groups: dict[tuple[int, float], list[int]] = {}
        for i in range(len(self.names)):
            # Moving icons all take the same alpha, so the source alone decides.
            alpha = -math.inf if moving[i] else float(self.alphas[i])
            groups.setdefault((int(self.keys[i]), alpha), []).append(i)
        labels = sorted(groups, key=lambda lab: (lab[1] != -math.inf, groups[lab][0]))
        first = [groups[lab][0] for lab in labels]
        is_moving = np.array([lab[1] == -math.inf for lab in labels], dtype=bool)
        return _Tracks(
            source=self.sources[first],
            alpha=np.where(is_moving, math.nan, [lab[1] for lab in labels]),
            moving=is_moving,
            key=self.keys[first],
            ref=self.refs[first],
            color=tuple(self.colors[i] for i in first),
            icons=tuple(tuple(groups[lab]) for lab in labels),
        )

    def icon_names(self, tracks: _Tracks, members: list[int] | NDArray[np.intp]) -> tuple[str, ...]:
        return tuple(sorted(self.names[i] for t in members for i in tracks.icons[int(t)]))

    def exempt(self, rule: Rule, canvas: str, icons: tuple[str, ...]) -> bool:
        return self.policy.exempt(rule, canvas, icons) is not None

    def unexempt_icons(self, rule: Rule, canvas: str, icons: tuple[str, ...]) -> tuple[str, ...]:
        """Icons of a per-icon finding that no exemption covers."""
        if not self.policy.exemptions:
            return icons
        return tuple(name for name in icons if not self.exempt(rule, canvas, (name,)))

    # -- the three kinds of event ------------------------------------------

    def contrast_limits(self, tracks: _Tracks) -> list[list[Limit]]:
        """Per canvas, the first unsafe alpha of each contrast rule and moving track."""
        out: list[list[Limit]] = [[] for _ in self.canvases]
        mv = np.flatnonzero(tracks.moving)
        if not self.contrast_rules or mv.size == 0:
            return out
        s = tracks.source[mv]
        y_src = relative_luminance(s)
        c_ref = contrast_from_luminance(y_src[:, np.newaxis], self.y_bg[np.newaxis, :])
        for rule in self.contrast_rules:
            limit = contrast_floor(rule, self.policy, c_ref, self.threshold)
            lo, hi = luminance_band(limit, self.y_bg[np.newaxis, :])
            start, attained = first_in_luminance_band(
                s[:, np.newaxis, :], self.backgrounds[np.newaxis, :, :], lo, hi, ALPHA_LO, self.a_hi
            )
            for r, j in zip(*np.nonzero(np.isfinite(start)), strict=True):
                canvas = self.canvases[j]
                icons = self.unexempt_icons(rule, canvas, self.icon_names(tracks, [mv[r]]))
                if icons:
                    out[j].append(
                        Limit(rule, canvas, icons, float(start[r, j]), bool(attained[r, j]))
                    )
        return out

    def collision_group(
        self, tracks: _Tracks, codes: NDArray[np.int64], j: int
    ) -> tuple[str, ...] | None:
        """Icons of the first unsafe collision group (holding a moving track), if any.

        ``codes`` are every track's packed 8-bit outputs on canvas ``j`` at one
        coefficient; the verdict is audit.py's and gate.py's, group by group.
        """
        rule = self.collision_rule
        assert rule is not None
        for t in np.flatnonzero(tracks.moving):
            members = np.flatnonzero(codes == codes[t])
            keys = frozenset(tracks.key[members].tolist())
            if len(keys) < 2 or (rule is Rule.NEW_COLLISION and keys in self.ref_groups):
                continue
            icons = self.icon_names(tracks, members)
            if not self.exempt(rule, self.canvases[j], icons):
                return icons
        return None

    def track_segments(
        self, source: NDArray[np.float64], j: int
    ) -> tuple[NDArray[np.float64], NDArray[np.int64]]:
        """One moving source's own timeline on canvas ``j``: (points, packed element codes).

        Cached per (source, canvas): the set-wide, per-colour and per-icon
        questions move the same sources again and again.
        """
        key = (source.tobytes(), j)
        found = self._timelines.get(key)
        if found is None:
            timeline = code_timeline(source, self.backgrounds[j], ALPHA_LO, self.a_hi)
            codes = timeline.elements()[2]  # (3, 2K + 1)
            found = (timeline.points, pack_8bit(codes.T))
            size = found[0].nbytes + found[1].nbytes
            if self._timeline_bytes + size > _TIMELINE_CACHE_BYTES:
                self._timelines.clear()  # memory stays bounded; recomputing is exact
                self._timeline_bytes = 0
            self._timelines[key] = found
            self._timeline_bytes += size
        return found

    def collision_limits(self, tracks: _Tracks) -> list[list[Limit]]:
        """Per canvas, where the first unsafe 8-bit collision starts (exact).

        Each track's code is a step function of alpha: a list of segments
        (a point or an open gap, each one code).  A collision needs two
        segments with one code overlapping, so one sort of all segments by
        code finds every place where two or more share a code; only those
        places are judged, in order, by :meth:`collision_group`.  Cost and
        memory are linear in the number of segments (about 2 x 3 x 255 per
        moving track at most), never tracks x tracks x events.
        """
        out: list[list[Limit]] = [[] for _ in self.canvases]
        rule = self.collision_rule
        mv = np.flatnonzero(tracks.moving)
        if rule is None or mv.size == 0 or len(tracks.key) < 2:
            return out
        fixed = np.flatnonzero(~tracks.moving)
        fixed_codes = pack_8bit(
            to_8bit(
                composite_extended(
                    tracks.source[fixed, np.newaxis, :],
                    self.backgrounds[np.newaxis, :, :],
                    tracks.alpha[fixed, np.newaxis],
                )
            )
        )  # (F, m)
        n_tracks = len(tracks.key)
        for j in range(len(self.canvases)):
            own = [self.track_segments(tracks.source[t], j) for t in mv]
            points = np.unique(np.concatenate([p for p, _ in own]))  # every event of canvas j
            last = 2 * (points.size - 1)  # global elements 0..last: point, gap, point, ...
            seg_track, seg_lo, seg_hi, seg_code = [], [], [], []
            for t, (p, codes) in zip(mv, own, strict=True):
                g = 2 * np.searchsorted(points, p)  # this track's points as global elements
                lo = np.empty(codes.size, dtype=np.int64)
                hi = np.empty(codes.size, dtype=np.int64)
                lo[0::2], hi[0::2] = g, g
                lo[1::2], hi[1::2] = g[:-1] + 1, g[1:] - 1
                seg_track.append(np.full(codes.size, t))
                seg_lo.append(lo)
                seg_hi.append(hi)
                seg_code.append(codes)
            seg_track.append(fixed)
            seg_lo.append(np.zeros(fixed.size, dtype=np.int64))
            seg_hi.append(np.full(fixed.size, last, dtype=np.int64))
            seg_code.append(fixed_codes[:, j])
            track = np.concatenate(seg_track)
            lo, hi, code = (np.concatenate(x) for x in (seg_lo, seg_hi, seg_code))
            candidates = _shared_code_starts(lo, hi, code)
            if candidates.size == 0:
                continue
            # Every track's code at a candidate element: its segment by track then start.
            order = np.lexsort((lo, track))
            sorted_key = track[order] * (last + 2) + lo[order]
            everyone = np.arange(n_tracks) * (last + 2)
            for e in candidates.tolist():
                at = order[np.searchsorted(sorted_key, everyone + e, side="right") - 1]
                icons = self.collision_group(tracks, code[at], j)
                if icons is not None:
                    start, is_point = float(points[e // 2]), e % 2 == 0
                    out[j].append(Limit(rule, self.canvases[j], icons, start, is_point))
                    break
        return out

    def separation_limits(self, tracks: _Tracks) -> list[list[Limit]]:
        """Per canvas, where CIEDE2000 between two colours first drops below the minimum.

        Canvas by canvas and a chunk of pairs at a time (bounded memory for any
        number of colours).  A pair whose lightness bound (``dE00 >= |dL| /
        S_L,max``, :mod:`alpha_audit.color.nearest`) keeps it at or above the
        minimum at every grid point cannot be found below it by the grid
        search either, so it is skipped without changing the answer.
        """
        out: list[list[Limit]] = [[] for _ in self.canvases]
        if not self.separation or len(tracks.key) < 2:
            return out
        labels = np.unique(np.array(tracks.color, dtype=object), return_inverse=True)[1]
        labels = labels.reshape(-1)
        level = self.policy.min_delta_e
        steps = max(1, math.ceil((self.a_hi - ALPHA_LO) / SEPARATION_GRID_STEP))
        breaks = clip_breakpoints(
            tracks.source[tracks.moving][:, np.newaxis, :], self.backgrounds[np.newaxis]
        ).reshape(-1)
        breaks = breaks[(breaks > ALPHA_LO) & (breaks < self.a_hi)]
        grid = np.unique(np.concatenate([np.linspace(ALPHA_LO, self.a_hi, steps + 1), breaks]))
        n_grid = grid.size
        every = np.arange(len(tracks.key))
        chunk = max(1, _SEPARATION_CHUNK // n_grid)
        for j, background in enumerate(self.backgrounds):

            def output(
                t: NDArray[np.intp], a: NDArray[np.float64], bg: NDArray[np.float64] = background
            ) -> NDArray[np.float64]:
                coef = np.where(tracks.moving[t][:, np.newaxis], a, tracks.alpha[t][:, np.newaxis])
                src = tracks.source[t][:, np.newaxis, :]
                return np.clip(bg + coef[..., np.newaxis] * (src - bg), 0.0, 1.0)

            lightness = linear_to_lab(output(every, grid))[..., 0]  # (T, N)
            s_l = lightness_weight_max(lightness)
            for first, second in iter_pairs(len(tracks.key), labels, chunk=chunk):
                moved = tracks.moving[first] | tracks.moving[second]
                first, second = first[moved], second[moved]
                if first.size == 0:
                    continue
                gap = np.min(np.abs(lightness[first] - lightness[second]), axis=1) / s_l
                near = gap < level * (1.0 + 1e-9)
                first, second = first[near], second[near]
                if first.size == 0:
                    continue

                def delta_e(
                    a: NDArray[np.float64],
                    f: NDArray[np.intp] = first,
                    g: NDArray[np.intp] = second,
                ) -> NDArray[np.float64]:
                    return delta_e_2000(output(f, a), output(g, a))  # (p, N)

                _, unsafe = first_below(delta_e, grid, level)
                for p in np.flatnonzero(np.isfinite(unsafe)):
                    icons = self.icon_names(tracks, [first[p], second[p]])
                    if not self.exempt(Rule.SEPARATION, self.canvases[j], icons):
                        out[j].append(
                            Limit(
                                Rule.SEPARATION,
                                self.canvases[j],
                                icons,
                                float(unsafe[p]),
                                True,
                                SEPARATION_GRID_STEP,
                            )
                        )
        return out

    # -- one question ----------------------------------------------------------

    def scenario(self, tracks: _Tracks) -> tuple[NDArray[np.bool_], PaintScenario]:
        """The question as the paint rules see it: moving icons, and the tracks."""
        moving = np.zeros(len(self.names), dtype=bool)
        for t in np.flatnonzero(tracks.moving):
            moving[list(tracks.icons[t])] = True
        return moving, PaintScenario(tracks.source, tracks.alpha, tracks.moving, tracks.icons)

    def paint_limits(
        self, tracks: _Tracks, caps: NDArray[np.float64], shrink: bool
    ) -> list[list[Limit]]:
        """Per canvas, the paint rules' limits (rules on every canvas go to each)."""
        out: list[list[Limit]] = [[] for _ in self.canvases]
        moving, scenario = self.scenario(tracks)
        found = self.paint_rules.limits(moving, scenario, caps, shrink=shrink)
        for rule, j, icons, at, attained in found:
            grid = GRID_STEP if rule in BRACKETED_RULES else None
            names = tuple(sorted(self.names[i] for i in icons))
            for k in range(len(self.canvases)) if j < 0 else (j,):
                canvas = "(every canvas)" if j < 0 else self.canvases[k]
                out[k].append(Limit(rule, canvas, names, at, attained, grid))
        return out

    def unsafe_at(self, tracks: _Tracks, a: float) -> bool:
        """Direct check of one coefficient: composite, quantise, apply the rules."""
        moving, scenario = self.scenario(tracks)
        if self.paint_rules.first_objection(moving, scenario, a) is not None:
            return True
        coef = np.where(tracks.moving, a, tracks.alpha)
        out = composite_extended(
            tracks.source[:, np.newaxis, :], self.backgrounds[np.newaxis], coef[:, np.newaxis]
        )  # (T, m, 3)
        mv = np.flatnonzero(tracks.moving)
        y_bg = self.y_bg[np.newaxis, :]
        c_ref = contrast_from_luminance(relative_luminance(tracks.source[mv])[:, np.newaxis], y_bg)
        contrast = contrast_from_luminance(relative_luminance(out[mv]), y_bg)
        for rule in self.contrast_rules:
            broken = contrast_breaks(rule, self.policy, c_ref, contrast, self.threshold)
            for r, j in zip(*np.nonzero(broken), strict=True):
                names = self.icon_names(tracks, [mv[r]])
                if self.unexempt_icons(rule, self.canvases[j], names):
                    return True
        if self.collision_rule is not None:
            codes = pack_8bit(to_8bit(out))
            for j in range(len(self.canvases)):
                if self.collision_group(tracks, codes[:, j], j) is not None:
                    return True
        if self.separation and len(tracks.key) > 1:
            labels = np.unique(np.array(tracks.color, dtype=object), return_inverse=True)[1]
            for j in range(len(self.canvases)):
                lab = linear_to_lab(out[:, j])

                def distance(
                    f: NDArray[np.intp], g: NDArray[np.intp], lab: NDArray[np.float64] = lab
                ) -> NDArray[np.float64]:
                    return delta_e_2000_lab(lab[f], lab[g])

                key = delta_e_2000_lightness_key(lab)
                first, second, _ = pairs_below(key, distance, self.policy.min_delta_e, labels)
                for a_i, b_i in zip(first.tolist(), second.tolist(), strict=True):
                    if not (tracks.moving[a_i] or tracks.moving[b_i]):
                        continue
                    names = self.icon_names(tracks, [a_i, b_i])
                    if not self.exempt(Rule.SEPARATION, self.canvases[j], names):
                        return True
        return False

    def answer(
        self, moving: NDArray[np.bool_], precision: int, per_canvas_needed: bool = True
    ) -> SafeAlpha:
        """Largest safe alpha when the icons in ``moving`` share one coefficient."""
        tracks = self.tracks(moving)
        found = [
            c + k + s
            for c, k, s in zip(
                self.contrast_limits(tracks),
                self.collision_limits(tracks),
                self.separation_limits(tracks),
                strict=True,
            )
        ]
        # A canvas's first limit lies at or below its earliest exact one; when only
        # the question's answer matters (not each canvas's), the earliest of all.
        caps = np.array([min([self.a_hi, *(lim.at for lim in ls)]) for ls in found])
        if not per_canvas_needed:
            caps[:] = caps.min()
        paint = self.paint_limits(tracks, caps, shrink=not per_canvas_needed)
        found = [f + p for f, p in zip(found, paint, strict=True)]
        per_canvas_limit = [min(ls, key=_limit_order) if ls else None for ls in found]
        per_canvas = tuple(
            CanvasLimit(name, self.rounded(limit, precision), limit)
            for name, limit in zip(self.canvases, per_canvas_limit, strict=True)
        )
        limits = [lim for lim in per_canvas_limit if lim is not None]
        limit = min(limits, key=_limit_order) if limits else None
        alpha = self.rounded(limit, precision)
        unit = 10.0**-precision
        while alpha is not None and self.unsafe_at(tracks, alpha):
            # Only a float disagreement exactly at the rounded point gets here.
            stepped = _round_down(alpha - unit + unit / 2, precision)
            alpha = stepped if stepped >= ALPHA_LO else None
        if limit is None:
            exact_at: float | None = self.a_hi
        elif limit.attained and limit.at <= ALPHA_LO:
            exact_at = None
        else:
            exact_at = limit.at
        return SafeAlpha(alpha=alpha, exact=exact_at, limit=limit, per_canvas=per_canvas)

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


def largest_safe_alpha(
    theme: Theme,
    iconset: IconSet,
    policy: Policy,
    *,
    icons: list[str] | None = None,
    alpha_max: float = 2.0,
    precision: int = 3,
    threshold: float | None = None,
    paints: PaintSet | None = None,
    pipeline: Pipeline = "linear",
) -> SafeAlpha:
    """The largest safe alpha when ``icons`` (default: all) share one coefficient.

    The other icons keep their configured alpha.

    >>> from alpha_audit.model import Canvas, Icon, IconSet, Theme
    >>> theme = Theme("t", (Canvas("yellow", "#ffff00"),))
    >>> dots = IconSet("s", (Icon("dot", "dot.svg", "#0000d0", 1.0),))
    >>> largest_safe_alpha(theme, dots, Policy()).limit.rule.value  # dark blue on yellow
    'loss'
    """
    engine = _engine(theme, iconset, policy, alpha_max, precision, threshold, paints, pipeline)
    moving = np.ones(len(iconset.icons), dtype=bool)
    if icons is not None:
        unknown = sorted(set(icons) - set(engine.names))
        if unknown:
            raise UsageError(f"no icon named {unknown[0]!r} in {iconset.name}")
        moving = np.isin(np.array(engine.names), icons)
    return engine.answer(moving, precision)


def _engine(
    theme: Theme,
    iconset: IconSet,
    policy: Policy,
    alpha_max: float,
    precision: int,
    threshold: float | None,
    paints: PaintSet | None = None,
    pipeline: Pipeline = "linear",
) -> _Suggester:
    if not ALPHA_MAX.allows(alpha_max):
        raise UsageError(ALPHA_MAX.refusal(f"alpha_max {alpha_max:g}"))
    if isinstance(precision, bool) or not isinstance(precision, int) or precision not in PRECISION:
        raise UsageError(PRECISION.refusal(f"precision {precision!r}"))
    if not iconset.icons:
        raise UsageError(f"icon set {iconset.name!r} has no icons")
    if not theme.canvases:
        raise UsageError(f"theme {theme.name!r} has no canvases")
    if paints is not None and paints.problems:
        # As check does: icons that could not be rendered are left out of the audit.
        broken = {p.icon for p in paints.problems}
        iconset = replace(iconset, icons=tuple(i for i in iconset.icons if i.name not in broken))
        if not iconset.icons:
            raise UsageError(f"no icon of {iconset.name!r} could be rendered")
    t = theme.threshold if threshold is None else float(threshold)
    if not math.isfinite(t):
        raise UsageError(f"threshold must be a finite number, got {t}")
    if pipeline == "css":
        # CSS opacity cannot exceed 1 (CSS Color 4 clamps alpha): the only
        # coefficient above the reference is none, so the question is alpha 1.
        alpha_max = ALPHA_LO
    return _Suggester(theme, iconset, policy, t, float(alpha_max), paints, pipeline)


def suggest(
    theme: Theme,
    iconset: IconSet,
    policy: Policy,
    *,
    alpha_max: float = 2.0,
    precision: int = 3,
    threshold: float | None = None,
    paints: PaintSet | None = None,
    pipeline: Pipeline = "linear",
) -> SuggestResult:
    """The largest safe alpha for the whole set, per palette colour and per icon.

    Set-wide, every icon takes the same coefficient; per colour, the icons of
    that palette colour move together; per icon, one icon moves.  Others keep
    their configured alpha.  ``policy`` is the gate's (required, so no default
    is applied silently; ``Policy()`` is the gate's default: no loss, no newly
    failing icon, no new collision).

    >>> from alpha_audit.model import Canvas, Icon, IconSet, Theme
    >>> theme = Theme("t", (Canvas("ink", "#0d1117"),))
    >>> orange, other = Icon("o", "o.svg", "#ee7733", 1.0), Icon("x", "x.svg", "#ff7f36", 1.0)
    >>> result = suggest(theme, IconSet("s", (orange, other)), Policy())
    >>> result.alpha  # together, the two never share an 8-bit output up to 2
    2.0
    >>> alone = result.per_icon[0].safe  # orange alone passes through #ff7f36
    >>> alone.alpha, alone.limit.rule.value, alone.limit.icons, round(alone.limit.at, 6)
    (1.165, 'new-collision', ('o', 'x'), 1.165168)
    """
    engine = _engine(theme, iconset, policy, alpha_max, precision, threshold, paints, pipeline)
    n = len(iconset.icons)
    overall = engine.answer(np.ones(n, dtype=bool), precision)

    groups: dict[str, list[int]] = {name: [] for name in iconset.palette}
    for i, icon in enumerate(iconset.icons):
        groups.setdefault(icon.color_name or icon.color, []).append(i)
    per_color = []
    for name, members in groups.items():
        if not members:
            continue
        moving = np.zeros(n, dtype=bool)
        moving[members] = True
        per_color.append(
            ColorSuggestion(
                color=name,
                source=iconset.icons[members[0]].color,
                icons=tuple(engine.names[i] for i in members),
                safe=engine.answer(moving, precision, per_canvas_needed=False),
            )
        )

    # Icons of one style (source, configured alpha) get the same answer, unless
    # an exemption names an icon; then every icon is asked on its own.
    share = not any(e.icon is not None for e in engine.policy.exemptions)
    cache: dict[tuple[int, float], tuple[str, SafeAlpha]] = {}
    per_icon = []
    for i, icon in enumerate(iconset.icons):
        style = (int(engine.keys[i]), float(engine.alphas[i]))
        if share and style in cache:
            rep, safe = cache[style]
            safe = _swap_names(safe, rep, icon.name)
        else:
            moving = np.zeros(n, dtype=bool)
            moving[i] = True
            safe = engine.answer(moving, precision, per_canvas_needed=False)
            cache[style] = (icon.name, safe)
        per_icon.append(IconSuggestion(icon.name, icon.color, icon.alpha, safe))
    return SuggestResult(
        theme=theme,
        iconset=iconset,
        policy=engine.policy,
        threshold=engine.threshold,
        alpha_max=engine.a_hi,
        precision=precision,
        overall=overall,
        per_color=tuple(per_color),
        per_icon=tuple(per_icon),
    )
