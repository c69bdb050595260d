"""CSS Color 4 parsing and the gamut policies, against colour-science conversions."""

from __future__ import annotations

import warnings

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from alpha_audit.color import delta_e_2000, parse_color, srgb_decode
from alpha_audit.color.css import color_from_components, parse_css_color
from alpha_audit.errors import ColorSyntaxError

with warnings.catch_warnings():
    warnings.simplefilter("ignore")
    import colour

D50 = colour.CCS_ILLUMINANTS["CIE 1931 2 Degree Standard Observer"]["D50"]
RGB = np.array([0.5, 0.45, 0.4])
XYZ = np.array([0.3, 0.32, 0.35])

# Independent references from colour-science.  Tolerance 2e-4: the two libraries
# round the D50/D65 white points and the RGB matrices differently (CSS Color 4
# derives them from the chromaticities; colour-science keeps published digits).
REFERENCES = [
    ("srgb-linear", RGB, colour.models.eotf_inverse_sRGB(RGB)),
    (
        "display-p3",
        RGB,
        colour.RGB_to_RGB(RGB, "Display P3", "sRGB", None, True, True),
    ),
    (
        "a98-rgb",
        RGB,
        colour.RGB_to_RGB(RGB, "Adobe RGB (1998)", "sRGB", None, True, True),
    ),
    (
        "prophoto-rgb",
        RGB,
        colour.RGB_to_RGB(
            RGB,
            "ProPhoto RGB",
            "sRGB",
            "Bradford",
            apply_cctf_decoding=True,
            apply_cctf_encoding=True,
        ),
    ),
    # coloraide's rec2020 decodes with a pure 2.4 power (BT.1886), as the CSS
    # Color 4 editors' draft does; colour-science's BT.2020 CCTF is the camera OETF.
    (
        "rec2020",
        RGB,
        colour.RGB_to_RGB(RGB**2.4, "ITU-R BT.2020", "sRGB", apply_cctf_encoding=True),
    ),
    ("xyz-d65", XYZ, colour.XYZ_to_sRGB(XYZ)),
    ("xyz-d50", XYZ, colour.XYZ_to_sRGB(XYZ, D50, "Bradford")),
    (
        "lab",
        np.array([50.0, 20.0, -30.0]),
        colour.XYZ_to_sRGB(colour.Lab_to_XYZ([50.0, 20.0, -30.0], D50), D50, "Bradford"),
    ),
    (
        "lch",
        np.array([50.0, 36.0, 300.0]),
        colour.XYZ_to_sRGB(
            colour.Lab_to_XYZ(colour.LCHab_to_Lab([50.0, 36.0, 300.0]), D50), D50, "Bradford"
        ),
    ),
    (
        "oklab",
        np.array([0.6, 0.05, -0.05]),
        colour.XYZ_to_sRGB(colour.Oklab_to_XYZ([0.6, 0.05, -0.05])),
    ),
    (
        "oklch",
        np.array([0.6, 0.08, 200.0]),
        colour.XYZ_to_sRGB(colour.Oklab_to_XYZ(colour.models.LCHab_to_Lab([0.6, 0.08, 200.0]))),
    ),
    ("hsl", np.array([200.0, 50.0, 40.0]), colour.HSL_to_RGB([200 / 360, 0.5, 0.4])),
    ("hwb", np.array([200.0, 20.0, 30.0]), colour.HSV_to_RGB([200 / 360, 1 - 0.2 / 0.7, 0.7])),
]


@pytest.mark.parametrize(
    ("space", "components", "expected"), REFERENCES, ids=[r[0] for r in REFERENCES]
)
def test_colour_object_matches_colour_science(space, components, expected) -> None:
    got = color_from_components(space, components.tolist())
    np.testing.assert_allclose(got.encoded, expected, atol=2e-4)


@pytest.mark.parametrize(
    ("space", "components", "expected"), REFERENCES, ids=[r[0] for r in REFERENCES]
)
def test_css_string_equals_the_colour_object(space, components, expected) -> None:
    c = components.tolist()
    if space == "hsl":
        text = f"hsl({c[0]} {c[1]}% {c[2]}%)"
    elif space == "hwb":
        text = f"hwb({c[0]} {c[1]}% {c[2]}%)"
    elif space in ("lab", "lch", "oklab", "oklch"):
        text = f"{space}({c[0]} {c[1]} {c[2]})"
    else:
        text = f"color({space} {c[0]} {c[1]} {c[2]})"
    assert parse_css_color(text).encoded == color_from_components(space, c).encoded


