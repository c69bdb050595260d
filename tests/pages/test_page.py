"""Done when: on a real page (Lucide icons, Tailwind v4 colours, translucent chips over a
gradient, light and dark through prefers-color-scheme) every icon is found in every state and
its measured contrast equals an independent computation from the page's CSS within 0.05.

The independent computation uses coloraide only (not alpha-audit's maths): the gradient
colour at the icon's centre (interpolated in OKLab, as the page's CSS says), the chip
composited over it and the icon's colour over that (source-over in sRGB, as browsers
composite), each step rounded to 8 bits as a browser's buffers are; then WCAG contrast.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest
from coloraide import Color

from alpha_audit.load.iconset import load_iconset
from alpha_audit.observed import Basis
from alpha_audit.pages import (
    FolderSource,
    RenderConfig,
    audit_pages,
    state_matrix,
)
from screen_truth import within_a_code

TOLERANCE = 0.05
# The page's layout (page/index.html): which icon sits on which chip, and each theme's tokens.
CHIPS = {"bell": "icon", "search": "icon", "settings": "soft", "heart": "icon", "star": "soft"}
BARE = ("info", "check")
THEMES = {
    "light": {
        "from": "sky-200", "to": "violet-300", "chip": ("white", 0.6), "icon": ("sky-700", 1.0),
        "soft": ("slate-900", 0.7), "bare": ("indigo-800", 1.0),
    },
    "dark": {
        "from": "slate-800", "to": "indigo-900", "chip": ("slate-950", 0.5),
        "icon": ("sky-300", 1.0), "soft": ("white", 0.7), "bare": ("amber-200", 1.0),
    },
}  # fmt: skip
MAIN_WIDTH = 960


@pytest.fixture(scope="module")
def result(project: Path):
    config = RenderConfig(
        (FolderSource(project / "page"),),
        states=state_matrix(color_schemes=["light", "dark"]),
        root=project,
        workers=2,
    )
    return audit_pages(config, load_iconset(project / "icons/iconset.yaml"))


def _tokens(project: Path) -> dict[str, str]:
    text = (project / "page/theme.css").read_text()
    tokens = dict(re.findall(r"--color-([a-z0-9-]+):\s*([^;]+);", text))
    return {**tokens, "white": "#fff", "black": "#000"}


def _eight_bit(color: Color) -> Color:
    """What a browser's 8-bit sRGB buffer keeps of an opaque colour."""
    srgb = color.convert("srgb").fit("srgb", method="clip")
    return Color("srgb", [round(c * 255) / 255 for c in srgb.coords()])


def _over(top: Color, below: Color) -> Color:
    """Source-over in sRGB (CSS Compositing 1), kept to 8 bits."""
    return _eight_bit(Color.layer([top, below], space="srgb"))


def _colours(tokens: dict[str, str], theme: str, icon: str, x: float) -> tuple[Color, Color]:
    """The icon's colour and its backdrop at ``x`` (CSS px along the gradient), 8-bit."""
    t = THEMES[theme]
    gradient = Color.interpolate([tokens[t["from"]], tokens[t["to"]]], space="oklab")
    backdrop = _eight_bit(gradient(x / MAIN_WIDTH))
    if icon in CHIPS:
        name, alpha = t["chip"]
        backdrop = _over(Color(tokens[name]).set("alpha", alpha), backdrop)
        name, alpha = t[CHIPS[icon]]
    else:
        name, alpha = t["bare"]
    return _over(Color(tokens[name]).set("alpha", alpha), backdrop), backdrop


def _expected(tokens: dict[str, str], theme: str, icon: str, centre_x: float) -> float:
    drawn, backdrop = _colours(tokens, theme, icon, centre_x)
    return drawn.contrast(backdrop, method="wcag21")


def _codes(color: Color) -> np.ndarray:
    return np.array([round(c * 255) for c in color.coords()], dtype=float)


def test_every_icon_is_found_in_every_state(result):
    assert result.run.problems == ()
    for state in ("color-scheme:light", "color-scheme:dark"):
        found = sorted(p.icon for p in result.paints if p.state == state)
        assert found == sorted([*CHIPS, *BARE]), state


def test_measured_contrast_equals_an_independent_computation(result, project):
    tokens = _tokens(project)
    checked = 0
    for paint in result.paints:
        theme = paint.state.split(":")[1]
        x, _, w, _ = paint.box
        expected = _expected(tokens, theme, paint.icon, x + w / 2)
        assert paint.contrast_median == pytest.approx(expected, abs=TOLERANCE), (
            paint.icon,
            theme,
            paint.drawn,
            paint.behind,
        )
        checked += 1
    assert checked == 2 * (len(CHIPS) + len(BARE))


def test_the_gated_contrast_is_the_least_contrasting_area_within_a_code(result, project):
    """Over the gradient the gate takes the icon's least-contrasting area, never an edge pixel.

    The truth is the least contrast of the icon's colour over the page's backdrop at each
    device pixel column the icon spans, each within one 8-bit code (tests/screen_truth.py).
    """
    tokens = _tokens(project)
    for paint in result.paints:
        theme = paint.state.split(":")[1]
        x, _, w, _ = paint.box
        columns = [_colours(tokens, theme, paint.icon, c) for c in np.arange(x, x + w, 0.5)]
        ranges = [within_a_code(_codes(d), _codes(b)) for d, b in columns]
        low, high = min(r[0] for r in ranges), min(r[1] for r in ranges)
        assert paint.basis is Basis.DECLARED
        assert low <= paint.contrast <= high, (paint.icon, theme, paint.drawn, low, high)
