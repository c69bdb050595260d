"""8-bit collisions, exactly: where a moving paint first ships the code of another.

Each track's 8-bit output is a step function of the coefficient
(:func:`~alpha_audit.suggest.events.code_timelines`); the verdict on a group
of tracks sharing a code is :mod:`alpha_audit.findings`' own
(:meth:`~alpha_audit.policy.Policy.collision_rule`).
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Sequence
from functools import cached_property

import numpy as np
from numpy.typing import NDArray

from alpha_audit.color import delta_e_2000_lab, linear_to_lab, pack_8bit, shipped, to_8bit
from alpha_audit.color.nearest import delta_e_2000_lightness_key, pairs_below
from alpha_audit.rules import RULES, Family, Rule
from alpha_audit.suggest.events import Floats, Indices, code_timelines
from alpha_audit.suggest.scene import ALPHA_LO, Found, Scene, Tracks

# Code timelines kept between questions (a few KB per paint and canvas).
_TIMELINE_CACHE_BYTES = 64 << 20
# A question moving few paints builds their timelines on every canvas in one batch.
_TIMELINES_AT_ONCE = 1024
# One paint's code timeline on one canvas: (points, packed codes of its elements).
Timeline = tuple[Floats, NDArray[np.int64]]


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
    moving: NDArray[np.bool_], subset: Indices, codes: NDArray[np.int64]
) -> Iterator[Indices]:
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


class Collisions:
    """The collision rules' questions on one scene, sharing codes, near pairs and timelines."""

    def __init__(self, scene: Scene) -> None:
        self.scene = scene
        # Whether any failing rule objects to a collision (which one depends on how far
        # apart its colours were at alpha 1: Policy.collision_rule).
        self.collides = any(RULES[r].family is Family.COLLISION for r in scene.policy.rules)
        self._near_pairs: dict[int, dict[tuple[int, int], float]] = {}
        self._timelines: dict[tuple[bytes, int, float, float], Timeline] = {}
        self._timeline_bytes = 0

    @cached_property
    def fixed_codes(self) -> NDArray[np.int32]:
        """Every row's packed 8-bit output on every canvas at its own alpha: (rows, canvases).

        What a track that does not move ships never depends on the question:
        it is the row's own output (:attr:`~alpha_audit.rows.AuditResult.output_codes`).
        """
        return pack_8bit(self.scene.result.output_codes).astype(np.int32)

    @cached_property
    def _code_index(self) -> tuple[NDArray[np.int32], NDArray[np.int32]]:
        """Each canvas's fixed codes sorted, and the rows in that order."""
        codes = self.fixed_codes.T  # (canvases, rows)
        order = np.argsort(codes, axis=1, kind="stable").astype(np.int32)
        return np.take_along_axis(codes, order, axis=1), order

    @cached_property
    def _ref_lab(self) -> Floats:
        """CIELAB of what each paint ships at alpha 1 on each canvas: (paints, canvases, 3)."""
        _, first = np.unique(self.scene.keys, return_index=True)  # a row of each paint
        return linear_to_lab(shipped(self.scene.result.reference[first]))

    def _near(
        self, tracks: Tracks, moving_codes: NDArray[np.int64], j: int
    ) -> tuple[Indices, NDArray[np.int64]]:
        """The fixed tracks whose code on canvas ``j`` is one of ``moving_codes``, and
        those codes: no other fixed track can share a code with a moving one.

        Found through each canvas's rows sorted by code, so a question costs what its
        own codes match, not the number of rows (rows of one fixed track ship one code).
        """
        if tracks.moving.all():  # a set-wide question: nothing stays
            return np.zeros(0, dtype=np.intp), np.zeros(0, dtype=np.int64)
        ordered, order = self._code_index[0][j], self._code_index[1][j]
        want = np.unique(moving_codes)
        lo = np.searchsorted(ordered, want, side="left")
        count = np.searchsorted(ordered, want, side="right") - lo
        at = np.repeat(lo - np.cumsum(count) + count, count) + np.arange(count.sum())
        track = tracks.row_track[order[at]]
        track = track[track >= 0]
        near = np.unique(track[~tracks.moving[track]])
        return near, self.fixed_codes[tracks.first[near], j].astype(np.int64)

    def near_pairs(self, j: int) -> dict[tuple[int, int], float]:
        """The paints already closer than the near-duplicate distance at alpha 1 on canvas
        ``j`` (CIEDE2000 of what they ship there), by pair of paint keys: found once per
        canvas by the lightness-pruned pair search (:func:`~alpha_audit.color.nearest.pairs_below`),
        so judging a collision is a look-up."""
        found = self._near_pairs.get(j)
        if found is None:
            lab = self._ref_lab[:, j]

            def distance(f: Indices, g: Indices) -> Floats:
                return delta_e_2000_lab(lab[f], lab[g])

            # Paints shipping one colour at alpha 1 (0 apart) are found whatever the distance.
            near = max(self.scene.policy.near_duplicate_delta_e, _SAME_COLOUR)
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
        self, tracks: Tracks, subset: Indices, codes: NDArray[np.int64], j: int
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
            rule = self.scene.policy.collision_rule(widest, self.scene.policy.rules)
            if rule is None:
                continue
            icons = self.scene.exempt(rule, j, [i for m in members for i in tracks.icons[m]])
            if icons is not None:
                return rule, icons
        return None

    def track_segments(
        self,
        tracks: Tracks,
        moving: Indices,
        canvases: Sequence[int],
        a_lo: float,
        a_hi: float,
    ) -> list[Timeline]:
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
                tracks.source[t], self.scene.backgrounds[j], a_lo, a_hi, tracks.opacity[t]
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

    def collision_limits(self, tracks: Tracks) -> list[Found]:
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
        if (
            not self.collides
            or mv.size == 0
            or len(tracks.label) < 2
            or self.scene.a_hi <= ALPHA_LO
        ):
            return out
        chosen = tracks.row_track >= 0
        rows = np.flatnonzero(chosen)[tracks.moving[tracks.row_track[chosen]]]
        own_alpha = float(self.scene.result.alpha[rows].max()) if rows.size else self.scene.a_hi
        windows = [(ALPHA_LO, self.scene.a_hi)]
        if ALPHA_LO < own_alpha < self.scene.a_hi:
            windows = [(ALPHA_LO, own_alpha), (own_alpha, self.scene.a_hi)]
        pending = list(range(len(self.scene.canvases)))
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
        self, tracks: Tracks, mv: Indices, j: int, a_lo: float, a_hi: float
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

    def at(self, tracks: Tracks, a: float) -> Found | None:
        """An unsafe collision at exactly ``a`` involving a moving track (an answer's re-check)."""
        if not self.collides or not tracks.moving.any():
            return None
        mv = np.flatnonzero(tracks.moving)
        for j in range(len(self.scene.canvases)):
            codes = pack_8bit(to_8bit(self.scene.shown(tracks, mv, np.array([a]), j)[:, 0]))
            fixed, fixed_codes = self._near(tracks, codes, j)
            subset, codes = np.concatenate([mv, fixed]), np.concatenate([codes, fixed_codes])
            group = self.collision_group(tracks, subset, codes, j)
            if group is not None:
                return Found(group[0], j, group[1], a, True)
        return None
