"""GitHub annotations within GitHub's limits, SARIF that leaks no path and points at lines."""

from __future__ import annotations

import json
import re
from collections.abc import Iterator
from pathlib import Path
from typing import Any
from urllib.parse import unquote

import pytest

from alpha_audit.gate import evaluate
from alpha_audit.load.config import ProjectConfig
from alpha_audit.model import Canvas, Icon, IconProblem, IconSet, Theme
from alpha_audit.policy import Policy
from alpha_audit.render import CheckFormat
from alpha_audit.render.common import RenderOptions
from alpha_audit.render.github import MAX_ANNOTATIONS
from alpha_audit.render.sarif import relative_uri
from alpha_audit.results import CheckReport
from alpha_audit.rows import audit
from alpha_audit.rules import RULES, Rule
from helpers import solid_paints

BASE = Path("/home/runner/work/design")
# A file name with every character a URI must encode: space, "#", "%", "?", a
# control character, a colon (a scheme in a first segment) and non-ASCII.
ODD = "a b#c%d?e\x01f:g é.svg"


def _many(n: int, *, color_line: int = 3, problems: int = 0) -> CheckReport:
    """``n`` icons that each lose contrast on one canvas (blue at alpha 1.6 on grey)."""
    theme = Theme("grey", (Canvas("mid", "#777777"),))
    icons = tuple(
        Icon(
            f"icon-{k}",
            BASE / "icons" / (ODD if k == 0 else f"i{k}.svg"),
            "#0000cc",
            1.6,
            color_line=color_line + k,
        )
        for k in range(n)
    )
    iconset = IconSet("set", icons, path=BASE / "icons" / "iconset.yaml")
    broken = tuple(
        IconProblem(f"broken-{k}", BASE / f"b{k}.svg", "not an SVG") for k in range(problems)
    )
    result = audit(theme, iconset, solid_paints(iconset, broken))
    policy = Policy(rules=frozenset({Rule.LOSS}))
    return CheckReport(audits=(result,), gate=evaluate([result], policy))


def _levels(text: str) -> list[str]:
    return [line.split(" ", 1)[0].split("::")[1] for line in text.splitlines()]


@pytest.mark.parametrize("n", [1, 9, 10, 30])
def test_github_errors_never_exceed_what_github_shows(n: int) -> None:
    report = _many(n, problems=14)
    assert len(report.gate.failures) == n
    text = CheckFormat.GITHUB.renderer()(report, RenderOptions(base=BASE))
    levels = _levels(text)
    assert levels.count("error") <= MAX_ANNOTATIONS == 10
    assert levels.count("warning") == MAX_ANNOTATIONS  # 14 warnings: 9 and a roll-up
    verdict = text.splitlines()[-1]
    assert verdict.startswith("::error title=alpha-audit::gate failed: ")
    annotated = sum(1 for line in text.splitlines() if line.startswith("::error file="))
    if n < MAX_ANNOTATIONS:
        assert annotated == n and "more finding" not in verdict
    else:
        assert annotated == MAX_ANNOTATIONS - 1
        assert f"{n - annotated} more line(s) not annotated" in verdict
    assert "5 more note(s): icons that could not be rendered" in text  # 14 - 9


def _strings(value: Any) -> Iterator[str]:
    if isinstance(value, dict):
        for k, v in value.items():
            yield k
            yield from _strings(v)
    elif isinstance(value, list):
        for v in value:
            yield from _strings(v)
    elif isinstance(value, str):
        yield value


def _sarif(report: CheckReport) -> dict[str, Any]:
    return json.loads(CheckFormat.SARIF.renderer()(report, RenderOptions(base=BASE)))


def _locations(doc: dict[str, Any]) -> list[dict[str, Any]]:
    """Every place a result names: its location and its related locations."""
    return [
        loc["physicalLocation"]
        for r in doc["runs"][0]["results"]
        for loc in (*r["locations"], *r.get("relatedLocations", ()))
    ]


def test_sarif_has_no_absolute_path_anywhere() -> None:
    text = CheckFormat.SARIF.renderer()(_many(3), RenderOptions(base=BASE))
    assert str(BASE) not in text and "file:" not in text
    assert not [s for s in _strings(json.loads(text)) if s.startswith("/")]
    base_ids = json.loads(text)["runs"][0]["originalUriBaseIds"]
    assert set(base_ids) == {"%SRCROOT%"} and "uri" not in base_ids["%SRCROOT%"]


