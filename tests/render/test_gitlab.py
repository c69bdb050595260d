"""GitLab Code Quality: the fields GitLab reads, unique fingerprints, relative paths."""

from __future__ import annotations

import json
from pathlib import Path

from alpha_audit.gate import evaluate
from alpha_audit.model import Canvas, Icon, IconProblem, IconSet, Theme
from alpha_audit.policy import Exemption, Policy
from alpha_audit.render import CheckFormat, RenderOptions, render_check
from alpha_audit.render.lines import by_line
from alpha_audit.results import CheckReport
from alpha_audit.rows import audit
from alpha_audit.rules import Rule
from helpers import solid_paints

ROOT = Path("/repo")
SEVERITIES = {"info", "minor", "major", "critical", "blocker"}


def _report(policy: Policy) -> CheckReport:
    light = Theme("light", (Canvas("white", "#ffffff"), Canvas("paper", "#f6f8fa")))
    dark = Theme("dark", (Canvas("ink", "#0d1117"),))
    icons = IconSet(
        "set",
        (
            Icon("a", ROOT / "icons/a.svg", "#ffcc00", 1.2, "warn", color_line=4, alpha_line=5),
            Icon("b", ROOT / "icons/b.svg", "#ffcc01", 1.2, "warm"),
            Icon("c", Path("/elsewhere/c.svg"), "#000000", 1.0),
        ),
        path=ROOT / "icons/iconset.yaml",
    )
    broken = (IconProblem("d", ROOT / "icons/d.svg", "not an SVG"),)
    audits = tuple(audit(t, icons, solid_paints(icons, broken)) for t in (light, dark))
    return CheckReport(audits=audits, gate=evaluate(audits, policy))


POLICY = Policy(
    rules=frozenset({Rule.BELOW_THRESHOLD, Rule.COLLISION, Rule.LOSS}),
    exemptions=(Exemption("decorative", canvas="paper", icon="b"),),
)


def _issues(policy: Policy = POLICY) -> tuple[CheckReport, list[dict]]:
    report = _report(policy)
    return report, json.loads(render_check(report, CheckFormat.GITLAB, RenderOptions(base=ROOT)))


def test_gitlab_issues_have_every_field_gitlab_reads() -> None:
    report, issues = _issues()
    assert isinstance(issues, list) and issues
    for issue in issues:
        assert isinstance(issue["description"], str) and issue["description"]
        assert issue["check_name"].startswith("alpha-audit/")
        assert issue["severity"] in SEVERITIES
        assert isinstance(issue["location"]["path"], str)
        assert not issue["location"]["path"].startswith("/")
        begin = issue["location"]["lines"]["begin"]
        assert isinstance(begin, int) and begin >= 1
    # One issue per failing line and rule, plus the broken icon once (a warning: info).
    failing = len(by_line(report.gate.failures))
    assert len(issues) == failing + 1 and failing < len(report.gate.failures)
    assert sum(i["severity"] == "info" for i in issues) == 1


def test_gitlab_fingerprints_are_unique_and_stable() -> None:
    _, issues = _issues()
    prints = [i["fingerprint"] for i in issues]
    assert len(set(prints)) == len(prints)
    _, again = _issues()
    assert [i["fingerprint"] for i in again] == prints


def test_gitlab_locations_point_at_the_colour_line() -> None:
    _, issues = _issues()
    on_a = [i for i in issues if i["description"].startswith("a on ")]
    assert on_a and all(
        i["location"] == {"path": "icons/iconset.yaml", "lines": {"begin": 4}} for i in on_a
    )
    # An icon whose colour is defaulted points at its SVG, line 1; outside the root: its name only.
    on_c = [i for i in issues if i["description"].startswith("c on ")]
    assert on_c and all(i["location"]["lines"]["begin"] == 1 for i in on_c)
    assert all(i["location"]["path"] == "c.svg" for i in on_c)


def test_gitlab_leaves_out_exempted_findings_and_names_fixes() -> None:
    report, issues = _issues()
    exempted = [f for f in report.gate.findings if f.exemption is not None]
    assert exempted
    descriptions = " ".join(i["description"] for i in issues)
    assert "b on paper" not in descriptions
    below = [i for i in issues if i["check_name"] == "alpha-audit/below-threshold"]
    assert below and all(
        "Fix: " in i["description"] for i in below if " on white" in i["description"]
    )


def test_gitlab_passing_report_is_an_empty_array() -> None:
    # Nothing reported either: a and b (#ffcc00, #ffcc01) are near-duplicates, a warning.
    _, issues = _issues(
        Policy(
            rules=frozenset({Rule.UNRENDERABLE}),
            warnings=frozenset(),
            exemptions=(Exemption("x", icon="d"),),
        )
    )
    assert issues == []
