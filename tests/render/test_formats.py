"""Renderers: every format renders, is pure and stable, and survives hostile names."""

from __future__ import annotations

import json
import math
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from alpha_audit.gate import evaluate
from alpha_audit.model import Canvas, Icon, IconSet, Theme
from alpha_audit.policy import Exemption, Policy
from alpha_audit.render import CheckFormat, RenderOptions, render_check
from alpha_audit.render.common import escape_markdown as escape_cell
from alpha_audit.render.github import escape_property
from alpha_audit.results import CheckReport
from alpha_audit.rows import audit
from alpha_audit.rules import Rule

BASE = Path("/repo")
HOSTILE = "evil|name\x07<b>@team\n::error::x%0A*"


def _report(name: str = "deep", policy: Policy | None = None) -> CheckReport:
    theme = Theme("brand", (Canvas("sun", "#ffff00"), Canvas("ink", "#000000")))
    icons = (
        Icon(name, BASE / "icons" / "deep.svg", "#0000cf", 1.4, color_line=7, alpha_line=8),
        Icon("pale", BASE / "icons" / "pale.svg", "#eeeeee", 2.0),
        Icon("paler", BASE / "icons" / "paler.svg", "#dddddd", 2.0),
    )
    iconset = IconSet("set", icons, path=BASE / "icons" / "iconset.yaml")
    result = audit(theme, iconset)
    policy = policy or Policy(rules=frozenset({Rule.LOSS, Rule.NEW_COLLISION}))
    return CheckReport(audits=(result,), gate=evaluate([result], policy))


OPTIONS = RenderOptions(width=100, base=BASE)


@pytest.mark.parametrize("fmt", list(CheckFormat))
def test_every_format_renders_deterministically(fmt: CheckFormat) -> None:
    report = _report()
    first = render_check(report, fmt, OPTIONS)
    assert first and first.endswith("\n")
    assert render_check(report, fmt, OPTIONS) == first


def test_json_gate_section() -> None:
    doc = json.loads(render_check(_report(), "json", OPTIONS))
    assert doc["schema"] == "alpha-audit.check/4"
    gate = doc["gate"]
    assert gate["passed"] is False and gate["counts"] == {"loss": 1, "new-collision": 1}
    collision, loss = gate["failures"]  # worst first: a collision leads a loss
    assert (loss["rule"], loss["icons"], loss["canvas"]) == ("loss", ["deep"], "sun")
    assert loss["canvases"] == ["sun"]
    assert loss["files"] == ["icons/deep.svg"] and loss["lines"] == [7, 8]
    assert [(p["file"], p["line"], p["what"]) for p in loss["locations"]] == [
        ("icons/iconset.yaml", 8, "alpha"),
        ("icons/iconset.yaml", 7, "colour"),
    ]
    assert loss["numbers"]["gain"] < 0
    assert collision["icons"] == ["pale", "paler"] and collision["numbers"]["output"] == "#ffffff"


def test_json_refuses_nan() -> None:
    from alpha_audit.render.common import dumps

    with pytest.raises(ValueError):
        dumps({"x": math.nan})


def test_junit_loads_and_shows_control_characters_as_escapes() -> None:
    text = render_check(_report(HOSTILE), "junit", OPTIONS)
    root = ET.fromstring(text.encode())
    assert root.get("tests") == "6" and root.get("failures") == "3"
    cases = root.findall(".//testcase")
    assert {c.get("classname") for c in cases} == {"set.sun", "set.ink"}
    names = {c.get("name") for c in cases}
    assert "evil|name\\x07<b>@team\n::error::x%0A*" in names  # BEL shown, the rest kept as text
    failure = next(c for c in cases if c.find("failure") is not None).find("failure")
    assert "loss" in failure.get("type") and "contrast_ref=" in failure.text