def test_sarif_uris_are_percent_encoded_relative_references() -> None:
    # RFC 3986 section 3.3: unreserved, sub-delims, "@", "/" and %XX only.
    allowed = re.compile(r"^(?:[A-Za-z0-9\-._~!$&'()*+,;=@/]|%[0-9A-F]{2})+$")
    locations = _locations(_sarif(_many(3)))
    uris = [loc["artifactLocation"]["uri"] for loc in locations]
    assert all(allowed.match(u) for u in uris), uris
    assert all(loc["artifactLocation"]["uriBaseId"] == "%SRCROOT%" for loc in locations)
    assert unquote(relative_uri(BASE / "icons" / ODD, BASE)) == f"icons/{ODD}"
    assert f"icons/{ODD}" in {unquote(u) for u in uris}
    assert ":" not in relative_uri(Path("c:d.svg"), None)  # not read as a scheme
    assert relative_uri(Path("/elsewhere/x.svg"), BASE).startswith("../")


def test_every_sarif_location_has_a_region_at_the_line_that_sets_the_colour() -> None:
    doc = _sarif(_many(3, color_line=11))
    for result in doc["runs"][0]["results"]:
        (first,) = (loc["physicalLocation"] for loc in result["locations"])
        assert first["artifactLocation"]["uri"] == "icons/iconset.yaml"
        assert first["region"]["startLine"] >= 11
        related = [loc["physicalLocation"] for loc in result["relatedLocations"]]
        svgs = [loc for loc in related if loc["artifactLocation"]["uri"].endswith(".svg")]
        assert svgs and all(loc["region"]["startLine"] == 1 for loc in svgs)  # the drawings
    assert all(loc["region"]["startLine"] >= 1 for loc in _locations(doc))


def test_sarif_rule_ids_are_opaque_and_every_rule_says_how_to_fix() -> None:
    rules = _sarif(_many(1))["runs"][0]["tool"]["driver"]["rules"]
    assert [r["id"] for r in rules] == [RULES[r].sarif_id for r in Rule]
    assert len({r["id"] for r in rules}) == len(Rule)
    for r in rules:
        assert re.fullmatch(r"AA\d{3}", r["id"]) and r["id"] != r["name"]
        assert r["help"]["text"] and "**Fix:**" in r["help"]["markdown"]
    results = _sarif(_many(1))["runs"][0]["results"]
    assert all(rules[r["ruleIndex"]]["id"] == r["ruleId"] for r in results)


def test_sarif_fingerprints_are_unique_and_survive_moved_lines() -> None:
    def prints(report: CheckReport) -> list[str]:
        return [
            r["partialFingerprints"]["alphaAuditFinding/v2"]
            for r in _sarif(report)["runs"][0]["results"]
        ]

    before, after = prints(_many(5, color_line=3)), prints(_many(5, color_line=40))
    assert before == after and len(set(before)) == 5


def test_sarif_log_has_the_required_2_1_0_structure() -> None:
    # Structural checks of the SARIF 2.1.0 schema's required properties (the
    # schema itself is not vendored): log version/runs, run tool.driver.name,
    # result message.text, artifactLocation uri.
    doc = _sarif(_many(2, problems=1))
    assert doc["version"] == "2.1.0" and doc["$schema"].endswith("sarif-2.1.0.json")
    (run,) = doc["runs"]
    assert run["tool"]["driver"]["name"] == "alpha-audit"
    for result in run["results"]:
        assert result["message"]["text"] and result["level"] in {"error", "warning", "note", "none"}
        for loc in result["locations"]:
            physical = loc["physicalLocation"]
            assert physical["artifactLocation"]["uri"]
            assert isinstance(physical["region"]["startLine"], int)


def test_sarif_failure_messages_end_with_their_fix() -> None:
    from alpha_audit.bundled import bundled_iconset, bundled_theme
    from alpha_audit.pipeline import check_project
    from alpha_audit.policy import Policy

    report = check_project(
        ProjectConfig(
            themes=(bundled_theme("paper16"),),
            iconsets=(bundled_iconset("vibrant"),),
            policy=Policy(),
            alpha=1.5,
        )
    )
    assert report.gate.failures
    doc = json.loads(CheckFormat.SARIF.renderer()(report, RenderOptions()))
    failing = [r for r in doc["runs"][0]["results"] if "suppressions" not in r]
    assert failing and all(". Fix: " in r["message"]["text"] for r in failing)
