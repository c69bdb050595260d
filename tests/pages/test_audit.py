"""Measured paints as paint rows, gated and fixed as check's (no browser).

Hand-made MeasuredPaint values go through ``page_report``: the rows' judged
contrast (the 8-bit pair that limits), the one folding, the fixes under the
run's policy and every renderer.  Expected contrasts and fixes are checked
against the specs (tests/helpers.py: CSS Color 4 decode, WCAG 2.2), not our code.
"""

from __future__ import annotations

import json
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from alpha_audit.baseline import parse_baseline
from alpha_audit.errors import UsageError
from alpha_audit.gate import baseline_document
from alpha_audit.load.iconset import load_iconset
from alpha_audit.model import Location
from alpha_audit.observed import UNMEASURED, MeasuredPaint, PageRun
from alpha_audit.pages import page_report
from alpha_audit.pages.config import render_rules
from alpha_audit.policy import RENDER_DRIFT_TOLERANCE, RENDER_POLICY, Policy
from alpha_audit.render import CheckFormat, RenderOptions
from alpha_audit.rules import Level, Rule
from helpers import measured_paint, spec_contrast, spec_decode, spec_hex


def paint(**changes: object) -> MeasuredPaint:
    """A red alert icon drawn as the manifest says (#cf222e) on white, passing (5.36:1)."""
    return measured_paint(**changes)


@pytest.fixture
def manifest(tmp_path: Path):
    (tmp_path / "svg").mkdir()
    for name in ("triangle-alert", "bell"):
        (tmp_path / "svg" / f"{name}.svg").write_text(
            '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 24 24"><path d="M1 1h20"/></svg>'
        )
    (tmp_path / "iconset.yaml").write_text(
        "name: s\nicons: svg/*.svg\ncolor: '#57606a'\nalpha: 1\n"
        "overrides:\n  triangle-alert: {color: '#cf222e'}\n"
    )
    return load_iconset(tmp_path / "iconset.yaml")


def _run(*paints: MeasuredPaint) -> PageRun:
    pages = tuple(dict.fromkeys((p.source, p.state) for p in paints))
    engines = tuple(sorted({(p.engine, "1") for p in paints}))
    return PageRun((), (), len(pages), len(paints), len(paints), engines, pages)


def report(*paints: MeasuredPaint, manifest=None, policy: Policy = RENDER_POLICY, **kw):  # type: ignore[no-untyped-def]
    return page_report(_run(*paints), paints, policy, manifest, **kw)


@pytest.mark.parametrize(
    ("drawn", "behind"),
    [
        ("#767676", "#ffffff"),
        ("#777777", "#ffffff"),
        ("#6e1a1f", "#0d1117"),
        ("#959595", "#ffffff"),
    ],
)
def test_below_threshold_judges_the_8bit_pair_that_limits(drawn, behind) -> None:
    truth = spec_contrast(spec_hex(drawn), spec_hex(behind))  # #767676 on white: 4.54
    gate = report(paint(drawn=drawn, behind=behind), fixes=False).gate
    failing = [f.rule for f in gate.failures]
    assert failing == ([Rule.BELOW_THRESHOLD] if truth < 3.0 else [])


def test_a_failing_paint_is_named_by_state_story_icon_and_backdrop() -> None:
    p = paint(state="theme:dark", drawn="#6e1a1f", behind="#0d1117", contrast_worst=1.2,
              contrast_median=1.65)  # fmt: skip
    (f,) = report(p, fixes=False).gate.failures
    assert (f.theme, f.iconset, f.icons, f.canvas) == (
        "theme:dark", "icons--alert", ("div.alert > svg",), "#0d1117"
    )  # fmt: skip
    assert f.level is Level.FAIL and f.fails
    truth = spec_contrast(spec_hex("#6e1a1f"), spec_hex("#0d1117"))
    assert f.figures.contrast == pytest.approx(truth, abs=1e-12)  # the pair, not the worst pixel
    assert f.observed.contrast_worst == 1.2 and f.observed.contrast_median == 1.65
    assert f.observed.nearer.contrast == 5.36 and f.observed.source == "icons--alert"
    assert f.observed.state == "theme:dark" and f.observed.dom_path == "div.alert > svg"
    assert "#6e1a1f on #0d1117" in f.message and f"{truth:.2f}:1" in f.message