PARSE = [
    ("#e73", (0xEE / 255, 0x77 / 255, 0x33 / 255)),
    ("#e73f", (0xEE / 255, 0x77 / 255, 0x33 / 255)),  # 4-digit hex, opaque
    ("#ee7733ff", (0xEE / 255, 0x77 / 255, 0x33 / 255)),
    ("hwb(0 0% 0%)", (1.0, 0.0, 0.0)),
    ("oklch(1 0 none)", (1.0, 1.0, 1.0)),  # achromatic with a none hue
    ("hsl(none 0% 50%)", (0.5, 0.5, 0.5)),
    ("color(srgb 0.25 none 1)", (0.25, 0.0, 1.0)),
    ("#ee773380", None),
    ("rgb(0 0 0 / 0.5)", None),
    ("color(display-p3 1 0 0 / 50%)", None),
    ("color(--oklch 0.5 0.1 20)", None),  # coloraide's own syntax is not CSS
    ("color(jzazbz 0.1 0 0)", None),
    ("hsl(0 100% 50%) extra", None),
    ("", None),
]


@pytest.mark.parametrize(("text", "expected"), PARSE)
def test_parse(text, expected) -> None:
    if expected is None:
        with pytest.raises(ColorSyntaxError):
            parse_color(text)
    else:
        np.testing.assert_allclose(parse_color(text), expected, atol=1e-12)


def test_alpha_allowed_where_it_means_an_opacity() -> None:
    assert parse_css_color("#ee773380", allow_alpha=True).alpha == pytest.approx(0x80 / 255)


P3_RED = "color(display-p3 1 0 0)"


def test_gamut_error_names_the_colour_and_the_policies() -> None:
    with pytest.raises(ColorSyntaxError, match=r"outside sRGB .*gamut: clip or gamut: map"):
        parse_color(P3_RED)


def test_gamut_clip_is_per_channel() -> None:
    c = parse_css_color(P3_RED, gamut="clip")
    assert not c.in_gamut and c.adjusted
    assert c.unmapped[0] > 1 and min(c.unmapped) < 0
    np.testing.assert_array_equal(c.encoded, np.clip(c.unmapped, 0, 1))
    expected = delta_e_2000(srgb_decode(c.unmapped), srgb_decode(c.encoded))
    assert c.delta_e == pytest.approx(float(expected))


def test_gamut_map_is_css_color_4_chroma_reduction() -> None:
    from coloraide import Color

    c = parse_css_color(P3_RED, gamut="map")
    ref = Color(P3_RED).fit("srgb", method="minde-chroma", pspace="oklch", jnd=0.02)
    np.testing.assert_allclose(c.encoded, np.clip(ref.convert("srgb")[:3], 0, 1), atol=1e-12)
    assert all(0 <= v <= 1 for v in c.encoded)
    # mapping keeps hue better than clipping: its OKLCH hue is nearer the original's
    orig = Color(P3_RED).convert("oklch")["hue"]
    mapped = Color("srgb", list(c.encoded)).convert("oklch")["hue"]
    clipped = Color("srgb", list(parse_css_color(P3_RED, gamut="clip").encoded)).convert("oklch")[
        "hue"
    ]
    assert abs(mapped - orig) < abs(clipped - orig)
    assert c.delta_e > 0


def test_in_gamut_colours_are_untouched_by_every_policy() -> None:
    for policy in ("clip", "map", "error"):
        c = parse_css_color("oklch(0.6 0.08 200)", gamut=policy)
        assert c.in_gamut and not c.adjusted and c.delta_e == 0.0
        assert c.encoded == tuple(np.clip(c.unmapped, 0, 1))


def test_unknown_policy() -> None:
    with pytest.raises(ColorSyntaxError, match="clip, map, error"):
        parse_css_color("#fff", gamut="squash")  # type: ignore[arg-type]


@given(st.tuples(*(st.floats(0, 1) for _ in range(3))))
def test_exact_css_form_round_trips(rgb) -> None:
    c = color_from_components("srgb", list(rgb))
    assert parse_color(c.css).tolist() == list(rgb)


def test_hex_stays_exact() -> None:
    for code in range(256):
        assert parse_color(f"#{code:02x}0000")[0] == code / 255
