"""q50, full share and size contrast against an independent computation from the mask."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from alpha_audit.color import (
    composite_paint,
    contrast_ratio,
    coverage_stats,
    coverage_stats_of,
    full_share,
    hex_to_linear,
    median_coverage,
    size_contrast_float,
)

codes = arrays(np.uint8, (6, 6), elements=st.integers(0, 255))
unit = st.floats(0, 1, allow_nan=False)
color = arrays(np.float64, (3,), elements=unit)


def reference_q50(mask: np.ndarray) -> float:
    """Walk the 256 coverage levels upwards, adding each level's ink, until half is reached."""
    values = mask.astype(int).ravel()
    total = sum(v for v in values if v > 0)
    running = 0
    for level in range(1, 256):
        running += level * sum(1 for v in values if v == level)
        if 2 * running >= total:
            return level / 255
    raise AssertionError("empty mask")


@given(codes)
def test_q50_matches_level_walk(mask: np.ndarray) -> None:
    if not mask.any():
        assert np.isnan(median_coverage(mask))
        return
    assert median_coverage(mask) == pytest.approx(reference_q50(mask), abs=1e-12)
    # the same mask as floats gives the same answer
    assert median_coverage(mask / 255.0) == pytest.approx(reference_q50(mask), abs=1e-12)


@given(codes)
def test_full_share_matches_counting(mask: np.ndarray) -> None:
    ink = mask[mask > 0].astype(int).sum()
    if ink == 0:
        assert np.isnan(full_share(mask))
        return
    assert full_share(mask) == pytest.approx(255 * np.count_nonzero(mask == 255) / ink)


@given(st.lists(arrays(np.uint8, st.tuples(st.integers(0, 9), st.integers(0, 9))), max_size=6))
def test_many_masks_at_once_are_each_exact(masks: list[np.ndarray]) -> None:
    """Each figure of each 8-bit mask, reduced together, is the correctly rounded value of
    its exact rational (Fraction), and q50 is the level walk's."""
    for mask, stats in zip(masks, coverage_stats_of(masks), strict=True):
        ink = int(mask.astype(int).sum())
        if ink == 0:
            assert stats.pixels == 0 and stats.ink == 0.0
            assert np.isnan(stats.q50) and np.isnan(stats.full_share)
            continue
        assert stats.pixels == np.count_nonzero(mask)
        assert stats.ink == float(Fraction(ink, 255))
        assert stats.full_share == float(Fraction(255 * np.count_nonzero(mask == 255), ink))
        assert stats.q50 == reference_q50(mask)
        assert coverage_stats(mask) == stats


def test_hand_examples() -> None:
    assert median_coverage([[1.0, 0.25, 0.25, 0.0]]) == 1.0
    # ink 0.1 + 0.2 + 0.3 + 0.4 = 1.0; cumulative 0.1, 0.3, 0.6: half reached at 0.3
    assert median_coverage([[0.4, 0.3, 0.2, 0.1]]) == 0.3
    stats = coverage_stats(np.array([[255, 0], [128, 255]], dtype=np.uint8))
    assert stats.pixels == 3
    assert stats.ink == pytest.approx(2 + 128 / 255)
    assert stats.full_share == pytest.approx(2 / (2 + 128 / 255))


def test_median_ignores_mask_order_and_does_not_mutate() -> None:
    mask = np.array([[0.2, 0.9], [0.5, 0.0]])
    before = mask.copy()
    assert median_coverage(mask) == median_coverage(mask[::-1, ::-1]) == 0.9
    np.testing.assert_array_equal(mask, before)


@given(color, color, st.floats(-1, 3), unit, unit)
def test_size_contrast_is_contrast_at_q50(
    source: np.ndarray, canvas: np.ndarray, alpha: float, q50: float, opacity: float
) -> None:
    shown = (
        opacity * q50 * np.clip(canvas + alpha * (source - canvas), 0, 1)
        + (1 - opacity * q50) * canvas
    )
    expected = float(contrast_ratio(shown, canvas))
    got = float(size_contrast_float(source, canvas, alpha, q50, opacity))
    assert got == pytest.approx(expected, rel=1e-12)


@given(color, color, st.floats(-1, 3), unit, unit)
def test_size_contrast_never_exceeds_colour_contrast_linear(
    source: np.ndarray, canvas: np.ndarray, alpha: float, q50: float, opacity: float
) -> None:
    colour_contrast = float(contrast_ratio(composite_paint(source, canvas, alpha, opacity), canvas))
    assert float(size_contrast_float(source, canvas, alpha, q50, opacity)) <= colour_contrast * (
        1 + 1e-12
    )


def test_css_size_contrast_can_exceed_colour_contrast() -> None:
    """Not a bug: a blend along a straight line in gamma space is not monotone in luminance.

    Under ``css`` the antialiased pixels of #0487c9 on #e01fad are further from the canvas's
    luminance than the solid paint, so "size contrast <= colour contrast" holds for the linear
    pipeline only (docs/model.md).
    """
    source, canvas = hex_to_linear("#0487c9"), hex_to_linear("#e01fad")
    solid = float(contrast_ratio(composite_paint(source, canvas, 1.0, pipeline="css"), canvas))
    edge = float(size_contrast_float(source, canvas, 1.0, 0.47, pipeline="css"))
    assert solid == pytest.approx(1.0695, abs=1e-4)
    assert edge == pytest.approx(1.3541, abs=1e-4)


@given(unit, unit, unit, unit)
def test_css_size_contrast_bounded_for_greys(s: float, b: float, alpha: float, q50: float) -> None:
    """On one axis (greys) the gamma-space path is monotone, so the bound holds under css too."""
    source, canvas = np.full(3, s), np.full(3, b)
    solid = float(contrast_ratio(composite_paint(source, canvas, alpha, pipeline="css"), canvas))
    assert float(size_contrast_float(source, canvas, alpha, q50, pipeline="css")) <= solid * (
        1 + 1e-12
    )
