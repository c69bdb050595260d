"""Event maths against direct evaluation (compositing + to_8bit + luminance)."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from alpha_audit.color import composite_extended, pack_8bit, relative_luminance, to_8bit
from alpha_audit.suggest.events import (
    CODE_THRESHOLDS,
    code_timelines,
    first_in_luminance_band,
    luminance_band,
)

unit = st.floats(0.0, 1.0, allow_nan=False)
WIDE = 1e-12  # a gap between events wider than float noise on a coefficient near 1


def _direct(s: np.ndarray, b: np.ndarray, a: np.ndarray, o: np.ndarray) -> np.ndarray:
    """Packed 8-bit codes of paints ``s`` (P, 3) at opacity ``o`` on ``b`` at ``a`` (P, N)."""
    shown = b + o[:, None, None] * (np.clip(b + a[..., None] * (s - b)[:, None, :], 0, 1) - b)
    return pack_8bit(to_8bit(shown))


@settings(max_examples=60, deadline=None)
@given(
    st.lists(st.tuples(unit, unit, unit, unit), min_size=1, max_size=8),
    st.tuples(unit, unit, unit),
    st.sampled_from([(1.0, 2.0), (1.1, 1.3), (1.0, 1.02)]),
)
def test_code_timelines_match_to_8bit_between_events(paints: list, background, window) -> None:
    """Every gap's code is what direct compositing and to_8bit give inside it."""
    s, o = np.array(paints)[:, :3], np.array(paints)[:, 3]
    b = np.array(background)
    for k, (points, codes) in enumerate(code_timelines(s, b, *window, o)):
        assert points[0] == window[0] and points[-1] == window[1]
        assert codes.size == 2 * points.size - 1
        mids = 0.5 * (points[:-1] + points[1:])
        # Crossings are computed to about an ulp, so two channels' events a few ulps apart
        # leave a gap whose midpoint the direct formula may put on either side: only gaps
        # wider than float noise are compared (the engine re-checks its rounded answer
        # directly).
        wide = np.diff(points) > WIDE
        direct = _direct(s[k : k + 1], b, mids[None, :], o[k : k + 1])[0]
        assert np.array_equal(direct[wide], codes[1::2][wide])


def test_code_timelines_gap_narrower_than_a_float() -> None:
    """Two channels whose events are 1e-15 apart (hypothesis found it): the wider gaps hold."""
    s, b = np.array([[0.5, 0.5, 0.0]]), np.array([0.0, 1.4348070227260641e-15, 0.0])
    points, codes = code_timelines(s, b, 1.0, 2.0)[0]
    mids = 0.5 * (points[:-1] + points[1:])
    wide = np.diff(points) > WIDE
    assert not wide.all()  # the case is real: some gaps are a few ulps wide
    assert wide.sum() > 30
    direct = _direct(s, b, mids[None, :], np.ones(1))[0]
    assert np.array_equal(direct[wide], codes[1::2][wide])


def test_paints_are_independent_of_each_other() -> None:
    """A paint's timeline is the same alone and among others (chunks included)."""
    rng = np.random.default_rng(7)
    s, o, b = rng.random((600, 3)), rng.random(600), rng.random(3)
    together = code_timelines(s, b, 1.0, 1.5, o)
    for k in (0, 255, 256, 599):
        alone = code_timelines(s[k : k + 1], b, 1.0, 1.5, o[k : k + 1])[0]
        assert np.array_equal(alone[0], together[k][0])
        assert np.array_equal(alone[1], together[k][1])


def test_a_paint_that_never_moves_keeps_the_canvas_code() -> None:
    points, codes = code_timelines([[0.2, 0.4, 0.6]], [0.2, 0.4, 0.6], 1.0, 2.0)[0]
    assert points.tolist() == [1.0, 2.0]
    assert codes.tolist() == [int(pack_8bit(to_8bit(np.array([0.2, 0.4, 0.6]))))] * 3