def test_junit_skips_exempted_findings() -> None:
    policy = Policy(exemptions=(Exemption(reason="brand yellow", canvas="sun"),))
    root = ET.fromstring(render_check(_report(policy=policy), "junit", OPTIONS))
    skipped = root.findall(".//skipped")
    assert [s.get("message") for s in skipped] == ["loss exempt: brand yellow"]


def test_sarif_points_at_icon_and_manifest_line() -> None:
    doc = json.loads(render_check(_report(), "sarif", OPTIONS))
    assert doc["version"] == "2.1.0"
    run = doc["runs"][0]
    ids = [r["id"] for r in run["tool"]["driver"]["rules"]]
    loss = next(r for r in run["results"] if r["ruleId"] == "AA001")
    assert ids[loss["ruleIndex"]] == "AA001" and loss["level"] == "error"

    def places(key: str) -> list[tuple[str, int]]:
        return [
            (
                loc["physicalLocation"]["artifactLocation"]["uri"],
                loc["physicalLocation"].get("region", {}).get("startLine"),
            )
            for loc in loss.get(key, [])
        ]

    # The loss is set by the alpha (line 8): that is the location; the colour's
    # line and the drawing are related places.
    assert places("locations") == [("icons/iconset.yaml", 8)]
    assert places("relatedLocations") == [("icons/iconset.yaml", 7), ("icons/deep.svg", 1)]
    assert loss["properties"]["canvas"] == "sun" and loss["partialFingerprints"]
    assert "uri" not in run["originalUriBaseIds"]["%SRCROOT%"]  # no local absolute path


def test_sarif_suppresses_exempted_findings() -> None:
    policy = Policy(exemptions=(Exemption(reason="brand yellow", icon="deep"),))
    run = json.loads(render_check(_report(policy=policy), "sarif", OPTIONS))["runs"][0]
    (loss,) = [r for r in run["results"] if r["ruleId"] == "AA001"]
    assert loss["suppressions"] == [{"kind": "external", "justification": "brand yellow"}]


def test_markdown_escapes_cells() -> None:
    text = render_check(_report(HOSTILE), "markdown", OPTIONS)
    row = next(line for line in text.splitlines() if " | loss | " in line)
    assert row.count(" | ") == 6  # seven cells: the pipe in the name is escaped
    assert "<b>@" not in text and "@team" not in text and "&#64;team" in text
    assert escape_cell("a|b\nc") == "a\\|b c"


def test_github_annotations_cannot_be_injected() -> None:
    text = render_check(_report(HOSTILE), "github", OPTIONS)
    lines = text.splitlines()
    assert all(line.startswith(("::error ", "::notice ", "::warning ")) for line in lines)
    loss = next(line for line in lines if "title=alpha-audit loss" in line)
    # At the manifest line that sets the alpha, not on the SVG (not in the diff).
    assert loss.startswith("::error file=icons/iconset.yaml,line=8,title=alpha-audit loss::evil")
    assert "%0A::error::x%250A" in loss
    assert escape_property("a:b,c") == "a%3Ab%2Cc"


def test_table_shows_gate_verdict() -> None:
    text = render_check(_report(), "table", OPTIONS)
    assert "Gate failed: 2 root cause(s)" in text and "loss: deep on sun" in text


def test_junit_fails_every_canvas_of_a_folded_root_cause() -> None:
    import xml.etree.ElementTree as ET

    theme = Theme("t", tuple(Canvas(n, c) for n, c in (("sun", "#ffff00"), ("lemon", "#ffff40"))))
    icons = (Icon("deep", BASE / "icons" / "deep.svg", "#0000cf", 1.4),)
    result = audit(theme, IconSet("set", icons))
    report = CheckReport(audits=(result,), gate=evaluate([result], Policy()))
    (finding,) = report.gate.failures
    assert finding.canvases == ("sun", "lemon")
    root = ET.fromstring(render_check(report, "junit", OPTIONS))
    failed = {
        case.get("classname") for case in root.iter("testcase") if case.find("failure") is not None
    }
    assert failed == {"set.sun", "set.lemon"}
