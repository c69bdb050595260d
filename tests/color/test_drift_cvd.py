"""Drift against colour-science's own CIEDE2000 route, hue shift, and Machado CVD matrices."""

from __future__ import annotations

import warnings

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from alpha_audit.color import (
    DEFICIENCIES,
    color_drift,
    composite_extended,
    composite_paint,
    cvd_matrix,
    hex_to_linear,
    hue_shift,
    linear_to_hex,
    oklch_degrees,
    simulate_cvd,
)

with warnings.catch_warnings():
    warnings.simplefilter("ignore")
    import colour

unit = st.floats(0, 1, allow_nan=False)
colors = arrays(np.float64, (6, 3), elements=unit)


def _colour_science_de2000(hex1: str, hex2: str) -> float:
    """Independent route: colour-science's sRGB decoding and its sRGB -> XYZ matrix."""
    labs = []
    for h in (hex1, hex2):
        rgb = np.array([int(h[i : i + 2], 16) for i in (1, 3, 5)]) / 255
        xyz = colour.sRGB_to_XYZ(rgb)
        labs.append(
            colour.XYZ_to_Lab(
                xyz, colour.CCS_ILLUMINANTS["CIE 1931 2 Degree Standard Observer"]["D65"]
            )
        )
    return float(colour.delta_E(labs[0], labs[1], method="CIE 2000"))


def test_slate_500_at_1_2_on_white_drifts_about_29_5() -> None:
    source = hex_to_linear("#64748b")
    displayed = composite_extended(source, hex_to_linear("#ffffff"), 1.2)
    assert linear_to_hex(displayed) == "#00195d"
    drift = float(color_drift(source, displayed))
    assert drift == pytest.approx(29.5, abs=0.05)
    # colour-science's rounded matrix and decoding agree to well within 0.1 here
    assert drift == pytest.approx(
        _colour_science_de2000("#64748b", linear_to_hex(displayed)), abs=0.1
    )


@pytest.mark.parametrize(
    ("hex1", "hex2"),
    [
        ("#bc4c00", "#d1242f"),
        ("#ee7733", "#f5ad85"),
        ("#0969da", "#1f6feb"),
        ("#808080", "#000000"),
    ],
)
def test_drift_matches_colour_science(hex1: str, hex2: str) -> None:
    got = float(color_drift(hex_to_linear(hex1), hex_to_linear(hex2)))
    assert got == pytest.approx(_colour_science_de2000(hex1, hex2), abs=0.1)


@given(colors, colors)
def test_drift_is_zero_at_alpha_one(source: np.ndarray, background: np.ndarray) -> None:
    for pipeline in ("linear", "css"):
        s = (
            source
            if pipeline == "linear"
            else colour.models.eotf_sRGB(
                np.rint(colour.models.eotf_inverse_sRGB(source) * 255) / 255
            )
        )
        displayed = composite_paint(s, background, 1.0, pipeline=pipeline)
        np.testing.assert_allclose(color_drift(s, displayed), 0.0, atol=1e-4)


def test_hue_shift_sign_wraps_and_achromatic() -> None:
    red, grey = hex_to_linear("#ff0000"), hex_to_linear("#808080")
    h_red, h_orange = oklch_degrees(red)[2], oklch_degrees(hex_to_linear("#ff8000"))[2]
    assert float(hue_shift(red, hex_to_linear("#ff8000"))) == pytest.approx(h_orange - h_red)
    # magenta (~328 deg) to red (~29 deg) is a short step forward across 0, not -299
    shift = float(hue_shift(hex_to_linear("#ff00ff"), red))
    assert 0 < shift < 90
    assert np.isnan(hue_shift(grey, red))
    assert np.isnan(hue_shift(red, np.zeros(3)))
    assert np.isnan(oklch_degrees(grey)[2])


@given(colors, colors)
def test_hue_shift_is_antisymmetric(a: np.ndarray, b: np.ndarray) -> None:
    forward, back = hue_shift(a, b), hue_shift(b, a)
    both = ~np.isnan(forward)
    np.testing.assert_array_equal(np.isnan(forward), np.isnan(back))
    # +-180 is one direction either way
    diff = (forward[both] + back[both] + 180) % 360 - 180
    np.testing.assert_allclose(diff, 0.0, atol=1e-9)


@pytest.mark.parametrize("deficiency", DEFICIENCIES)
def test_cvd_matrix_is_machado_severity_one(deficiency: str) -> None:
    name = {
        "protanopia": "Protanomaly",
        "deuteranopia": "Deuteranomaly",
        "tritanopia": "Tritanomaly",
    }
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the tritan caveat, documented in docs/model.md
        expected = colour.blindness.matrix_cvd_Machado2009(name[deficiency], 1.0)
    np.testing.assert_array_equal(cvd_matrix(deficiency), expected)
    # Machado et al. (2009), Table: protanopia severity 1.0, first row
    if deficiency == "protanopia":
        np.testing.assert_allclose(cvd_matrix(deficiency)[0], [0.152286, 1.052583, -0.204868])
    np.testing.assert_allclose(cvd_matrix(deficiency).sum(axis=1), 1.0, atol=1e-5)


@given(colors)
def test_cvd_keeps_shape_range_and_greys(c: np.ndarray) -> None:
    for deficiency in DEFICIENCIES:
        out = simulate_cvd(c, deficiency)
        assert out.shape == c.shape
        assert np.all((out >= 0) & (out <= 1))
    grey = np.repeat(c[:, :1], 3, axis=1)
    np.testing.assert_allclose(simulate_cvd(grey, "deuteranopia"), grey, atol=1e-5)


def test_protanopia_collapses_red_green() -> None:
    red, green = hex_to_linear("#d1242f"), hex_to_linear("#2da44e")
    normal = float(color_drift(red, green))
    seen = float(color_drift(simulate_cvd(red, "protanopia"), simulate_cvd(green, "protanopia")))
    assert seen < normal / 2


def test_unknown_deficiency_lists_valid_ones() -> None:
    with pytest.raises(ValueError, match="protanopia, deuteranopia, tritanopia"):
        simulate_cvd([0.5, 0.5, 0.5], "achromatopsia")  # type: ignore[arg-type]


def test_achromatic_threshold_separates_8bit_greys_from_near_greys() -> None:
    from alpha_audit.color import ACHROMATIC_CHROMA, from_8bit

    levels = np.arange(256)
    greys = np.repeat(levels[:, None], 3, axis=1)
    assert np.all(oklch_degrees(from_8bit(greys))[:, 1] <= ACHROMATIC_CHROMA)
    near = []
    for channel in range(3):
        for step in (-1, 1):
            c = greys.copy()
            c[:, channel] += step
            near.append(c[(c[:, channel] >= 0) & (c[:, channel] <= 255)])
    assert np.all(oklch_degrees(from_8bit(np.concatenate(near)))[:, 1] > ACHROMATIC_CHROMA)
