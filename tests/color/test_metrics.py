"""Luminance, WCAG contrast and CIEDE2000 against published references."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from alpha_audit.color import (
    composite_extended,
    contrast_ratio,
    delta_e_2000,
    delta_e_2000_lab,
    linear_to_lab,
    parse_color,
    relative_luminance,
    srgb_decode,
)

colors = arrays(np.float64, (4, 3), elements=st.floats(0, 1))

# Sharma, Wu & Dalal (2005), "The CIEDE2000 Color-Difference Formula", Table 1.
SHARMA = [
    ((50.0000, 2.6772, -79.7751), (50.0000, 0.0000, -82.7485), 2.0425),
    ((50.0000, 3.1571, -77.2803), (50.0000, 0.0000, -82.7485), 2.8615),
    ((50.0000, 2.8361, -74.0200), (50.0000, 0.0000, -82.7485), 3.4412),
    ((50.0000, -1.3802, -84.2814), (50.0000, 0.0000, -82.7485), 1.0000),
    ((50.0000, -1.1848, -84.8006), (50.0000, 0.0000, -82.7485), 1.0000),
    ((50.0000, -0.9009, -85.5211), (50.0000, 0.0000, -82.7485), 1.0000),
    ((50.0000, 0.0000, 0.0000), (50.0000, -1.0000, 2.0000), 2.3669),
    ((50.0000, -1.0000, 2.0000), (50.0000, 0.0000, 0.0000), 2.3669),
    ((50.0000, 2.4900, -0.0010), (50.0000, -2.4900, 0.0009), 7.1792),
    ((50.0000, 2.4900, -0.0010), (50.0000, -2.4900, 0.0010), 7.1792),
    ((50.0000, 2.4900, -0.0010), (50.0000, -2.4900, 0.0011), 7.2195),
    ((50.0000, 2.4900, -0.0010), (50.0000, -2.4900, 0.0012), 7.2195),
    ((50.0000, -0.0010, 2.4900), (50.0000, 0.0009, -2.4900), 4.8045),
    ((50.0000, -0.0010, 2.4900), (50.0000, 0.0010, -2.4900), 4.8045),
    ((50.0000, -0.0010, 2.4900), (50.0000, 0.0011, -2.4900), 4.7461),
    ((50.0000, -0.0010, 2.4900), (50.0000, 0.0012, -2.4900), 4.7461),
    ((50.0000, 2.5000, 0.0000), (50.0000, 0.0000, -2.5000), 4.3065),
    ((50.0000, 2.5000, 0.0000), (73.0000, 25.0000, -18.0000), 27.1492),
    ((50.0000, 2.5000, 0.0000), (61.0000, -5.0000, 29.0000), 22.8977),
    ((50.0000, 2.5000, 0.0000), (56.0000, -27.0000, -3.0000), 31.9030),
    ((50.0000, 2.5000, 0.0000), (58.0000, 24.0000, 15.0000), 19.4535),
    ((50.0000, 2.5000, 0.0000), (50.0000, 3.1736, 0.5854), 1.0000),
    ((50.0000, 2.5000, 0.0000), (50.0000, 3.2972, 0.0000), 1.0000),
    ((50.0000, 2.5000, 0.0000), (50.0000, 1.8634, 0.5757), 1.0000),
    ((50.0000, 2.5000, 0.0000), (50.0000, 3.2592, 0.3350), 1.0000),
    ((60.2574, -34.0099, 36.2677), (60.4626, -34.1751, 39.4387), 1.2644),
    ((63.0109, -31.0961, -5.8663), (62.8187, -29.7946, -4.0864), 1.2630),
    ((61.2901, 3.7196, -5.3901), (61.4292, 2.2480, -4.9620), 1.8731),
    ((35.0831, -44.1164, 3.7933), (35.0232, -40.0716, 1.5901), 1.8645),
    ((22.7233, 20.0904, -46.6940), (23.0331, 14.9730, -42.5619), 2.0373),
    ((36.4612, 47.8580, 18.3852), (36.2715, 50.5065, 21.2231), 1.4146),
    ((90.8027, -2.0831, 1.4410), (91.1528, -1.6435, 0.0447), 1.4441),
    ((90.9257, -0.5406, -0.9208), (88.6381, -0.8985, -0.7239), 1.5381),
    ((6.7747, -0.2908, -2.4247), (5.8714, -0.0985, -2.2286), 0.6377),
    ((2.0776, 0.0795, -1.1350), (0.9033, -0.0636, -0.5514), 0.9082),
]


def test_ciede2000_matches_sharma_table() -> None:
    lab1 = np.array([p[0] for p in SHARMA])
    lab2 = np.array([p[1] for p in SHARMA])
    expected = np.array([p[2] for p in SHARMA])
    # The table is printed to 4 decimals; every pair, including the 180-degree
    # hue-boundary pairs 13-16, must agree within half a unit of the last digit.
    np.testing.assert_allclose(delta_e_2000_lab(lab1, lab2), expected, atol=5e-5, rtol=0)
    np.testing.assert_allclose(delta_e_2000_lab(lab2, lab1), expected, atol=5e-5, rtol=0)


def test_ciede2000_tiled_to_n_dimensions() -> None:
    lab1 = np.array([p[0] for p in SHARMA])
    lab2 = np.array([p[1] for p in SHARMA])
    flat = delta_e_2000_lab(lab1, lab2)
    tiled = delta_e_2000_lab(np.tile(lab1, (2, 3, 1, 1)), np.tile(lab2, (2, 3, 1, 1)))
    assert tiled.shape == (2, 3, len(SHARMA))
    np.testing.assert_array_equal(tiled[1, 2], flat)


def test_lab_of_white_is_100_0_0() -> None:
    np.testing.assert_allclose(linear_to_lab([1.0, 1.0, 1.0]), [100, 0, 0], atol=1e-9)


def test_lab_of_srgb_primaries() -> None:
    # CIELAB (D65) of the sRGB primaries as commonly tabulated (Lindbloom, 2
    # decimals, from a 4-digit matrix; the exact CSS matrix moves blue's b* by 0.02).
    got = linear_to_lab(np.eye(3))
    expected = [[53.24, 80.09, 67.20], [87.73, -86.18, 83.18], [32.30, 79.19, -107.86]]
    np.testing.assert_allclose(got, expected, atol=0.03)


def test_matrix_maps_white_to_d65() -> None:
    from alpha_audit.color.metrics import D65_XY, LINEAR_SRGB_TO_XYZ

    x, y = D65_XY
    np.testing.assert_allclose(
        LINEAR_SRGB_TO_XYZ.sum(axis=1), [x / y, 1, (1 - x - y) / y], atol=1e-15
    )


@given(colors)
def test_ciede2000_of_a_colour_with_itself_is_zero(c: np.ndarray) -> None:
    np.testing.assert_allclose(delta_e_2000(c, c), 0, atol=1e-9)


def test_luminance_weights() -> None:
    np.testing.assert_array_equal(relative_luminance(np.eye(3)), [0.2126, 0.7152, 0.0722])


@given(colors, colors)
def test_contrast_is_symmetric_and_at_least_one(a: np.ndarray, b: np.ndarray) -> None:
    np.testing.assert_array_equal(contrast_ratio(a, b), contrast_ratio(b, a))
    assert (contrast_ratio(a, b) >= 1).all()
    np.testing.assert_array_equal(contrast_ratio(a, a), 1)


def test_black_on_white_is_21() -> None:
    assert float(contrast_ratio([0, 0, 0], [1, 1, 1])) == 21.0


@pytest.mark.parametrize(("alpha", "expected"), [(1.0, 10.2773), (1.1, 9.8118), (1.4, 8.6379)])
def test_papers_worst_case(alpha: float, expected: float) -> None:
    # Section 4: dark blue (0, 0, 0.8125) on yellow (1, 1, 0) loses contrast as
    # red and green clip below zero while blue keeps rising.
    source, background = srgb_decode([0, 0, 0.8125]), srgb_decode([1, 1, 0])
    out = composite_extended(source, background, alpha)
    assert float(contrast_ratio(out, background)) == pytest.approx(expected, abs=5e-5)


def test_issue_reference_row() -> None:
    # Vibrant orange on white at 1.1, the row given in the check JSON spec.
    s, b = srgb_decode(parse_color("#ee7733")), np.ones(3)
    assert float(contrast_ratio(s, b)) == 2.868083650384096
    assert float(contrast_ratio(composite_extended(s, b, 1.1), b)) == 3.4733853122940994
