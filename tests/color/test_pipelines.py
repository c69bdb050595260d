"""The css pipeline against hand-computed gamma-space blends, and both pipelines' shared limits."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from alpha_audit.color import (
    PIPELINES,
    composite_coverage,
    composite_css,
    composite_extended,
    composite_paint,
    from_8bit,
    hex_to_linear,
    linear_to_hex,
    srgb_decode,
    to_8bit,
)

unit = st.floats(0, 1, allow_nan=False)
colors = arrays(np.float64, (4, 3), elements=unit)
WHITE = hex_to_linear("#ffffff")


def _by_hand_css(source_hex: str, canvas_hex: str, alpha: float) -> str:
    """Integer codes blended as a browser does: c = round(cb + a (cs - cb)), half to even."""
    s = [int(source_hex[i : i + 2], 16) for i in (1, 3, 5)]
    b = [int(canvas_hex[i : i + 2], 16) for i in (1, 3, 5)]
    out = [round(cb + alpha * (cs - cb)) for cs, cb in zip(s, b, strict=True)]
    return "#" + "".join(f"{c:02x}" for c in out)


@pytest.mark.parametrize(
    ("source", "canvas", "alpha", "css", "linear"),
    [
        # the example: 238 + ... -> 244.8, 173.4, 132.6 in gamma space
        ("#ee7733", "#ffffff", 0.6, "#f5ad85", "#f5bdad"),
        ("#ee7733", "#000000", 0.25, "#3c1e0d", None),
        ("#0969da", "#0d1117", 0.3, "#0c2b52", None),
    ],
)
def test_css_blend_matches_hand_computation(
    source: str, canvas: str, alpha: float, css: str, linear: str | None
) -> None:
    assert _by_hand_css(source, canvas, alpha) == css
    got = composite_css(hex_to_linear(source), hex_to_linear(canvas), alpha)
    assert linear_to_hex(got) == css
    if linear is not None:
        lin = composite_extended(hex_to_linear(source), hex_to_linear(canvas), alpha)
        assert linear_to_hex(lin) == linear


@given(colors, colors, st.floats(0, 1))
def test_css_output_is_8bit(source: np.ndarray, background: np.ndarray, alpha: float) -> None:
    out = composite_css(source, background, alpha)
    np.testing.assert_array_equal(from_8bit(to_8bit(out)), out)


@given(colors, colors)
def test_pipelines_agree_at_zero_and_one(source: np.ndarray, background: np.ndarray) -> None:
    s8, b8 = from_8bit(to_8bit(source)), from_8bit(to_8bit(background))
    for alpha in (0.0, 1.0):
        css = composite_paint(s8, b8, alpha, pipeline="css")
        linear = composite_paint(s8, b8, alpha, pipeline="linear")
        np.testing.assert_array_equal(to_8bit(css), to_8bit(linear))


@pytest.mark.parametrize("alpha", [1.2, -0.1, 1.0000001])
def test_css_refuses_alpha_outside_unit_interval(alpha: float) -> None:
    with pytest.raises(ValueError, match=r"cannot be expressed in CSS"):
        composite_css(WHITE, WHITE, alpha)
    with pytest.raises(ValueError, match=r"cannot be expressed in CSS"):
        composite_paint(WHITE, WHITE, alpha, 0.5, pipeline="css")


def test_unknown_pipeline_lists_valid_ones() -> None:
    with pytest.raises(ValueError, match=r"use one of linear, css"):
        composite_paint(WHITE, WHITE, 1.0, pipeline="srgb")  # type: ignore[arg-type]
    assert PIPELINES == ("linear", "css")


@given(colors, colors, st.floats(-2, 3), st.floats(0, 1))
def test_linear_paint_is_the_coverage_form(
    source: np.ndarray, background: np.ndarray, alpha: float, opacity: float
) -> None:
    by_formula = (
        opacity * np.clip(background + alpha * (source - background), 0, 1)
        + (1 - opacity) * background
    )
    np.testing.assert_allclose(
        composite_paint(source, background, alpha, opacity), by_formula, atol=1e-15
    )
    np.testing.assert_array_equal(
        composite_paint(source, background, alpha, opacity),
        composite_coverage(source, background, alpha, opacity),
    )


@given(colors, colors, st.floats(0, 1), st.floats(0, 1))
def test_css_opacity_multiplies_alpha(
    source: np.ndarray, background: np.ndarray, alpha: float, opacity: float
) -> None:
    np.testing.assert_array_equal(
        composite_paint(source, background, alpha, opacity, pipeline="css"),
        composite_css(source, background, alpha * opacity),
    )


def test_css_keeps_leading_shape_and_does_not_mutate() -> None:
    s = np.tile(hex_to_linear("#ee7733"), (2, 3, 1))
    b = np.tile(WHITE, (2, 3, 1))
    before = s.copy()
    out = composite_css(s, b, np.full((2, 3), 0.6))
    assert out.shape == (2, 3, 3)
    np.testing.assert_array_equal(s, before)
    np.testing.assert_allclose(out[1, 2], srgb_decode(np.array([245, 173, 133]) / 255))


def test_css_blend_of_8bit_colours_rounds_ties_half_to_even() -> None:
    """Every 8-bit pair at alphas of two decimals, as integer codes blended by hand.

    Exact halves are common there (17 over 32 at 0.9 is 18.5): they round half to even,
    as the blend of the codes themselves does, never by the float noise of a colour
    taken to linear light and back.
    """
    from fractions import Fraction

    rng = np.random.default_rng(7)
    s = rng.integers(0, 256, (4000, 3))
    b = rng.integers(0, 256, (4000, 3))
    a = rng.integers(0, 101, 4000) / 100
    got = to_8bit(composite_css(srgb_decode(s / 255), srgb_decode(b / 255), a))
    exact = [
        [
            round(Fraction(int(cb)) + Fraction(round(100 * al), 100) * (int(cs) - int(cb)))
            for cs, cb in zip(si, bi, strict=True)
        ]
        for si, bi, al in zip(s, b, a, strict=True)
    ]
    np.testing.assert_array_equal(got, np.array(exact))
    assert (
        linear_to_hex(composite_css(hex_to_linear("#110000"), hex_to_linear("#200000"), 0.9))
        == "#120000"
    )
