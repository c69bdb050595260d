"""Fold by the line that causes it: a set-wide ``alpha:`` failing every icon is one entry per
rule on that line in every CI report (GitHub, GitLab, SARIF, the pull-request comment)."""

from __future__ import annotations

import json
import re
import shutil
from collections import Counter
from pathlib import Path

import pytest
from typer.testing import CliRunner

from alpha_audit.cli import app

REPO = Path(__file__).resolve().parents[2]
MANIFEST = """\
name: Vibrant demo
icons: svg/*.svg
palette:
  orange:  "#ee7733"
  blue:    "#0077bb"
  cyan:    "#33bbee"
  magenta: "#ee3377"
  red:     "#cc3311"
  teal:    "#009988"
  grey:    "#bbbbbb"
color: cycle
alpha: {alpha}
sizes: [24]
"""
ALPHA_LINE = 12  # the set-wide alpha: above


@pytest.fixture(scope="module")
def reports(tmp_path_factory: pytest.TempPathFactory) -> dict[str, str]:
    """A manifest whose set-wide ``alpha:`` (0.85) fails every icon: every CI report."""
    project = tmp_path_factory.mktemp("fold")
    (project / ".git").mkdir()
    shutil.copytree(REPO / "examples/vibrant/svg", project / "svg")
    shutil.copy(REPO / "themes/paper16.yaml", project / "paper16.yaml")
    (project / "iconset.yaml").write_text(MANIFEST.format(alpha=0.85))
    (project / "alpha-audit.yaml").write_text("theme: paper16.yaml\niconset: iconset.yaml\n")
    args = ["check", "-f", "github", "-o", "gh.txt", "-f", "gitlab", "-o", "gl.json"]
    args += ["-f", "sarif", "-o", "a.sarif", "-f", "markdown", "-o", "pr.md", "-f", "json"]
    with pytest.MonkeyPatch.context() as mp:
        mp.chdir(project)
        result = CliRunner().invoke(app, args)
    assert result.exit_code == 1, result.output
    out = {name: (project / name).read_text() for name in ("gh.txt", "gl.json", "a.sarif", "pr.md")}
    out["json"] = result.stdout
    return out


def _failing_on_alpha_line(reports: dict[str, str]) -> Counter[str]:
    """Failing root causes per rule whose first location is the alpha: line (the JSON)."""
    doc = json.loads(reports["json"])
    return Counter(
        f["rule"]
        for f in doc["gate"]["failures"]
        if f["locations"] and f["locations"][0]["line"] == ALPHA_LINE
    )


def test_every_icon_fails_on_the_alpha_line(reports: dict[str, str]) -> None:
    failing = _failing_on_alpha_line(reports)
    assert failing["loss"] == 12  # every icon of the set: the case the reports fold


def test_github_annotates_the_alpha_line_once_per_rule(reports: dict[str, str]) -> None:
    lines = [ln for ln in reports["gh.txt"].splitlines() if ln.startswith("::error file=")]
    per_rule = Counter(
        re.search(r"title=alpha-audit ([\w-]+)", ln).group(1)  # type: ignore[union-attr]
        for ln in lines
        if f"file=iconset.yaml,line={ALPHA_LINE}," in ln
    )
    assert per_rule and max(per_rule.values()) == 1
    assert set(per_rule) == set(_failing_on_alpha_line(reports))
    (loss,) = [ln for ln in lines if "title=alpha-audit loss" in ln]
    assert "::12 icons (" in loss and "on 16 canvases; worst: " in loss
    assert "root cause(s) on " in reports["gh.txt"].splitlines()[-1]


def test_gitlab_has_one_issue_per_rule_on_the_alpha_line(reports: dict[str, str]) -> None:
    issues = json.loads(reports["gl.json"])
    places = Counter(
        (i["location"]["path"], i["location"]["lines"]["begin"], i["check_name"]) for i in issues
    )
    assert max(places.values()) == 1
    on_line = {c for (p, b, c) in places if (p, b) == ("iconset.yaml", ALPHA_LINE)}
    assert on_line == {f"alpha-audit/{r}" for r in _failing_on_alpha_line(reports)}
    assert len({i["fingerprint"] for i in issues}) == len(issues)


def test_sarif_has_one_result_per_rule_on_the_alpha_line_with_every_icon(
    reports: dict[str, str],
) -> None:
    results = json.loads(reports["a.sarif"])["runs"][0]["results"]
    failing = [r for r in results if r["level"] == "error" and "suppressions" not in r]

    def place(r: dict) -> tuple[str, int, str]:
        physical = r["locations"][0]["physicalLocation"]
        return physical["artifactLocation"]["uri"], physical["region"]["startLine"], r["ruleId"]

    assert max(Counter(place(r) for r in failing).values()) == 1
    (loss,) = [
        r
        for r in failing
        if place(r)[:2] == ("iconset.yaml", ALPHA_LINE) and r["properties"]["rootCauses"] == 12
    ]
    assert len(loss["properties"]["icons"]) == 12 and len(loss["properties"]["canvases"]) == 16


def test_the_comment_has_one_row_per_rule_on_the_alpha_line(reports: dict[str, str]) -> None:
    rows = [
        [c.strip() for c in re.split(r"(?<!\\)\|", ln)[1:-1]]
        for ln in reports["pr.md"].splitlines()
        if ln.startswith("| ") and f"iconset.yaml:{ALPHA_LINE}" in ln
    ]
    failing_rows = [r for r in rows if r[1] == f"iconset.yaml:{ALPHA_LINE}"]
    per_rule = Counter(r[3] for r in failing_rows)
    assert per_rule == Counter(dict.fromkeys(_failing_on_alpha_line(reports), 1))
    (loss,) = [r for r in failing_rows if r[3] == "loss"]
    assert loss[5].startswith("12 icons: ")


def test_findings_located_only_at_a_story_or_svg_file_never_fold() -> None:
    """Two icons of one story, each failing on its own: the story file at line 1 is where
    they are drawn, not a value they share, so each stays a root cause of its own."""
    from alpha_audit.findings import Finding
    from alpha_audit.model import Location
    from alpha_audit.render.lines import by_line
    from alpha_audit.rules import Rule

    story = Location(Path("stories/icons.stories.js"), 1, "story")
    found = [
        Finding(Rule.BELOW_THRESHOLD, "dark", "icons--toolbar", "#0d1117", (i,), "m",
                locations=(story,))
        for i in ("bell", "search")
    ]  # fmt: skip
    assert [g.icons for g in by_line(found)] == [("bell",), ("search",)]
    value = Location(Path("theme.css"), 12, "css-colour")
    shared = [Finding(f.rule, f.theme, f.iconset, f.canvas, f.icons, f.message,
                      locations=(value, story)) for f in found]  # fmt: skip
    assert [g.icons for g in by_line(shared)] == [("bell", "search")]
