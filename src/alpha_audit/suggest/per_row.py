"""Per-row limits: contrast, thin strokes, drift and lock, each row on its own.

A row's verdict depends on no other icon, so every row's first unsafe alpha
is found once per audit, moving from 1 to ``a_hi``.  The contrast rules and
``thin-strokes`` are exact (luminance bands on the clipped composite, then
every 8-bit code on the way); drift and lock are bracketed on a grid and
bisected (CIEDE2000 has no closed form in ``a``).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from alpha_audit.color import (
    composite_coverage,
    contrast_from_luminance,
    contrast_ratio,
    delta_e_2000,
    relative_luminance,
    shipped,
)
from alpha_audit.findings import LOCK_TOLERANCE
from alpha_audit.policy import (
    contrast_breaks,
    contrast_floor,
    drift_breaks,
    drift_ceiling,
    size_contrast_floor,
)
from alpha_audit.rules import Rule
from alpha_audit.suggest.events import (
    Floats,
    code_crossings,
    first_below,
    first_in_luminance_band,
    luminance_band,
    luminance_band_pieces,
)
from alpha_audit.suggest.scene import ALPHA_LO, CHUNK, Found, Scene, alpha_grid

# The most an 8-bit screen moves a linear channel, so a luminance: half the widest gap
# between decoded codes (next to white: (1 - decode(254/255)) / 2 = 0.004449), rounded up.
SHIPPED_Y_ERROR = 0.0045
# Candidates judged at once by _first_unsafe_code (each up to ~1,500 elements).
_CANDIDATES = 512


def _first_unsafe_code(
    source: Floats,
    background: Floats,
    coverage: Floats,
    a_lo: Floats,
    a_hi: float,
    y_screen: Floats,
    floor: Floats,
    windows: Floats,
) -> tuple[Floats, NDArray[np.bool_]]:
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


def per_row_limits(scene: Scene) -> list[Found]:
    """First unsafe alpha of every per-row rule, each row moving from 1 to ``a_hi``."""
    found: list[Found] = []
    if scene.a_hi > ALPHA_LO and len(scene.row_icon):
        found += _contrast(scene)
        rules = scene.policy.rules
        if Rule.THIN_STROKES in rules:
            found += _thin_strokes(scene)
        if Rule.DRIFT in rules:
            every = np.ones(len(scene.row_icon), dtype=bool)
            found += _drift(scene, Rule.DRIFT, scene.policy.max_drift, every)
        if Rule.LOCK in rules:
            found += _drift(scene, Rule.LOCK, LOCK_TOLERANCE, scene.locked)
    return found


def _band_starts(scene: Scene, floor: Floats, coverage: Floats) -> tuple[Floats, NDArray[np.bool_]]:
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
    lo, hi = luminance_band(floor, scene.y_screen.reshape(shape_bg))
    lo, hi = lo - SHIPPED_Y_ERROR, hi + SHIPPED_Y_ERROR
    y_bg = scene.y_bg.reshape(shape_bg)
    o = coverage
    with np.errstate(divide="ignore", invalid="ignore"):
        lo_c = np.where(o > 0, (lo - (1.0 - o) * y_bg) / o, np.inf)
        hi_c = np.where(o > 0, (hi - (1.0 - o) * y_bg) / o, -np.inf)
    p, m = len(scene.row_icon), len(scene.canvases)
    shape = (*floor.shape, 3)  # cells index every axis, sizes included
    s = np.broadcast_to(scene.result.sources.reshape(p, 1, *([1] * extra), 3), shape)
    b = np.broadcast_to(scene.backgrounds.reshape(1, m, *([1] * extra), 3), shape)
    pieces = luminance_band_pieces(s, b, lo_c, hi_c, ALPHA_LO, scene.a_hi)
    bound, _ = first_in_luminance_band(s, b, lo_c, hi_c, ALPHA_LO, scene.a_hi, pieces=pieces)
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
    y_screen = np.broadcast_to(scene.y_screen.reshape(shape_bg), floor.shape)
    cells = np.argwhere(np.isfinite(bound))
    for chunk in range(0, len(cells), _CANDIDATES):
        at = tuple(cells[chunk : chunk + _CANDIDATES].T)
        first, point = _first_unsafe_code(
            s[at], b[at], np.broadcast_to(o, floor.shape)[at], bound[at], scene.a_hi,
            y_screen[at], floor[at], windows[at],
        )  # fmt: skip
        start[at], attained[at] = first, point
    return start, attained


def _contrast(scene: Scene) -> list[Found]:
    out: list[Found] = []
    r = scene.result
    o = np.broadcast_to(r.opacity[:, np.newaxis], r.contrast_ref.shape)
    for rule in scene.policy.contrast_rules:
        floor = contrast_floor(rule, scene.policy, r.contrast_ref, scene.threshold)
        start, attained = _band_starts(scene, floor, o)
        out += _collect(scene, rule, start, attained)
    return out


def _thin_strokes(scene: Scene) -> list[Found]:
    r = scene.result
    if not r.sizes:
        return []
    limit = scene.policy.size_contrast_limit(scene.threshold)
    p, m, k = len(scene.row_icon), len(scene.canvases), len(r.sizes)
    coverage = (np.nan_to_num(r.q50, nan=0.0) * r.opacity[:, np.newaxis])[:, None, :]
    floor = np.full((p, m, k), size_contrast_floor(limit))
    start, attained = _band_starts(scene, floor, np.broadcast_to(coverage, (p, m, k)))
    start = np.where(np.isnan(r.q50)[:, np.newaxis, :], np.nan, start)  # no ink
    first = np.nanmin(np.where(np.isnan(start), np.inf, start), axis=2)
    hit = np.isfinite(first)
    att = np.any(attained & (start == first[..., np.newaxis]), axis=2)
    return _collect(scene, Rule.THIN_STROKES, np.where(hit, first, np.nan), att)


def _drift(scene: Scene, rule: Rule, limit: float, selected: NDArray[np.bool_]) -> list[Found]:
    r = scene.result
    rows = np.flatnonzero(selected)
    m = len(scene.canvases)
    start = np.full((len(scene.row_icon), m), np.nan)
    if rows.size == 0:
        return []
    grid = alpha_grid(ALPHA_LO, scene.a_hi, scene.breaks(r.sources[rows]))
    per = max(1, CHUNK // (grid.size * m))
    bg = scene.backgrounds[np.newaxis, :, np.newaxis, :]
    for lo in range(0, rows.size, per):
        sel = rows[lo : lo + per]
        s = r.sources[sel][:, np.newaxis, np.newaxis, :]
        o = r.opacity[sel][:, np.newaxis, np.newaxis]
        ref = scene.ship(s, bg, 1.0, o)  # (q, m, 1, 3)

        def minus_drift(
            a: Floats,
            s: Floats = s,
            o: Floats = o,
            ref: Floats = ref,
        ) -> Floats:
            a = a.reshape(1, 1, -1) if a.ndim == 1 else a.reshape(len(s), m, -1)
            return -delta_e_2000(ref, scene.ship(s, bg, a, o))

        # drift_breaks(d, limit) is d > drift_ceiling(limit), i.e. -d < -ceiling.
        _, unsafe = first_below(minus_drift, grid, -drift_ceiling(limit))
        start[sel] = unsafe
    return _collect(scene, rule, start, np.isfinite(start))


def _collect(scene: Scene, rule: Rule, start: Floats, attained: NDArray[np.bool_]) -> list[Found]:
    out: list[Found] = []
    for p, j in zip(*np.nonzero(np.isfinite(start)), strict=True):
        icon = scene.exempt(rule, int(j), (int(scene.row_icon[p]),))
        if icon is not None:
            out.append(Found(rule, int(j), icon, float(start[p, j]), bool(attained[p, j])))
    return out


def row_objection(scene: Scene, moving_icons: NDArray[np.bool_], a: float) -> Found | None:
    """A per-row rule broken at exactly ``a`` by a moving icon's row (an answer's re-check)."""
    r, rules = scene.result, scene.policy.rules
    rows = np.flatnonzero(moving_icons[scene.row_icon])
    bg = scene.backgrounds[np.newaxis]
    if not rows.size:
        return None
    s = r.sources[rows][:, np.newaxis, :]
    o = r.opacity[rows][:, np.newaxis]
    shown = scene.ship(s, bg, a, o)
    c_now = contrast_ratio(shown, shipped(bg))
    checks: list[tuple[Rule, NDArray[np.bool_]]] = [
        (
            rule,
            contrast_breaks(rule, scene.policy, r.contrast_ref[rows], c_now, scene.threshold),
        )
        for rule in scene.policy.contrast_rules
    ]
    if Rule.DRIFT in rules or Rule.LOCK in rules:
        d = delta_e_2000(shipped(r.reference[rows]), shown)
        if Rule.DRIFT in rules:
            checks.append((Rule.DRIFT, drift_breaks(d, scene.policy.max_drift)))
        if Rule.LOCK in rules:
            lock = drift_breaks(d, LOCK_TOLERANCE) & scene.locked[rows][:, np.newaxis]
            checks.append((Rule.LOCK, lock))
    if Rule.THIN_STROKES in rules and r.sizes:
        limit = scene.policy.size_contrast_limit(scene.threshold)
        q = (np.nan_to_num(r.q50[rows]) * r.opacity[rows][:, np.newaxis])[:, np.newaxis, :]
        at = scene.ship(s[:, :, None], bg[..., None, :], a, q)
        sc = contrast_ratio(at, shipped(bg)[..., np.newaxis, :])
        sc = np.where(np.isnan(r.q50[rows])[:, np.newaxis, :], np.nan, sc)
        thin = np.asarray((sc < size_contrast_floor(limit)).any(axis=2))
        checks.append((Rule.THIN_STROKES, thin))
    for rule, broken in checks:
        for k, j in zip(*np.nonzero(broken), strict=True):
            icon = scene.exempt(rule, int(j), (int(scene.row_icon[rows[k]]),))
            if icon is not None:
                return Found(rule, int(j), icon, a, True)
    return None
