"""Reports point at the line of the design token that sets a colour (issue 12)."""

from __future__ import annotations

import json
from pathlib import Path

from alpha_audit.load.config import ProjectConfig, load_config
from alpha_audit.pipeline import check_project
from alpha_audit.policy import Policy
from alpha_audit.render import CheckFormat, RenderOptions
from alpha_audit.rules import Rule

REPO = Path(__file__).resolve().parents[2]
EXAMPLE = REPO / "examples/tokens"


def _line_of(path: Path, needle: str) -> int:
    """1-based line of the first line containing ``needle`` (an independent locator)."""
    lines = path.read_text().splitlines()
    return next(n for n, text in enumerate(lines, 1) if needle in text)


def _report():
    project = load_config(EXAMPLE / "alpha-audit.yaml")
    # threshold 21: every icon x canvas is below it, so every icon has a finding.
    policy = Policy(rules=frozenset({Rule.BELOW_THRESHOLD}))
    return check_project(
        ProjectConfig(
            iconsets=project.iconsets, policy=policy, threshold=21.0, tokens=project.tokens
        )
    )


def test_findings_carry_the_token_lines_of_icon_colour_and_canvas() -> None:
    report = _report()
    base = EXAMPLE / "base.tokens.json"
    light = EXAMPLE / "light.tokens.json"
    red = (base, _line_of(base, '"red": {'))  # the alias chain ends at palette.red
    white = (base, _line_of(base, '"white":'))  # color.bg.canvas -> palette.white
    found = [
        f
        for f in report.gate.findings
        if f.icons == ("alert",) and "color.bg.canvas" in f.canvases and "light" in f.iconset
    ]
    assert found, "the light mode's alert on the canvas must fail threshold 21"
    # The icon's colour first, then the tokens of the canvases it fails on.
    assert found[0].sources[0] == red and white in found[0].sources
    assert light not in {p for p, _ in found[0].sources}  # the alias is not where it is set


def test_sarif_locations_start_at_the_token_line_as_relative_uris() -> None:
    report = _report()
    text = CheckFormat.SARIF.renderer()(report, RenderOptions(base=REPO))
    results = json.loads(text)["runs"][0]["results"]
    base = EXAMPLE / "base.tokens.json"
    alert = next(
        r
        for r in results
        if r["properties"]["icons"] == ["alert"]
        and "color.bg.canvas" in r["properties"]["canvases"]
        and "light" in r["properties"]["iconset"]
    )
    first = alert["locations"][0]["physicalLocation"]
    assert first["artifactLocation"] == {
        "uri": "examples/tokens/base.tokens.json",
        "uriBaseId": "%SRCROOT%",
    }
    assert first["region"]["startLine"] == _line_of(base, '"red": {')
    for r in results:  # never an absolute path of this machine
        for loc in r["locations"]:
            assert not loc["physicalLocation"]["artifactLocation"]["uri"].startswith("/")


def test_json_and_github_name_the_token_line() -> None:
    report = _report()
    base = EXAMPLE / "base.tokens.json"
    line = _line_of(base, '"red": {')
    doc = json.loads(CheckFormat.JSON.renderer()(report, RenderOptions(base=REPO)))
    findings = [f for f in doc["gate"]["failures"] if f["icons"] == ["alert"]]
    assert {"file": "examples/tokens/base.tokens.json", "line": line} in findings[0]["sources"]
    github = CheckFormat.GITHUB.renderer()(report, RenderOptions(base=REPO))
    assert f"file=examples/tokens/base.tokens.json,line={line}" in github
