"""The page audit's gate and reports on the real two-theme Storybook (tools/page_fixtures.py).

One library run of every story in both themes feeds the report checks; the CLI
runs (baseline written, accepted, then a new failure) audit two stories only.
The Storybook's CSS (``.storybook/theme.css``) is the independent source: the
dark theme's ``--danger`` is too dark on its surface (the alert fails in dark
only), and the chips and mask icons draw ``--accent`` where the manifest says
``#57606a`` (render drift), while the toolbar, sprite and light alert draw what
the manifest says.
"""

from __future__ import annotations

import json
import os
from pathlib import Path

import pytest
from typer.testing import CliRunner

from alpha_audit.cli import app
from alpha_audit.load.iconset import load_iconset
from alpha_audit.pages import RenderConfig, StorybookSource, audit_pages, page_report, state_matrix
from alpha_audit.policy import RENDER_POLICY
from alpha_audit.render import CheckFormat, RenderOptions
from alpha_audit.rules import RULES, Rule

THEMES = [[("theme", "light")], [("theme", "dark")]]
runner = CliRunner()


@pytest.fixture(scope="module")
def report(project: Path, icon_stories: StorybookSource):
    manifest = load_iconset(project / "icons/iconset.yaml")
    config = RenderConfig(
        (icon_stories,),
        states=state_matrix(THEMES),
        root=project,
        workers=2,
    )
    run, paints = audit_pages(config, manifest)
    return page_report(run, paints, RENDER_POLICY, manifest)


def test_the_dark_only_alert_fails_the_gate_with_its_story_theme_and_manifest_line(report, project):
    alert = [f for f in report.gate.failures if f.iconset == "icons--alert"]
    assert [(f.rule, f.theme, f.icons) for f in alert] == [
        (Rule.BELOW_THRESHOLD, "theme:dark", ("triangle-alert",))
    ]
    (f,) = alert
    where = [(loc.file.name, loc.line, loc.what) for loc in f.locations]
    # The page overrides the manifest's colour (--danger): the page's declaration leads
    # where it is found; the manifest's line (overrides: triangle-alert: {color: ...})
    # and the story file (index.json's importPath) follow.
    assert ("iconset.yaml", 6, "colour") in where
    # The line of the story's export (index.json's importPath and exportName).
    story = next(line for name, line, what in where if what == "story")
    lines = (project / "stories/icons.stories.js").read_text().splitlines()
    assert lines[story - 1].startswith("export const Alert")
    # The page's own declaration of the colour leads: the dark theme's --danger value.
    css = next(w for w in f.locations if w.what == "css-colour")
    assert css.span is not None and css.span.text.strip().lower() == "#6e1a1f"
    assert not report.gate.passed


def test_no_crops_are_cut_unless_a_report_asks_for_them(report):
    assert report.gate.failures and report.pages.crops == ()  # RenderConfig.crops is 0
    assert report.pages.crops_left_out == 0


def test_render_drift_fires_on_the_css_overrides_and_not_on_the_others(report):
    drifted = {(f.iconset, f.theme, f.icons[0]) for f in report.gate.warnings
               if f.rule is Rule.RENDER_DRIFT}  # fmt: skip
    light = {(s, i) for s, t, i in drifted if t == "theme:light"}
    # Light: chips and the mask draw --accent (#0969da), the <img> draws black (an SVG
    # image's currentColor); the toolbar, sprite and alert draw the manifest's colour.
    assert light == {("icons--chip", "check"), ("icons--chip", "info"),
                     ("icons--images", "heart"), ("icons--images", "star")}  # fmt: skip
    # Dark: every story overrides the manifest's (light) colours.
    dark = {s for s, t, _ in drifted if t == "theme:dark"}
    assert dark == {"icons--toolbar", "icons--chip", "icons--alert", "icons--sprite",
                    "icons--images"}  # fmt: skip
    assert all(not f.fails for f in report.gate.warnings)


def test_sarif_locates_the_failure_at_the_manifest_line_with_the_story_related(report, project):
    log = json.loads(CheckFormat.SARIF.renderer()(report, RenderOptions(base=project)))
    (run,) = log["runs"]
    alert = [r for r in run["results"] if r["properties"].get("story") == "icons--alert"
             and r["ruleId"] == RULES[Rule.BELOW_THRESHOLD].sarif_id]  # fmt: skip
    (result,) = alert
    places = [result["locations"][0], *result["relatedLocations"]]
    where = [(r["physicalLocation"]["artifactLocation"]["uri"],
              r["physicalLocation"]["region"]["startLine"]) for r in places]  # fmt: skip
    assert ("icons/iconset.yaml", 6) in where
    assert any(uri == "stories/icons.stories.js" and line > 1 for uri, line in where)
    props = result["properties"]
    assert (props["state"], props["dom_path"].endswith("svg")) == ("theme:dark", True)
    assert "theme:dark / icons--alert" in result["message"]["text"]
    assert result["level"] == "error" and "Fix:" in result["message"]["text"]
    ids = {r["id"] for r in run["tool"]["driver"]["rules"]}
    assert RULES[Rule.RENDER_DRIFT].sarif_id in ids