@pytest.mark.parametrize(
    ("drift", "fires"),
    [(RENDER_DRIFT_TOLERANCE + 0.01, True), (19.6, True), (RENDER_DRIFT_TOLERANCE, False),
     (0.0, False), (None, False)],
)  # fmt: skip
def test_render_drift_is_reported_above_the_tolerance(drift, fires) -> None:
    gate = report(paint(render_drift=drift), fixes=False).gate
    assert [(f.rule, f.level) for f in gate.warnings] == (
        [(Rule.RENDER_DRIFT, Level.WARN)] if fires else []
    )


def test_render_drift_fails_when_the_policy_says_so() -> None:
    policy = replace(RENDER_POLICY, rules=frozenset({Rule.RENDER_DRIFT}))
    (f,) = report(paint(render_drift=19.6, drawn="#6e1a1f"), policy=policy).gate.failures
    assert f.fails and f.figures.drift == 19.6 and "#6e1a1f" in f.message


def test_instances_of_one_icon_on_one_backdrop_fold_into_the_worst() -> None:
    # One declared colour; the second instance measured a code lighter (say, a
    # different subpixel offset): the row keeps the worse.
    a = paint(name="alert", dom_path="a > svg", drawn="#f4bbbb", behind="#ffffff")
    b = paint(name="alert", dom_path="b > svg", drawn="#f5bcbc", behind="#ffffff")
    c = paint(name="alert", dom_path="c > svg", drawn="#f4bbbb", behind="#eeeeee")
    a, b, c = (replace(x, declared="#f4bbbb") for x in (a, b, c))
    found = report(a, b, c, fixes=False)
    assert sum(len(r.entries) for r in found.audits) == 2  # one row per backdrop
    failures = found.gate.failures
    assert sorted((f.canvas, f.observed.dom_path) for f in failures) == [
        ("#eeeeee", "c > svg"),
        ("#ffffff", "b > svg"),  # the worse of the two on white
    ]


def test_a_mapped_icon_drawn_as_the_manifest_says_points_at_its_lines(manifest, tmp_path) -> None:
    story = tmp_path / "alert.stories.js"
    p = paint(icon="triangle-alert", name="triangle-alert", drawn="#cf222e", behind="#f08080",
              file=story)  # fmt: skip
    (f,) = report(p, manifest=manifest, fixes=False).gate.failures
    icon = next(i for i in manifest.icons if i.name == "triangle-alert")
    assert [(loc.file.name, loc.line, loc.what) for loc in f.locations] == [
        ("iconset.yaml", icon.color_line, "colour"),
        ("iconset.yaml", icon.alpha_line, "alpha"),
        ("alert.stories.js", 1, "story"),
    ]
    assert icon.color_line == 6  # the override's colour, the value a pull request edits


def test_a_css_override_points_at_the_page_first_and_the_manifest_after(manifest, tmp_path):
    story = tmp_path / "alert.stories.js"
    p = paint(icon="triangle-alert", name="triangle-alert", state="theme:dark", drawn="#6e1a1f",
              behind="#0d1117", render_drift=19.6, file=story)  # fmt: skip
    (f,) = report(p, manifest=manifest, fixes=False).gate.failures
    assert [(loc.file.name, loc.what) for loc in f.locations] == [
        ("iconset.yaml", "colour"),  # no CSS declaration known: the icon's source next
        ("alert.stories.js", "story"),
    ]
    css = Location(tmp_path / "theme.css", 17, "css-colour")
    (f,) = report(replace(p, locations=(css,)), manifest=manifest, fixes=False).gate.failures
    assert next((loc.file.name, loc.line, loc.what) for loc in f.locations) == (
        "theme.css",
        17,
        "css-colour",
    )  # the declaration that draws it leads


def test_an_unmapped_icon_points_at_its_story_only(tmp_path) -> None:
    p = paint(drawn="#eeaaaa", file=tmp_path / "a.js")
    (f,) = report(p, fixes=False).gate.failures
    assert [(loc.line, loc.what) for loc in f.locations] == [(1, "story")]


def test_a_paint_with_no_full_coverage_pixel_is_not_audited_never_failed() -> None:
    p = replace(paint(status=UNMEASURED, name="hairline"), drawn=None, drawn_linear=None,
                behind=None, behind_linear=None, contrast=None)  # fmt: skip
    gate = report(p, paint(name="bell"), fixes=False).gate
    assert gate.passed and not gate.failures
    assert [(f.rule, f.level, f.icons) for f in gate.warnings] == [
        (Rule.NOT_AUDITED, Level.WARN, ("hairline",))
    ]


