"""Extended compositing: the properties the paper proves (Section 3, Appendix A.3)."""

from __future__ import annotations

import numpy as np
from hypothesis import given
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from alpha_audit.color import (
    composite_coverage,
    composite_extended,
    composite_raw,
    contrast_ratio,
    difference_blend,
    exclusion_blend,
)

unit = st.floats(0, 1, allow_nan=False)
colors = arrays(np.float64, (5, 3), elements=unit)
alphas = st.floats(-4, 4, allow_nan=False)


@given(colors, colors)
def test_identity_at_one(source: np.ndarray, background: np.ndarray) -> None:
    np.testing.assert_allclose(composite_extended(source, background, 1.0), source, atol=1e-15)


@given(colors, colors)
def test_background_at_zero(source: np.ndarray, background: np.ndarray) -> None:
    np.testing.assert_array_equal(composite_extended(source, background, 0.0), background)


@given(colors, colors, st.floats(0, 1))
def test_no_clipping_inside_unit_interval(s: np.ndarray, b: np.ndarray, a: float) -> None:
    np.testing.assert_array_equal(composite_extended(s, b, a), composite_raw(s, b, a))
    conventional = a * s + (1 - a) * b  # the paper's Eq. 2 form
    np.testing.assert_allclose(composite_extended(s, b, a), conventional, atol=1e-15)


@given(colors, colors, alphas)
def test_unclipped_difference_is_scaled(s: np.ndarray, b: np.ndarray, a: float) -> None:
    np.testing.assert_allclose(composite_raw(s, b, a) - b, a * (s - b), atol=1e-14)


@given(colors, colors, st.floats(1, 8))
def test_background_distance_never_shrinks_for_a_ge_1(
    s: np.ndarray, b: np.ndarray, a: float
) -> None:
    out = composite_extended(s, b, a)
    assert (np.abs(out - b) >= np.abs(s - b) - 1e-15).all()


@given(colors, st.floats(1, 8), st.sampled_from([0.0, 1.0]))
def test_no_contrast_decrease_on_black_or_white(s: np.ndarray, a: float, level: float) -> None:
    bg = np.full(3, level)
    before = contrast_ratio(s, bg)
    after = contrast_ratio(composite_extended(s, bg, a), bg)
    assert (after >= before - 1e-10).all()


@given(colors, colors, alphas)
def test_output_is_in_gamut(s: np.ndarray, b: np.ndarray, a: float) -> None:
    out = composite_extended(s, b, a)
    assert ((out >= 0) & (out <= 1)).all()


def test_alpha_broadcasts_over_leading_shape() -> None:
    s = np.full((2, 3, 3), 0.25)
    b = np.zeros((1, 3, 3))
    out = composite_extended(s, b, np.array([[1.0, 2.0, 3.0]]))
    np.testing.assert_allclose(out[0, :, 0], [0.25, 0.5, 0.75])


@given(colors, colors, alphas)
def test_full_coverage_is_the_composite_and_zero_is_the_canvas(
    s: np.ndarray, b: np.ndarray, a: float
) -> None:
    ones, zeros = np.ones(5), np.zeros(5)
    np.testing.assert_allclose(composite_coverage(s, b, a, ones), composite_extended(s, b, a))
    np.testing.assert_allclose(composite_coverage(s, b, a, zeros), b)


def test_coverage_mixes_after_clipping() -> None:
    # Coverage must not be folded into the coefficient: q*clip(raw) != clip(b + q*a*(s-b)).
    s, b = np.array([0.9, 0.5, 0.1]), np.array([0.2, 0.5, 0.8])
    half = composite_coverage(s, b, 3.0, np.array(0.5))
    np.testing.assert_allclose(half, 0.5 * composite_extended(s, b, 3.0) + 0.5 * b)
    assert not np.allclose(half, composite_extended(s, b, 1.5))


def test_controls() -> None:
    s, b = np.array([0.2, 0.9, 0.5]), np.array([0.6, 0.1, 0.5])
    np.testing.assert_allclose(difference_blend(s, b), [0.4, 0.8, 0.0])
    np.testing.assert_allclose(exclusion_blend(s, b), [0.56, 0.82, 0.5])
