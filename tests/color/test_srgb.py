"""sRGB transfer, 8-bit quantisation and colour parsing."""

from __future__ import annotations

import warnings

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from alpha_audit.color import (
    from_8bit,
    linear_to_hex,
    parse_color,
    srgb_decode,
    srgb_encode,
    to_8bit,
)
from alpha_audit.errors import ColorSyntaxError

with warnings.catch_warnings():
    warnings.simplefilter("ignore")
    from colour.models import eotf_inverse_sRGB, eotf_sRGB


def test_decode_matches_colour_science_on_every_8bit_code() -> None:
    # colour-science puts the decode break at 12.92 * 0.0031308, CSS Color 4 at
    # 0.04045; no 8-bit code lies between the two, so all 256 must agree.
    codes = np.arange(256) / 255
    np.testing.assert_allclose(srgb_decode(codes), eotf_sRGB(codes), rtol=0, atol=1e-15)


def test_encode_matches_colour_science() -> None:
    linear = np.linspace(0, 1, 10_001)
    np.testing.assert_allclose(srgb_encode(linear), eotf_inverse_sRGB(linear), atol=1e-15)


def test_css_color_4_breakpoints() -> None:
    assert srgb_decode(0.04045) == pytest.approx(0.04045 / 12.92, abs=0)
    assert srgb_encode(0.0031308) == pytest.approx(0.0031308 * 12.92, abs=0)


@given(st.floats(0, 1))
def test_encode_inverts_decode(v: float) -> None:
    # CSS Color 4's two breakpoints (0.04045 encoded, 0.0031308 linear) do not
    # meet exactly: just above 0.04045/12.92 the round trip is off by ~3e-8.
    seam = abs(v - 0.04045) < 1e-6
    assert float(srgb_encode(srgb_decode(v))) == pytest.approx(v, abs=1e-7 if seam else 1e-12)


def test_every_8bit_code_round_trips() -> None:
    codes = np.arange(256)
    assert (to_8bit(from_8bit(codes)) == codes).all()


def test_8bit_rounds_half_to_even() -> None:
    # 0.5/255 and 2.5/255 encoded are exact ties: half to even gives 0 and 2.
    ties = srgb_decode(np.array([0.5, 2.5, 3.5]) / 255)
    assert to_8bit(ties).tolist() == [0, 2, 4]


def test_8bit_clips_out_of_range() -> None:
    assert to_8bit([-0.2, 1.7, 0.5]).tolist() == [0, 255, 188]


def test_shape_is_kept() -> None:
    grid = np.random.default_rng(1).random((4, 5, 3))
    assert srgb_decode(grid).shape == (4, 5, 3)
    assert to_8bit(grid).shape == (4, 5, 3)


def test_nan_and_inf_do_not_raise() -> None:
    with np.errstate(invalid="ignore"):
        out = srgb_decode([np.nan, np.inf, -np.inf])
    assert np.isnan(out[0]) and np.isinf(out[1])


PARSE_CASES = [
    ("#ee7733", (0xEE, 0x77, 0x33)),
    ("#EE7733", (0xEE, 0x77, 0x33)),
    ("#e73", (0xEE, 0x77, 0x33)),
    ("  #0d1117 ", (0x0D, 0x11, 0x17)),
    ("rgb(238 119 51)", (238, 119, 51)),
    ("rgb(238, 119, 51)", (238, 119, 51)),
    ("rgb(100% 0% 50%)", (255, 0, 127.5)),
    ("white", (255, 255, 255)),
    ("RebeccaPurple", (0x66, 0x33, 0x99)),
    ("#ee773380", None),  # carries alpha
    ("#e738", None),
    ("rgba(1, 2, 3, 0.5)", None),
    ("rgb(1 2 3 / 50%)", None),
    ("rgb(256 0 0)", None),  # outside sRGB
    ("rgb(-1 0 0)", None),
    ("transparent", None),
    ("blurple", None),
    ("#12345", None),
    ("", None),
    ("hsl(0 100% 50%)", (255, 0, 0)),
    ("rgba(255 0 0 / 1)", (255, 0, 0)),
]


@pytest.mark.parametrize(("text", "expected"), PARSE_CASES)
def test_parse_color(text: str, expected: tuple[float, float, float] | None) -> None:
    if expected is None:
        with pytest.raises(ColorSyntaxError):
            parse_color(text)
    else:
        np.testing.assert_allclose(parse_color(text), np.array(expected) / 255, atol=1e-15)


def test_parse_error_says_what_is_allowed() -> None:
    with pytest.raises(ColorSyntaxError, match=r"#rrggbb.*CSS colour name"):
        parse_color("blurple")
    with pytest.raises(ColorSyntaxError, match="own alpha"):
        parse_color("#ee773380")


def test_non_string_is_refused() -> None:
    with pytest.raises(ColorSyntaxError):
        parse_color(0xEE7733)  # type: ignore[arg-type]


def test_linear_to_hex_round_trip() -> None:
    assert linear_to_hex(srgb_decode(parse_color("#0077bb"))) == "#0077bb"
