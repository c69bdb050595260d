"""Measured paints as findings, from hand-made MeasuredPaint values (no browser).

The rules' statements are the policy's (below-threshold: worst pixel under the
threshold; render-drift: CIEDE2000 above RENDER_DRIFT_TOLERANCE); these tests pin
what a finding of a page says and where it points.
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import pytest

from alpha_audit.errors import UsageError
from alpha_audit.gate import baseline_document
from alpha_audit.load.baseline import parse_baseline
from alpha_audit.load.iconset import load_iconset
from alpha_audit.pages.config import render_rules
from alpha_audit.pages.findings import RENDER_DRIFT_TOLERANCE, paint_findings
from alpha_audit.pages.measured import Coverage, IconMatch, MeasuredPaint, Prediction, RenderResult
from alpha_audit.pages.report import RENDER_POLICY, judge_pages
from alpha_audit.policy import Policy
from alpha_audit.render import RenderFormat, RenderOptions
from alpha_audit.rules import Level, Rule


def paint(**changes: object) -> MeasuredPaint:
    """A red alert icon drawn as the manifest says (#cf222e) on white, passing."""
    base = MeasuredPaint(
        source="icons--alert",
        source_kind="storybook",
        url="http://127.0.0.1:1/iframe.html?id=icons--alert",
        state="theme:light",
        engine="chromium",
        label="icons--alert [theme:light] div > svg",
        icon=None,
        match=IconMatch.NONE,
        element="svg",
        dom_path="div.alert > svg",
        paint="currentColor",
        kinds=("stroke",),
        drawn="#cf222e",
        drawn_linear=None,
        behind="#ffffff",
        behind_linear=None,
        around="#ffffff",
        around_linear=None,
        coverage=Coverage(100, 40, 60.0, 1.0, 0.6),
        contrast_worst=5.36,
        contrast_median=5.36,
        model_source="#cf222e",
        model_alpha=1.0,
        model_opacity=1.0,
        predictions=(
            Prediction("linear", "#cf222e", (0.6, 0.02, 0.03), 5.36, 0.0),
            Prediction("css", "#cf222e", (0.6, 0.02, 0.03), 5.36, 0.0),
        ),
        render_drift=0.0,
        box=(0.0, 0.0, 24.0, 24.0),
    )
    return replace(base, **changes)  # type: ignore[arg-type]


@pytest.fixture
def manifest(tmp_path: Path):
    (tmp_path / "svg").mkdir()
    (tmp_path / "svg" / "triangle-alert.svg").write_text(
        '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 24 24"><path d="M1 1h20"/></svg>'
    )
    (tmp_path / "iconset.yaml").write_text(
        "name: s\nicons: svg/*.svg\ncolor: '#57606a'\nalpha: 1\n"
        "overrides:\n  triangle-alert: {color: '#cf222e'}\n"
    )
    return load_iconset(tmp_path / "iconset.yaml")


@pytest.mark.parametrize(
    ("worst", "fires"), [(2.99, True), (1.0, True), (3.0, False), (3.01, False), (None, False)]
)
def test_below_threshold_is_the_worst_pixel_under_the_threshold(worst, fires) -> None:
    found = paint_findings([paint(contrast_worst=worst)], RENDER_POLICY)
    assert [f.rule for f in found] == ([Rule.BELOW_THRESHOLD] if fires else [])


def test_a_failing_paint_is_named_by_state_story_icon_and_backdrop() -> None:
    p = paint(state="theme:dark", drawn="#6e1a1f", behind="#0d1117", contrast_worst=1.63,
              contrast_median=1.65)  # fmt: skip
    (f,) = paint_findings([p], RENDER_POLICY)
    assert (f.theme, f.iconset, f.icons, f.canvas) == (
        "theme:dark", "icons--alert", ("div.alert > svg",), "#0d1117"
    )  # fmt: skip
    assert f.level is Level.FAIL and f.fails
    assert f.numbers["contrast"] == 1.63 and f.numbers["contrast_median"] == 1.65
    assert f.numbers["model_contrast"] == 5.36 and f.numbers["story"] == "icons--alert"
    assert f.numbers["state"] == "theme:dark" and f.numbers["dom_path"] == "div.alert > svg"
    assert "1.63:1" in f.message and "#0d1117" in f.message


@pytest.mark.parametrize(
    ("drift", "fires"),
    [(RENDER_DRIFT_TOLERANCE + 0.01, True), (19.6, True), (RENDER_DRIFT_TOLERANCE, False),
     (0.0, False), (None, False)],
)  # fmt: skip
def test_render_drift_is_reported_above_the_tolerance(drift, fires) -> None:
    found = paint_findings([paint(render_drift=drift, drawn="#6e1a1f")], RENDER_POLICY)
    assert [(f.rule, f.level) for f in found] == (
        [(Rule.RENDER_DRIFT, Level.WARN)] if fires else []
    )


def test_render_drift_fails_when_the_policy_says_so() -> None:
    policy = replace(RENDER_POLICY, rules=frozenset({Rule.RENDER_DRIFT}))
    (f,) = paint_findings([paint(render_drift=19.6, drawn="#6e1a1f")], policy)
    assert f.fails and f.numbers["drift"] == 19.6 and "#6e1a1f" in f.message


def test_instances_of_one_icon_fold_into_one_root_cause_with_the_worst_figures() -> None:
    a = paint(icon="triangle-alert", dom_path="a > svg", contrast_worst=2.5, behind="#eeeeee")
    b = paint(icon="triangle-alert", dom_path="b > svg", contrast_worst=1.5, behind="#dddddd")
    c = paint(icon="triangle-alert", state="theme:dark", contrast_worst=2.0)
    found = paint_findings([a, b, c], RENDER_POLICY)
    assert [(f.theme, f.canvas, f.canvases) for f in found] == [
        ("theme:light", "#dddddd", ("#eeeeee", "#dddddd")),
        ("theme:dark", "#ffffff", ("#ffffff",)),
    ]
    assert found[0].numbers["dom_path"] == "b > svg"  # the worst instance's


def test_a_mapped_icon_points_at_its_manifest_lines_then_the_story(manifest, tmp_path) -> None:
    story = tmp_path / "alert.stories.js"
    p = paint(icon="triangle-alert", contrast_worst=1.6, file=story)
    (f,) = paint_findings([p], RENDER_POLICY, manifest)
    icon = manifest.icons[0]
    assert [(loc.file.name, loc.line, loc.what) for loc in f.locations] == [
        ("iconset.yaml", icon.color_line, "colour"),
        ("iconset.yaml", icon.alpha_line, "alpha"),
        ("alert.stories.js", 1, "story"),
    ]
    assert icon.color_line == 6  # the override's colour, the value a pull request edits


def test_an_unmapped_icon_points_at_its_story_only(tmp_path) -> None:
    (f,) = paint_findings([paint(contrast_worst=1.6, file=tmp_path / "a.js")], RENDER_POLICY)
    assert [(loc.line, loc.what) for loc in f.locations] == [(1, "story")]
    assert f.manifest is None and f.files == ()


def test_rules_of_check_are_refused_for_render() -> None:
    assert render_rules(frozenset({Rule.RENDER_DRIFT}), "x") == {Rule.RENDER_DRIFT}
    with pytest.raises(UsageError, match="loss is a rule of check"):
        render_rules(frozenset({Rule.LOSS}), "--fail-on")


def _result(*paints: MeasuredPaint) -> RenderResult:
    pages = tuple(dict.fromkeys((p.source, p.state) for p in paints))
    return RenderResult(paints, (), (), len(pages), len(paints), (("chromium", "1"),), pages)


def test_a_baseline_accepts_todays_failures_and_not_a_new_one(manifest) -> None:
    old = paint(icon="triangle-alert", state="theme:dark", contrast_worst=1.6)
    report = judge_pages(_result(old), RENDER_POLICY, manifest, fixes=False)
    assert not report.gate.passed
    text = __import__("json").dumps(baseline_document(report.gate))
    baseline = parse_baseline(text, Path("b.json"))
    again = judge_pages(_result(old), RENDER_POLICY, manifest, baseline=baseline, fixes=False)
    assert again.gate.passed and len(again.gate.baselined) == 1
    new = paint(source="icons--chip", state="theme:dark", contrast_worst=2.0)
    worse = judge_pages(_result(old, new), RENDER_POLICY, manifest, baseline=baseline, fixes=False)
    assert [f.iconset for f in worse.gate.failures] == ["icons--chip"]


def test_a_failing_mapped_icon_drawn_as_predicted_gets_an_alpha_and_colour_fix(manifest):
    # #cf222e on a pink chip: 2.07:1; alpha above 1 (linear) pushes it away from the pink.
    p = paint(icon="triangle-alert", contrast_worst=2.07, behind="#f08080")
    (fix,) = judge_pages(_result(p), RENDER_POLICY, manifest).fixes
    assert fix.reach.alpha is not None and fix.reach.alpha > 1.0
    assert fix.nearest is not None and fix.line == manifest.icons[0].color_line
    from alpha_audit.color import composite_paint, contrast_ratio, hex_to_linear, shipped

    grey = hex_to_linear("#f08080")
    for a, ok in ((fix.reach.alpha, True), (fix.reach.alpha - 0.01, False)):
        shown = shipped(composite_paint(manifest.icons[0].linear, grey, a, 1.0, "linear"))
        assert bool(contrast_ratio(shown, grey) >= 3.0) is ok


def test_a_css_override_is_fixed_on_the_colour_drawn_not_the_manifest(manifest):
    p = paint(icon="triangle-alert", state="theme:dark", drawn="#6e1a1f", behind="#0d1117",
              contrast_worst=1.63, render_drift=19.6)  # fmt: skip
    report = judge_pages(_result(p), RENDER_POLICY, manifest)
    (fix,) = report.fixes
    assert fix.reach.alpha is None and fix.manifest is None and fix.source == "#6e1a1f"
    assert fix.nearest is not None
    from alpha_audit.color import contrast_ratio, hex_to_linear

    assert contrast_ratio(hex_to_linear(fix.nearest.color), hex_to_linear("#0d1117")) >= 3.0
    assert report.gate.failures[0].fixes == (0,)


@pytest.mark.parametrize("fmt", list(RenderFormat))
def test_every_render_format_renders_a_report(fmt, manifest) -> None:
    p = paint(icon="triangle-alert", state="theme:dark", contrast_worst=1.6, render_drift=19.6)
    text = fmt.renderer()(judge_pages(_result(p, paint()), RENDER_POLICY, manifest),
                          RenderOptions())  # fmt: skip
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
        paint(source=story, state="theme:dark", icon="triangle-alert",
              drawn="#6e1a1f", behind="#0d1117", contrast_worst=1.63, contrast_median=1.65),
        paint(source=story, state="theme:dark", icon="bell"),
        paint(source=story, state="theme:light", icon="bell"),
        paint(icon="triangle-alert"),
    ]  # fmt: skip
    report = judge_pages(_result(*paints), RENDER_POLICY, manifest, fixes=False)
    text = RenderFormat.TABLE.renderer()(report, RenderOptions(width=80))
    lines = text.splitlines()
    lines = lines[: next(k for k, line in enumerate(lines) if "page states" in line)]
    assert max(len(line) for line in lines) <= 80  # the table (findings' lines follow it)
    names = [line.split("  #")[0].strip() for line in lines if line.strip()]
    tree = [n for n in names if n in {"theme:light", "theme:dark", "bell", "triangle-alert",
                                       "icons--alert"}]  # fmt: skip
    assert tree == ["theme:dark", "triangle-alert", "bell", "theme:light",
                    "bell", "icons--alert", "theme:light", "triangle-alert"]  # fmt: skip
    first = next(line for line in lines if "#6e1a1f" in line)
    assert first.split() == ["triangle-alert", "#6e1a1f", "#0d1117", "1.63", "1.65", "5.36",
                             "5.36", "0.00"]  # fmt: skip
    assert story in "".join(line.strip() for line in lines)  # wrapped, never cut
