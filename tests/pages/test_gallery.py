"""Done when: a real Storybook with many real Lucide icons at 16 and 24 px in two themes has
zero false failures, and its true failures are caught.

The Storybook is tests/pages/site: ``gallery--lucide`` draws 48 Lucide icons (chosen by a
rule, not by how they draw) at 16 and 24 px in three roles, ``gallery--faded`` a passing
colour under an ``opacity: 0.5`` wrapper, and the ``icons--*`` stories the rest (a colour
too dark in the dark theme only, an ``<img>`` that draws black, chips, a sprite, a mask).
The truth is computed here from the theme's CSS values as the build ships them
(tests/screen_truth.py: source-over on encoded sRGB, WCAG 2.2's ratio), never from what
alpha-audit measured.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np

from alpha_audit.observed import MEASURED, MeasuredPaint
from alpha_audit.pages import (
    RenderConfig,
    StorybookSource,
    audit_pages,
    page_report,
    state_matrix,
)
from screen_truth import css_colour, over, ratio, within_a_code

THRESHOLD = 3.0

THEMES = [[("theme", "light")], [("theme", "dark")]]
# Each paint's colour (a theme variable, or a literal), opacity and backdrop layers, bottom
# up, as .storybook/theme.css and the stories lay them out.
ROLES = {
    "plain": ("icon", 1.0, ("raised",)),
    "accent": ("accent", 1.0, ("raised",)),
    "chip": ("accent", 1.0, ("raised", "chip")),
    "faded": ("icon", 0.5, ("raised",)),
}
STORIES = {
    "icons--toolbar": ("icon", 1.0, ("raised",)),
    "icons--sprite": ("icon", 1.0, ("raised",)),
    "icons--chip": ("accent", 1.0, ("surface", "chip")),
    "icons--alert": ("danger", 1.0, ("surface",)),
}
IMAGES = {"img": ("#000000", 1.0, ("raised",)), "mask": ("accent", 1.0, ("raised",))}
# The true failures the fixture holds, by construction (story, theme, how many paints).
TRUE_FAILURES = {
    ("icons--alert", "theme:dark"): 1,  # --danger is too dark on the dark surface
    ("icons--images", "theme:dark"): 1,  # the <img> draws black (an SVG image's currentColor)
    ("gallery--faded", "theme:light"): 2,  # opacity 0.5 halves --icon's difference
    ("gallery--faded", "theme:dark"): 2,
}


def _themes(project: Path) -> dict[str, dict[str, str]]:
    """Each theme's custom properties, as the built CSS ships them."""
    css = "".join(p.read_text() for p in (project / "storybook-static/assets").glob("*.css"))
    out = {}
    for theme in ("light", "dark"):
        block = re.search(r'html\[data-theme="?' + theme + r'"?\]\s*\{([^}]*)\}', css)
        assert block, f"no {theme} block in the built CSS"
        out[theme] = dict(re.findall(r"--([a-z]+):\s*([^;]+)", block.group(1)))
    return out


def _role(paint) -> tuple[str, float, tuple[str, ...]]:
    if paint.source == "icons--images":
        return IMAGES[paint.element]
    if paint.source.startswith("gallery--"):
        found = re.search(r"#([a-z]+)-\d+-", paint.dom_path)
        assert found, paint.dom_path
        return ROLES[found.group(1)]
    return STORIES[paint.source]


def _truth(theme: dict[str, str], paint) -> tuple[np.ndarray, np.ndarray]:
    """The paint's colour at full coverage and its backdrop, 8-bit, from the CSS values."""
    colour, opacity, layers = _role(paint)
    behind = css_colour(theme[layers[0]])[0]
    for layer in layers[1:]:
        top, alpha = css_colour(theme[layer])
        behind = over(top, alpha, behind)
    codes = css_colour(colour if colour.startswith("#") else theme[colour])[0]
    return over(codes, opacity, behind), behind


def _passes(paint: MeasuredPaint) -> bool | None:
    """The paint's verdict from its gated contrast (None: could not measure)."""
    if paint.status != MEASURED or paint.contrast is None:
        return None
    return paint.contrast >= THRESHOLD


def _audit(
    engine: str, project: Path
) -> tuple[set[tuple[str, str]], list[tuple[MeasuredPaint, np.ndarray, np.ndarray]]]:
    """The (story, state) pairs the gate fails, and every paint of every story in both
    themes with its truth (colour, backdrop)."""
    config = RenderConfig(
        (StorybookSource(project / "storybook-static"),),
        states=state_matrix(THEMES),
        root=project,
        engines=(engine,),
        workers=2,
        timeout=120,
    )
    run, paints = audit_pages(config)
    assert run.problems == ()
    gate = page_report(run, paints, threshold=THRESHOLD, fixes=False).gate
    failing = {(f.iconset, f.theme) for f in gate.failures}
    themes = _themes(project)
    return failing, [(p, *_truth(themes[p.state.split(":")[1]], p)) for p in paints]


def test_zero_false_failures_and_every_true_failure_caught(engine, project):
    """One test per engine, so one audit per engine (a missing engine skips, or fails on CI).

    pytest-xdist may hand a module's tests to different workers, and each would audit
    the Storybook again.
    """
    gate_failing, audited = _audit(engine[0], project)
    # Many real icons: 48 distinct Lucide icons at 16 and 24 px in both themes.
    gallery = [p for p, _, _ in audited if p.source == "gallery--lucide"]
    names = {re.search(r"-(\d+)-([a-z0-9-]+)$", p.dom_path).groups() for p in gallery}
    assert len({name for _, name in names}) >= 40
    assert {size for size, _ in names} == {"16", "24"}
    assert len(gallery) == 2 * 2 * 48
    # No true pass fails, every true failure is caught.
    wrong = [
        (p.source, p.state, p.dom_path, round(ratio(drawn, behind), 3), p.contrast)
        for p, drawn, behind in audited
        if _passes(p) is not (ratio(drawn, behind) >= THRESHOLD)
    ]
    assert wrong == []
    failing: dict[tuple[str, str], int] = {}
    for p, _, _ in audited:
        if _passes(p) is False:
            failing[(p.source, p.state)] = failing.get((p.source, p.state), 0) + 1
    assert failing == TRUE_FAILURES
    # The gate (the paints as rows, judged as check's) fails exactly those stories and themes.
    assert gate_failing == set(TRUE_FAILURES)
    # Every paint measured, its gated contrast within one 8-bit code of its CSS values'.
    off = []
    for p, drawn, behind in audited:
        low, high = within_a_code(drawn, behind)
        if p.status != MEASURED or not low <= (p.contrast or 0) <= high:
            off.append((p.source, p.state, p.dom_path, str(p.status), p.contrast, low, high))
    assert off == []
