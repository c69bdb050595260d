"""Event maths against direct evaluation (compositing + to_8bit + luminance)."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from alpha_audit.color import composite_extended, relative_luminance, to_8bit
from alpha_audit.suggest.events import (
    CODE_THRESHOLDS,
    code_timeline,
    first_in_luminance_band,
    luminance_band,
)

unit = st.floats(0.0, 1.0, allow_nan=False)
WIDE = 1e-12  # a gap between events wider than float noise on a coefficient near 1


@settings(max_examples=60, deadline=None)
@given(st.lists(st.tuples(unit, unit), min_size=1, max_size=6))
def test_code_timeline_matches_to_8bit_between_events(channels: list) -> None:
    s, b = np.array(channels).T
    t = code_timeline(s, b, 1.0, 2.0)
    mids = 0.5 * (t.points[:-1] + t.points[1:])
    # Crossings are computed to about an ulp, so two channels' events a few ulps apart
    # leave a gap whose midpoint the direct formula may put on either side: only gaps wider
    # than float noise are compared (the engine re-checks its rounded answer directly).
    inside = np.diff(t.points) > WIDE
    direct = to_8bit(np.clip(b[:, None] + mids[None, :] * (s - b)[:, None], 0, 1))
    assert inside.sum() >= 1
    assert np.array_equal(direct[:, inside], t.between[:, inside])


def test_code_timeline_gap_narrower_than_a_float() -> None:
    """Two channels whose events are 1e-15 apart (hypothesis found it): the wider gaps hold."""
    t = code_timeline([0.5, 0.5], [0.0, 1.4348070227260641e-15], 1.0, 2.0)
    mids = 0.5 * (t.points[:-1] + t.points[1:])
    inside = np.diff(t.points) > WIDE
    assert not inside.all()  # the case is real: some gaps are a few ulps wide
    assert inside.sum() > 30
    s, b = np.array([0.5, 0.5]), np.array([0.0, 1.4348070227260641e-15])
    direct = to_8bit(np.clip(b[:, None] + mids[None, :] * (s - b)[:, None], 0, 1))
    assert np.array_equal(direct[:, inside], t.between[:, inside])


def test_half_way_rounds_to_even() -> None:
    # Channel from 0 on black: at the event for threshold n the code is the even one.
    t = code_timeline([CODE_THRESHOLDS[100] / 1.5], [0.0], 1.0, 2.0)
    k = int(np.flatnonzero(np.isclose(t.points, 1.5))[0])
    assert t.at_points[0, k] == 100 and t.between[0, k - 1] == 100 and t.between[0, k] == 101
    t = code_timeline([CODE_THRESHOLDS[101] / 1.5], [0.0], 1.0, 2.0)
    k = int(np.flatnonzero(np.isclose(t.points, 1.5))[0])
    assert t.at_points[0, k] == 102 and t.between[0, k - 1] == 101


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