def test_half_way_rounds_to_even() -> None:
    # Red from 0 on black: at the event for threshold n the code is the even one.
    for n, at, before, after in ((100, 100, 100, 101), (101, 102, 101, 102)):
        points, codes = code_timelines([[CODE_THRESHOLDS[n] / 1.5, 0, 0]], [0.0] * 3, 1.0, 2.0)[0]
        k = int(np.flatnonzero(np.isclose(points, 1.5))[0])
        red = codes >> 16
        assert (red[2 * k], red[2 * k - 1], red[2 * k + 1]) == (at, before, after)


@settings(max_examples=60, deadline=None)
@given(unit, unit, unit, unit, unit, unit, st.floats(1.05, 10.0))
def test_luminance_band_start_matches_a_dense_scan(r, g, bl, br, bg, bb, limit) -> None:
    s, b = np.array([r, g, bl]), np.array([br, bg, bb])
    lo, hi = luminance_band(limit, relative_luminance(b))
    start, attained = first_in_luminance_band(s, b, lo, hi, 1.0, 2.0)
    grid = np.linspace(1.0, 2.0, 20001)
    y = relative_luminance(composite_extended(s, b, grid))
    inside = (lo < y) & (y < hi)
    if np.isnan(start):
        assert not inside.any()
    else:
        assert not inside[grid < start - 1e-12].any()
        if inside.any():
            assert grid[np.argmax(inside)] - start < 1e-4 + 1e-12
        assert bool(attained) == bool(start == 1.0 and inside[0])


@settings(max_examples=60, deadline=None)
@given(
    st.lists(st.floats(0.05, 1.95), min_size=1, max_size=40),
    st.floats(0.5, 40.0),
    st.sampled_from([1, 4096]),
)
def test_first_below_brackets_each_items_crossing(crossings, slope, budget) -> None:
    """Several points per step (few items) or plain bisection (budget 1): the same bracket.

    Item i is ``slope * (c_i - a)`` -- it drops below 0 exactly at ``c_i`` -- and an item
    that never drops; each bracket must hold its ``c_i`` and be within the tolerance.
    """
    import importlib

    from alpha_audit.suggest.events import BISECTION_TOLERANCE, first_below

    events = importlib.import_module("alpha_audit.suggest.events")  # the package name is shadowed
    c = np.array([*crossings, 5.0])  # the last one never drops below on [0, 2]
    calls = []

    def f(a: np.ndarray) -> np.ndarray:
        calls.append(a.shape)
        points = np.broadcast_to(a, (c.size, a.shape[-1])) if a.ndim == 1 else a
        return slope * (c[:, np.newaxis] - points)

    old = events._REFINE_POINTS
    events._REFINE_POINTS = budget
    try:
        safe, unsafe = first_below(f, np.linspace(0.0, 2.0, 2001), 0.0)
    finally:
        events._REFINE_POINTS = old
    assert np.isnan(safe[-1]) and np.isnan(unsafe[-1])
    ok = ~np.isnan(unsafe)
    assert ok[:-1].all()
    tol = BISECTION_TOLERANCE * (1 + 1e-6)
    assert np.all(unsafe[ok] - safe[ok] <= tol)
    assert np.all(safe[ok] <= c[ok] + 1e-12) and np.all(c[ok] <= unsafe[ok] + 1e-12)
    assert np.all(slope * (c[ok] - unsafe[ok]) < 0) and np.all(slope * (c[ok] - safe[ok]) >= 0)
    if budget == 1:
        assert all(shape[-1] == 1 for shape in calls[1:])  # plain bisection
    else:
        assert len(calls) <= 1 + 5  # 1e-3 to 1e-9 in 16-fold steps


def test_one_background_per_paint_is_each_paint_on_its_own_canvas() -> None:
    rng = np.random.default_rng(11)
    s, b, o = rng.random((40, 3)), rng.random((40, 3)), rng.random(40)
    together = code_timelines(s, b, 1.0, 2.0, o)
    for k in (0, 13, 39):
        alone = code_timelines(s[k : k + 1], b[k], 1.0, 2.0, o[k : k + 1])[0]
        assert np.array_equal(alone[0], together[k][0])
        assert np.array_equal(alone[1], together[k][1])