def test_the_comment_has_the_story_by_theme_matrix_and_the_failing_icons(report, project):
    text = CheckFormat.MARKDOWN.renderer()(report, RenderOptions(base=project))
    lines = text.splitlines()
    assert "| story or page | theme:light | theme:dark |" in lines
    assert "| icons--alert | pass | **1 failing** |" in lines
    assert "| icons--toolbar | pass | pass |" in lines
    row = next(line for line in lines if line.startswith("| triangle-alert |"))
    assert "theme:dark" in row and "#6e1a1f on #0d1117" in row
    assert "1.65:1" in row  # --danger #6e1a1f on the dark surface #0d1117, by the specs
    assert len(text) < 65_536


def _cli(project: Path, *args: str) -> tuple[int, str]:
    cwd = Path.cwd()
    os.chdir(project)
    try:
        result = runner.invoke(
            app,
            ["render", "storybook-static", "--globals", "theme:light", "--globals",
             "theme:dark", "--iconset", "icons/iconset.yaml", "--workers", "2", *args],
        )  # fmt: skip
    finally:
        os.chdir(cwd)
    return result.exit_code, result.output


def test_a_baseline_accepts_the_failure_and_a_new_one_still_fails(project):
    code, out = _cli(project, "--stories", "icons--alert", "--write-baseline", "render.json")
    assert code == 0, out
    entries = json.loads((project / "render.json").read_text())["entries"]
    assert entries == [{"theme": "theme:dark", "iconset": "icons--alert",
                        "rule": "below-threshold", "icons": ["triangle-alert"]}]  # fmt: skip
    code, out = _cli(project, "--stories", "icons--alert", "--baseline", "render.json")
    assert code == 0, out
    code, out = _cli(
        project, "--stories", "icons--alert", "--stories", "icons--images",
        "--baseline", "render.json", "-f", "json", "-o", "render-out.json",
    )  # fmt: skip
    assert code == 1, out
    gate = json.loads((project / "render-out.json").read_text())["gate"]
    assert [f["iconset"] for f in gate["failures"]] == ["icons--images"]  # the new one
    assert [f["iconset"] for f in gate["baselined"]] == ["icons--alert"]


@pytest.mark.parametrize("engine", ["firefox", "webkit"])
def test_firefox_and_webkit_audit_the_storybook_and_see_the_same_dark_failure(project, engine):
    """The probe runs in Firefox's isolated world too (no TypedArray read across its Xrays)."""
    from alpha_audit.browser import ENGINES

    if ENGINES[engine].find() is None:
        pytest.skip(f"{engine} is not installed")
    manifest = load_iconset(project / "icons/iconset.yaml")
    config = RenderConfig(
        (StorybookSource(project / "storybook-static", ("icons--alert",)),),
        states=state_matrix(THEMES),
        root=project,
        engines=(engine,),
        workers=1,
        timeout=120,  # a page state's limit, generous for a loaded machine
    )
    run, paints = audit_pages(config, manifest)
    assert list(run.problems) == [], run.problems
    worst = {(p.state, p.icon, p.match.value): p.contrast for p in paints}
    assert set(worst) == {
        ("theme:light", "triangle-alert", "data-attribute"),
        ("theme:dark", "triangle-alert", "data-attribute"),
    }
    assert worst[("theme:dark", "triangle-alert", "data-attribute")] < 3.0
    assert worst[("theme:light", "triangle-alert", "data-attribute")] >= 3.0


def test_a_globals_value_the_toolbar_does_not_offer_is_refused_naming_the_values(project):
    """theme:purple is no theme of the Storybook (addon-themes offers light and dark): an
    unstyled story would be audited without a word, so the run stops with exit 2."""
    cwd = Path.cwd()
    os.chdir(project)
    try:
        result = runner.invoke(
            app, ["render", "storybook-static", "--stories", "icons--alert", "--globals",
                  "theme:purple", "--workers", "1"],
        )  # fmt: skip
    finally:
        os.chdir(cwd)
    assert result.exit_code == 2, result.output
    assert "theme:purple" in result.output and "light, dark" in result.output