def test_rules_of_check_are_refused_for_render() -> None:
    assert render_rules(frozenset({Rule.RENDER_DRIFT}), "x") == {Rule.RENDER_DRIFT}
    with pytest.raises(UsageError, match="loss is a rule of check"):
        render_rules(frozenset({Rule.LOSS}), "--fail-on")


def test_a_baseline_accepts_todays_failures_and_not_a_new_one(manifest) -> None:
    old = paint(icon="triangle-alert", name="triangle-alert", state="theme:dark",
                drawn="#6e1a1f", behind="#0d1117", render_drift=19.6)  # fmt: skip
    first = report(old, manifest=manifest, fixes=False)
    assert not first.gate.passed
    baseline = parse_baseline(json.dumps(baseline_document(first.gate)), Path("b.json"))
    again = report(old, manifest=manifest, baseline=baseline, fixes=False)
    assert again.gate.passed and len(again.gate.baselined) == 1
    new = paint(source="icons--chip", state="theme:dark", drawn="#6e1a1f", behind="#0d1117")
    worse = report(old, new, manifest=manifest, baseline=baseline, fixes=False)
    assert [f.iconset for f in worse.gate.failures] == ["icons--chip"]


def _css_over(colour: str, backdrop: str, opacity: float):  # type: ignore[no-untyped-def]
    """A browser's source-over of an opaque colour at ``opacity``, 8-bit (CSS Compositing)."""
    s = np.array([int(colour[k : k + 2], 16) for k in (1, 3, 5)]) / 255.0
    b = np.array([int(backdrop[k : k + 2], 16) for k in (1, 3, 5)]) / 255.0
    return spec_decode(np.rint((b + opacity * (s - b)) * 255.0) / 255.0)


def _css_least(colour: str, backdrop: str, opacity: float):  # type: ignore[no-untyped-def]
    """The engine reading nearest the backdrop: 8-bit alpha rounded down, each channel
    rounded towards the backdrop (what a fix must pass in every browser)."""
    s = np.array([int(colour[k : k + 2], 16) for k in (1, 3, 5)])
    b = np.array([int(backdrop[k : k + 2], 16) for k in (1, 3, 5)])
    alpha = np.floor(opacity * 255 + 1e-9)
    exact = b * 255 + alpha * (s - b)  # x 255: whole numbers, no float ties
    codes = np.where(s > b, np.floor_divide(exact, 255), -np.floor_divide(-exact, 255))
    return spec_decode(codes / 255.0)


def test_a_failing_mapped_icon_drawn_as_predicted_gets_an_alpha_and_colour_fix(manifest):
    # #cf222e on a pink chip: 2.07:1; alpha above 1 (linear) pushes it away from the pink.
    p = paint(icon="triangle-alert", name="triangle-alert", drawn="#cf222e", behind="#f08080")
    r = report(p, manifest=manifest)
    (fix,) = r.fixes
    assert fix.opacity is None  # the model's row: a coefficient, edited in the manifest
    assert fix.reach.alpha is not None and fix.reach.alpha > 1.0
    icon = next(i for i in manifest.icons if i.name == "triangle-alert")
    assert fix.nearest is not None and fix.line == icon.color_line
    from alpha_audit.color import composite_paint  # the paper's linear form, clipped

    pink = spec_hex("#f08080")
    for a, ok in ((fix.reach.alpha, True), (fix.reach.alpha - 0.001, False)):
        shown = composite_paint(icon.linear, pink, a, 1.0, "linear")
        from helpers import spec_ship

        assert (spec_contrast(spec_ship(shown), pink) >= 3.0) is ok


def test_an_opacity_wrapper_is_fixed_by_an_opacity_or_a_colour_at_that_opacity() -> None:
    # #57606a at opacity 0.5 over white: the browser draws #abb0b4 (G: 175.5 rounds to 176).
    drawn = "#abb0b4"
    assert np.allclose(_css_over("#57606a", "#ffffff", 0.5), spec_hex(drawn))
    p = paint(drawn=drawn, declared="#57606a", declared_opacity=0.5, name="bell")
    r = report(p)
    (f,) = r.gate.failures
    (fix,) = (r.fixes[k] for k in f.fixes)
    assert fix.opacity == 0.5 and fix.reach.alpha is not None
    needed = fix.reach.alpha * 0.5
    white = spec_hex("#ffffff")
    for shown in (_css_over, _css_least):  # the formula, and every engine's reading
        assert spec_contrast(shown("#57606a", "#ffffff", needed), white) >= 3.0
    # The smallest: one 8-bit alpha step less fails in some engine's reading.
    assert spec_contrast(_css_least("#57606a", "#ffffff", needed - 1 / 255), white) < 3.0
    assert fix.nearest is not None
    for shown in (_css_over, _css_least):
        assert spec_contrast(shown(fix.nearest.color, "#ffffff", 0.5), white) >= 3.0
    from alpha_audit.render.common import finding_fix

    said = finding_fix(f, r)
    assert f"opacity {needed:.4g} or above (now 0.5)" in said and "alpha" not in said


