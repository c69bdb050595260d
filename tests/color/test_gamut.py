"""Vectorised CSS Color 4 gamut mapping against coloraide's minde-chroma."""

from __future__ import annotations

import numpy as np
import pytest
from coloraide import Color

from alpha_audit.color.css import map_parsed, parse_css_color
from alpha_audit.color.gamut import map_to_srgb

# Same algorithm, same matrices: only float rounding may differ (observed ~1e-13).
TOLERANCE = 1e-9


def _reference(c: Color) -> np.ndarray:
    fitted = c.clone().fit("srgb", method="minde-chroma", pspace="oklch", jnd=0.02)
    return np.clip(fitted.convert("srgb").coords(nans=False), 0.0, 1.0)


def _random_colors(n: int, seed: int) -> list[Color]:
    rng = np.random.default_rng(seed)
    spaces = [
        lambda: Color("display-p3", list(rng.random(3))),
        lambda: Color("rec2020", list(rng.uniform(-0.05, 1.05, 3))),
        lambda: Color("oklch", [rng.uniform(0, 1.05), rng.uniform(0, 0.45), rng.uniform(0, 360)]),
        lambda: Color("lab", [rng.uniform(0, 100), *rng.uniform(-150, 150, 2)]),
    ]
    return [spaces[i % len(spaces)]() for i in range(n)]


def test_agrees_with_coloraide_on_random_colours() -> None:
    colors = _random_colors(1200, seed=12)
    unmapped = np.array([c.convert("srgb", norm=False).coords(nans=False) for c in colors])
    outside = np.any((unmapped < 0) | (unmapped > 1), axis=1)
    assert outside.sum() > 500  # the sample exercises the search, not only the clip
    ours = map_to_srgb(unmapped)
    reference = np.array(
        [
            _reference(c) if o else np.clip(u, 0, 1)
            for c, u, o in zip(colors, unmapped, outside, strict=True)
        ]
    )
    assert np.max(np.abs(ours - reference)) < TOLERANCE


def test_in_gamut_colours_are_returned_unchanged() -> None:
    rgb = np.random.default_rng(3).random((500, 3))
    assert np.array_equal(map_to_srgb(rgb), rgb)


def test_results_lie_in_srgb_and_keep_the_shape() -> None:
    rgb = np.array([[1.3, -0.2, 0.4], [0.1, 1.2, -0.3], [2.0, 2.0, 2.0], [-1.0, -1.0, -1.0]])
    out = map_to_srgb(rgb)
    assert out.shape == rgb.shape and np.all((out >= 0) & (out <= 1))
    np.testing.assert_array_equal(out[2], [1.0, 1.0, 1.0])  # lighter than white: white
    np.testing.assert_array_equal(out[3], [0.0, 0.0, 0.0])  # darker than black: black
    tiled = map_to_srgb(np.tile(rgb, (2, 3, 1, 1)))
    assert tiled.shape == (2, 3, 4, 3)
    # Matrix products of other sizes may round differently in the last bit.
    np.testing.assert_allclose(tiled[1, 2], out, rtol=0, atol=1e-15)
    assert map_to_srgb(rgb[0]).shape == (3,)


def test_nan_does_not_raise() -> None:
    out = map_to_srgb([[np.nan, 0.5, 0.5], [1.5, 0.0, 0.0]])
    assert np.all((out[1] >= 0) & (out[1] <= 1))


@pytest.mark.parametrize(
    "text",
    ["color(display-p3 1 0 0)", "oklch(0.7 0.3 140)", "color(rec2020 0 0 1)", "lab(50 120 -90)"],
)
def test_batch_equals_one_at_a_time_and_coloraide(text) -> None:
    (batched,) = map_parsed([parse_css_color(text, gamut="clip")])
    single = parse_css_color(text, gamut="map")
    assert batched.encoded == single.encoded and batched.gamut == "map"
    assert np.max(np.abs(np.array(single.encoded) - _reference(Color(text)))) < TOLERANCE
