"""Every result type x every format: one frame, and each output parses as its format.

The four result types (check, suggest, pair, reproduce) share one mechanism: an
enum whose ``renderer()`` gives a ``(result, options) -> str`` function.  Names
here are hostile (Markdown, HTML, a mention, a bare URL, a control character),
so a format that lets one through fails its parse check, not a snapshot.
"""

from __future__ import annotations

import json
import xml.etree.ElementTree as ET
from collections import Counter
from collections.abc import Callable
from enum import StrEnum
from functools import cache
from html.parser import HTMLParser
from pathlib import Path
from typing import Any

import pytest
from markdown_it import MarkdownIt

from alpha_audit.gate import evaluate
from alpha_audit.load.config import ProjectConfig
from alpha_audit.model import Canvas, Icon, IconProblem, IconSet, Theme
from alpha_audit.pair import pair_report
from alpha_audit.policy import Policy
from alpha_audit.render import CheckFormat, PairFormat, SuggestFormat
from alpha_audit.render.common import RenderOptions
from alpha_audit.reproduce.formats import ReproduceFormat
from alpha_audit.reproduce.run import Experiment, reproduce
from alpha_audit.results import CheckReport
from alpha_audit.rows import audit
from alpha_audit.rules import Rule
from alpha_audit.suggest import suggest
from helpers import solid_paints

BASE = Path("/repo")
HOSTILE = "evil|x <img src=x> @team https://evil.example `c` *b*\x07"
OPTIONS = RenderOptions(width=100, base=BASE)


def _theme() -> Theme:
    return Theme(
        HOSTILE, (Canvas(f"sun {HOSTILE}", "#ffff00", "light"), Canvas("ink", "#0d1117", "dark"))
    )


def _iconset() -> IconSet:
    icons = (
        Icon(HOSTILE, BASE / "icons" / "deep.svg", "#0000cf", 1.4, color_line=7),
        Icon("pale", BASE / "icons" / "pale.svg", "#eeeeee", 2.0),
        Icon("paler", BASE / "icons" / "paler.svg", "#dddddd", 2.0),
    )
    return IconSet(HOSTILE, icons, path=BASE / "icons" / "iconset.yaml")


@cache
def check_report() -> CheckReport:
    result = audit(_theme(), _iconset())
    policy = Policy(rules=frozenset({Rule.LOSS, Rule.COLLISION, Rule.SEPARATION}))
    return CheckReport(audits=(result,), gate=evaluate([result], policy))


@cache
def suggest_result() -> Any:
    return suggest(audit(_theme(), _iconset()), Policy())


@cache
def pair() -> Any:
    return pair_report("#ee7733", ["white", "#0d1117"], [1.0, 1.4])


@cache
def reproduction() -> Any:
    return reproduce(_theme(), only=[Experiment.FULL_GAMUT, Experiment.SWEEP], quick=True)


RESULTS: dict[type[StrEnum], Callable[[], Any]] = {
    CheckFormat: check_report,
    SuggestFormat: suggest_result,
    PairFormat: pair,
    ReproduceFormat: reproduction,
}
CASES = [
    pytest.param(fmt, RESULTS[kind], id=f"{kind.__name__}-{fmt}")
    for kind in RESULTS
    for fmt in kind
]


def _strict_json(text: str) -> Any:
    def refuse(name: str) -> None:
        raise AssertionError(f"{name} in JSON output")

    return json.loads(text, parse_constant=refuse)


def _markdown(text: str) -> str:
    """The HTML GitHub-flavoured Markdown turns ``text`` into (tables on)."""
    html = MarkdownIt("commonmark").enable("table").render(text)
    assert "<img" not in html and "<a " not in html, "hostile name became markup"
    assert "@team" not in text and "https://evil" not in text and "\x07" not in text
    return html


class _Tags(HTMLParser):
    """Counts the start tags of an HTML document."""

    def __init__(self) -> None:
        super().__init__()
        self.tags: Counter[str] = Counter()

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        self.tags[tag] += 1


