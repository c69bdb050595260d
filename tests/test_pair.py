"""``pair`` is a one-icon audit: the same contrast and verdict as ``check``, and as the specs.

The reference here is written from the specs, not from alpha-audit's code: the
paper's composite ``clip(Cb + a (Cs - Cb))`` in linear light, the CSS Color 4
sRGB transfer functions, 8-bit codes rounded half to even, the WCAG 2.2
relative luminance and contrast ratio.
"""

from __future__ import annotations

import numpy as np
import pytest

from alpha_audit.model import Canvas, Icon, IconSet, Theme
from alpha_audit.pair import pair_table
from alpha_audit.rows import audit
from helpers import spec_decode, spec_ship

LUMINANCE = np.array([0.2126, 0.7152, 0.0722])  # WCAG 2.2 relative luminance


def _shipped_contrast(codes_s: np.ndarray, codes_b: np.ndarray, alpha: np.ndarray) -> np.ndarray:
    """The spec's contrast of what ships for every (source, canvas, alpha), ``(s, b, a)``."""
    cs = spec_decode(codes_s / 255.0)[:, None, None, :]
    cb = spec_decode(codes_b / 255.0)[None, :, None, :]
    shown = spec_ship(cb + alpha[None, None, :, None] * (cs - cb))  # the paper's composite
    y_shown = shown @ LUMINANCE
    y_canvas = np.broadcast_to(cb, shown.shape) @ LUMINANCE  # 8-bit canvases ship as themselves
    return (np.maximum(y_shown, y_canvas) + 0.05) / (np.minimum(y_shown, y_canvas) + 0.05)


def _hex(codes: np.ndarray) -> list[str]:
    return ["#{:02x}{:02x}{:02x}".format(*c) for c in codes.tolist()]


@pytest.mark.parametrize(
    ("color", "canvas", "alpha", "contrast", "passes"),
    [
        ("#e8600a", "#0c3720", 0.7, 2.9954, False),  # 3.0013 as floats: the old pair said pass
        ("#e8600a", "#0c3720", 1.0, 3.8590, True),
        ("#000000", "#ffffff", 1.0, 21.0, True),
        ("#ee7733", "#ffffff", 1.0, 2.8681, False),
    ],
)
def test_pair_judges_what_ships(
    color: str, canvas: str, alpha: float, contrast: float, passes: bool
) -> None:
    (row,) = pair_table(color, [canvas], [alpha])
    assert row.contrast == pytest.approx(contrast, abs=5e-5)
    assert row.passes is passes and row.threshold == 3.0


def test_pair_and_check_agree_with_the_specs_on_100000_cases() -> None:
    """25 colours x 64 canvases x 64 alphas: ``pair``'s rows, ``check``'s rows and the specs.

    ``check``'s rows are one audit of 1,600 icons (every colour at every alpha) on a
    64-canvas theme; ``pair`` is asked colour by colour.
    """
    rng = np.random.default_rng(28)
    n_s, n_b, n_a = 25, 64, 64
    codes_s = rng.integers(0, 256, (n_s, 3))
    codes_b = rng.integers(0, 256, (n_b, 3))
    alphas = np.round(rng.uniform(0.0, 2.5, n_a), 4)
    sources, backgrounds = _hex(codes_s), _hex(codes_b)
    expected = _shipped_contrast(codes_s, codes_b, alphas)  # (s, b, a)

    paired = np.empty((n_s, n_b, n_a))
    verdict = np.empty((n_s, n_b, n_a), dtype=bool)
    for i, color in enumerate(sources):
        rows = pair_table(color, backgrounds, alphas.tolist())  # background-major
        paired[i] = np.array([r.contrast for r in rows]).reshape(n_b, n_a)
        verdict[i] = np.array([r.passes for r in rows]).reshape(n_b, n_a)

    theme = Theme("random", tuple(Canvas(f"c{j}", c) for j, c in enumerate(backgrounds)))
    icons = tuple(
        Icon(f"s{i}a{k}", f"s{i}a{k}.svg", color, float(a))
        for i, color in enumerate(sources)
        for k, a in enumerate(alphas)
    )
    checked = audit(theme, IconSet("random", icons))
    assert checked.contrast.size == n_s * n_b * n_a >= 100_000
    check_contrast = checked.contrast.reshape(n_s, n_a, n_b).transpose(0, 2, 1)
    check_passes = checked.passes.reshape(n_s, n_a, n_b).transpose(0, 2, 1)

    np.testing.assert_array_equal(paired, check_contrast)  # one judgement: bit for bit
    np.testing.assert_array_equal(verdict, check_passes)
    np.testing.assert_allclose(paired, expected, rtol=1e-12)
    np.testing.assert_array_equal(verdict, expected >= 3.0)
    # The float colours' contrast would have given other verdicts: the test can fail.
    floats = checked.contrast_float.reshape(n_s, n_a, n_b).transpose(0, 2, 1)
    assert np.count_nonzero((floats >= 3.0) != check_passes) > 0


def test_css_columns_are_the_css_pipelines_rows() -> None:
    """The browser columns are the same icon audited under pipeline css, to the code."""
    (row,) = pair_table("#ee7733", ["#ffffff"], [0.6])
    theme = Theme("t", (Canvas("paper", "#ffffff"),))
    result = audit(theme, IconSet("s", (Icon("i", "i.svg", "#ee7733", 0.6),)), pipeline="css")
    css = next(result.rows())
    assert (row.css_output, row.css_contrast) == (css.output, css.contrast)
    assert css.output == "#f5ad85" and css.contrast == pytest.approx(1.88, abs=5e-3)