def test_a_css_override_is_fixed_on_the_colour_drawn_not_the_manifest(manifest):
    p = paint(icon="triangle-alert", name="triangle-alert", state="theme:dark", drawn="#6e1a1f",
              behind="#0d1117", render_drift=19.6)  # fmt: skip
    r = report(p, manifest=manifest)
    (fix,) = r.fixes
    assert fix.source == "#6e1a1f" and fix.opacity == 1.0 and fix.nearest is not None
    assert spec_contrast(spec_hex(fix.nearest.color), spec_hex("#0d1117")) >= 3.0
    assert r.gate.failures[0].fixes == (0,)


@pytest.mark.parametrize("fmt", list(CheckFormat))
def test_every_format_renders_a_page_report(fmt, manifest) -> None:
    p = paint(icon="triangle-alert", name="triangle-alert", state="theme:dark",
              drawn="#6e1a1f", behind="#0d1117", render_drift=19.6)  # fmt: skip
    text = fmt.renderer()(report(p, paint(), manifest=manifest), RenderOptions())
    assert "triangle-alert" in text


def test_below_threshold_is_off_in_check_and_fails_in_render() -> None:
    from alpha_audit.rules import RULES

    assert RULES[Rule.BELOW_THRESHOLD].default is Level.OFF
    assert RENDER_POLICY.level(Rule.BELOW_THRESHOLD) is Level.FAIL
    assert RENDER_POLICY.level(Rule.RENDER_DRIFT) is Level.WARN
    assert Policy().level(Rule.RENDER_DRIFT) is Level.OFF


def test_the_table_is_a_tree_of_story_state_and_icon_with_every_figure_whole(manifest) -> None:
    """At 80 columns a long story id and state keep their own lines; figures are never cut."""
    story = "design-system-components-navigation--toolbar-with-overflow-menu"
    paints = [
        paint(source=story, state="theme:dark", icon="triangle-alert", name="triangle-alert",
              drawn="#6e1a1f", behind="#0d1117", render_drift=19.6, box=(0, 0, 24, 24)),
        paint(source=story, state="theme:dark", name="bell", box=(30, 0, 24, 24)),
        paint(source=story, state="theme:light", name="bell"),
        paint(icon="triangle-alert", name="triangle-alert"),
    ]  # fmt: skip
    text = CheckFormat.TABLE.renderer()(report(*paints, manifest=manifest, fixes=False),
                                        RenderOptions(width=80))  # fmt: skip
    lines = text.splitlines()
    lines = lines[: next(k for k, line in enumerate(lines) if "page states" in line)]
    assert max(len(line) for line in lines) <= 80  # the table (findings' lines follow it)
    names = [line.split("  #")[0].strip() for line in lines if line.strip()]
    tree = [n for n in names if n in {"theme:light", "theme:dark", "bell", "triangle-alert",
                                       "icons--alert"}]  # fmt: skip
    assert tree == ["theme:dark", "triangle-alert", "bell", "theme:light",
                    "bell", "icons--alert", "theme:light", "triangle-alert"]  # fmt: skip
    first = next(line for line in lines if "#6e1a1f" in line)
    truth = spec_contrast(spec_hex("#6e1a1f"), spec_hex("#0d1117"))
    assert first.split() == ["triangle-alert", "#6e1a1f", "#0d1117", f"{truth:.2f}", "5.36",
                             "5.36", "19.60"]  # fmt: skip
    assert story in "".join(line.strip() for line in lines)  # wrapped, never cut


def test_hostile_page_names_never_reach_a_report_raw() -> None:
    """A page's id with a newline and a workflow command, ESC, BEL and RLO (issue 30)."""
    hostile = "x\n::error::owned\x1b[31m\x07\u202eevil"
    p = paint(name=hostile, source=hostile, dom_path=hostile, drawn="#eeaaaa")
    r = report(p)
    for fmt in CheckFormat:
        text = fmt.renderer()(r, RenderOptions())
        for line in text.splitlines():
            assert not line.lstrip().startswith("::error::owned"), fmt
        assert "\x1b" not in text and "\x07" not in text and "\u202e" not in text, fmt