def _check(fmt: str, text: str) -> None:
    if fmt == "json":
        assert isinstance(_strict_json(text), dict)
    elif fmt == "sarif":
        assert _strict_json(text)["version"] == "2.1.0"
    elif fmt == "junit":
        assert ET.fromstring(text).tag == "testsuites"
    elif fmt == "markdown":
        assert "<table>" in _markdown(text)
    elif fmt == "github":
        assert all(line.startswith("::") for line in text.splitlines())
    elif fmt == "table":
        assert "\x1b" not in text  # no colour unless asked
    elif fmt == "gitlab":
        issues = _strict_json(text)
        assert isinstance(issues, list)
        prints = [i["fingerprint"] for i in issues]
        assert len(set(prints)) == len(prints)
        assert all(not i["location"]["path"].startswith("/") for i in issues)
    elif fmt == "html":
        parser = _Tags()
        parser.feed(text)
        parser.close()
        assert parser.tags["html"] == 1 and "script" not in parser.tags and "a" not in parser.tags
        assert "img" not in parser.tags  # a check report has no crops: a name never becomes one
        assert 'http-equiv="Content-Security-Policy"' in text
    else:  # pragma: no cover - a new format needs its parse check here
        raise AssertionError(f"no parse check for format {fmt!r}")


@pytest.mark.parametrize(("fmt", "make"), CASES)
def test_every_result_type_renders_every_format(fmt: StrEnum, make: Callable[[], Any]) -> None:
    renderer = fmt.renderer()  # type: ignore[attr-defined]
    text = renderer(make(), OPTIONS)
    assert text.strip() and text.endswith("\n")
    _check(fmt.value, text)
    assert renderer(make(), OPTIONS) == text  # pure: same result, same text


@pytest.mark.parametrize("fmt", list(CheckFormat))
def test_a_report_where_no_icon_rendered_is_still_a_report(fmt: CheckFormat) -> None:
    iconset = _iconset()
    broken = tuple(IconProblem(i.name, Path(i.file), "not an SVG") for i in iconset.icons)
    result = audit(_theme(), iconset, solid_paints(iconset, broken))
    report = CheckReport(audits=(result,), gate=evaluate([result], Policy()))
    _check(fmt.value, fmt.renderer()(report, OPTIONS))


def test_json_documents_are_ascii_and_keep_every_float() -> None:
    text = SuggestFormat.JSON.renderer()(suggest_result(), OPTIONS)
    assert text.isascii()
    doc = _strict_json(text)
    assert doc["iconset"] == HOSTILE  # escaped in the text, identical once parsed
    assert doc["per_color"][0]["exact"] == suggest_result().per_color[0].safe.exact


@cache
def _every_rule_report() -> CheckReport:
    """The bundled example through the whole pipeline with every rule on, pushed hard.

    Real SVGs, so paints are read and every paint rule (drift, confusion, CVD,
    thin strokes ...) can produce findings of its own shape.
    """
    from alpha_audit.bundled import bundled_iconset, bundled_theme
    from alpha_audit.pipeline import check_project

    policy = Policy(rules=frozenset(Rule) - {Rule.LOCK}, min_delta_e=25.0, max_drift=5.0)
    return check_project(
        ProjectConfig(
            themes=(bundled_theme("paper16"),),
            iconsets=(bundled_iconset("vibrant"),),
            policy=policy,
            alpha=1.8,
        )
    )


def test_the_pipeline_with_every_rule_on_makes_findings_of_many_rules() -> None:
    rules = {f.rule for f in _every_rule_report().gate.failures}
    assert {Rule.CONFUSION, Rule.DRIFT, Rule.COLLISION, Rule.SEPARATION} <= rules


def test_every_rule_has_an_id_help_fix_and_severity() -> None:
    from alpha_audit.rules import RULES

    assert set(RULES) == set(Rule)
    assert all(s.help and s.fix and s.sarif_id and s.severity for s in RULES.values())
    assert len({s.sarif_id for s in RULES.values()}) == len(Rule)


@pytest.mark.parametrize("fmt", list(CheckFormat))
def test_every_format_renders_findings_of_every_rule(fmt: CheckFormat) -> None:
    text = fmt.renderer()(_every_rule_report(), OPTIONS)
    assert text.strip()
    if fmt is not CheckFormat.MARKDOWN:  # the example's names are not hostile
        _check(fmt.value, text)
    else:
        assert "<table>" in MarkdownIt("commonmark").enable("table").render(text)
