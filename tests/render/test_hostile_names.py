"""Defence in depth: whatever a name holds, every renderer's output parses and sends nothing.

Loaders refuse control, bidi and surrogate characters in names (load/names.py),
but the library takes a :class:`~alpha_audit.model.Theme` from any caller, and a
renderer must not rely on the loader: for arbitrary names (every Unicode
category, lone surrogates included, mixed with escape sequences, workflow
commands, markup and XML's forbidden characters), every format of every result
renders without an exception, encodes as UTF-8, holds no instruction character
(the one policy, :func:`alpha_audit.safe_text.first_unsafe`; a format's own
line ends aside) and parses as its format, with no markup made from a name.
"""

from __future__ import annotations

import json
import re
import xml.etree.ElementTree as ET
from pathlib import Path
from typing import Any

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from markdown_it import MarkdownIt

from alpha_audit.export.escape import css_ident, css_name, css_string, xml_attr, xml_text
from alpha_audit.gate import evaluate
from alpha_audit.model import Canvas, Icon, IconSet, Theme
from alpha_audit.policy import Policy
from alpha_audit.render import CheckFormat, SuggestFormat
from alpha_audit.render.common import RenderOptions, digest
from alpha_audit.results import CheckReport
from alpha_audit.rows import audit
from alpha_audit.rules import Rule
from alpha_audit.safe_text import first_unsafe
from alpha_audit.suggest import suggest

BASE = Path("/repo")
OPTIONS = RenderOptions(width=100, base=BASE)
FRAGMENTS = [
    "\x1b]52;c;SGVsbG8=\x07",  # OSC 52: the reviewer's clipboard
    "\x1b[2J",
    "\x9b31m",  # C1 CSI
    "\n::add-mask::secret",
    "\r\n::stop-commands::tok",
    "%0A::error::x",
    "a:b,c",
    "\u202eexe",
    "\u2066\u2069\u200e\u061c",
    "\ud800",  # lone surrogate
    "\udcff",  # a non-UTF-8 file name's byte (PEP 383)
    "\u2028\u2029\x85",
    "\x00\x0b\ufffe\uffff",  # forbidden in XML 1.0
    "</details><img src=x onerror=alert(1)>",
    "| a | b |",
    "*x* _y_ `z` [l](http://e)",
    "@team https://evil.example",
    "[bold red]markup[/]",
    "]]><!--",
    "\U000e0041\U000e0042",  # tag characters: hidden text
    "👩\u200d💻",  # emoji ZWJ sequence: text, kept
    "__ALPHA_AUDIT_SCRIPT__",
]
# Every code point hypothesis draws, surrogates included, plus the fragments above.
NAMES = st.lists(
    st.one_of(st.sampled_from(FRAGMENTS), st.text(st.characters(exclude_categories=()))),
    min_size=1,
    max_size=4,
).map("".join)
LINE_ENDS = {"\n"}


def _report(name: str) -> tuple[CheckReport, Any]:
    theme = Theme(f"t{name}", (Canvas(f"sun{name}", "#ffff00", "light"), Canvas("ink", "#0d1117")))
    icons = (
        Icon(f"i{name}", BASE / "icons" / f"{name[:20]}.svg", "#0000cf", 1.4, color_line=7),
        Icon("pale", BASE / "icons" / "pale.svg", "#eeeeee", 2.0),
        Icon(f"paler{name}", BASE / "icons" / "paler.svg", "#dddddd", 2.0),
    )
    iconset = IconSet(f"s{name}", icons, path=BASE / "icons" / "iconset.yaml")
    result = audit(theme, iconset)
    policy = Policy(rules=frozenset({Rule.LOSS, Rule.COLLISION, Rule.SEPARATION}))
    return CheckReport(audits=(result,), gate=evaluate([result], policy)), suggest(result, policy)


def _inert(text: str) -> None:
    text.encode("utf-8")  # a lone surrogate crashed table, SARIF, Markdown and GitLab
    bad = first_unsafe("".join(ch for ch in text if ch not in LINE_ENDS))
    assert bad is None, f"raw U+{ord(bad):04X} in output"


def _markdown(text: str) -> None:
    html = MarkdownIt("commonmark").enable("table").render(text)
    assert "<img" not in html and "<a " not in html and "<script" not in html
    assert html.count("<details") == html.count("</details>")  # no name closes a section
    assert "@team" not in text and "https://evil" not in text


def _parse(fmt: str, text: str) -> None:
    if fmt in ("json", "sarif", "gitlab"):
        json.loads(text)
    elif fmt == "junit":
        ET.fromstring(text)
    elif fmt == "markdown":
        _markdown(text)
    elif fmt == "github":
        for line in text.splitlines():
            match = re.fullmatch(r"::(error|warning|notice) ([^:]*)::(.*)", line)
            assert match, line  # no name starts a command or ends the properties
            assert all(re.fullmatch(r"\w+=[^,]*", p) for p in match[2].split(",")), line


@settings(max_examples=25)
@given(NAMES)
def test_every_check_and_suggest_format_is_inert_and_parses_for_any_name(name: str) -> None:
    report, suggested = _report(name)
    for fmt in CheckFormat:
        text = fmt.renderer()(report, OPTIONS)
        _inert(text)
        _parse(fmt.value, text)
    for sfmt in SuggestFormat:
        text = sfmt.renderer()(suggested, OPTIONS)
        _inert(text)
        _parse(sfmt.value, text)


def test_terminal_output_shows_escapes_and_keeps_colour() -> None:
    report, _ = _report("\x1b]52;c;SGVsbG8=\x07\u202e")
    plain = CheckFormat.TABLE.renderer()(report, OPTIONS)
    assert "\\x1b]52;c;SGVsbG8=\\x07\\u202e" in plain and "\x1b" not in plain
    coloured = CheckFormat.TABLE.renderer()(report, RenderOptions(width=100, color=True))
    assert "\x1b[" in coloured  # rich's own colour codes stay
    assert "\x1b]" not in coloured and "\\x1b]52" in coloured  # the name's OSC does not


def test_fingerprints_of_names_with_surrogates_are_stable_and_distinct() -> None:
    assert digest("a\ud800") == digest("a\ud800") != digest("a\ud801") != digest("a")


def test_emoji_names_are_kept_as_they_are() -> None:
    report, _ = _report("👩\u200d💻")
    for fmt in (CheckFormat.TABLE, CheckFormat.MARKDOWN, CheckFormat.JUNIT, CheckFormat.GITHUB):
        assert "👩\u200d💻" in fmt.renderer()(report, OPTIONS), fmt


# --- export: CSS and SVG -----------------------------------------------------------------


@given(st.text(st.characters(exclude_categories=()), min_size=1, max_size=12))
def test_css_escapes_give_one_token_that_reads_back_as_the_name(name: str) -> None:
    import tinycss2

    def single(css: str) -> Any:
        tokens = [t for t in tinycss2.parse_component_value_list(css) if t.type != "whitespace"]
        assert len(tokens) == 1, (css, tokens)
        return tokens[0]

    def norm(text: str) -> str:
        # An escaped NUL or lone surrogate reads back as U+FFFD (CSS Syntax Level 3,
        # 4.3.7; tinycss2 keeps the surrogate): either way not the character itself.
        return re.sub("[\x00\ud800-\udfff]", "\ufffd", text)

    expect = norm(name)
    selector = tinycss2.parse_component_value_list("." + css_ident(name))  # a class selector
    assert [t.type for t in selector] == ["literal", "ident"], selector
    assert norm(selector[1].value) == expect
    prop = single("--" + css_name(name))
    assert prop.type == "ident" and norm(prop.value) == "--" + expect
    string = single(css_string(name))
    assert string.type == "string" and norm(string.value) == expect
    assert "<" not in css_string(name)  # no </style> when a sheet is inlined


@pytest.mark.parametrize("name", ["1dark", "-2x", "-", "--", "0", "_1", "-_", "é1"])
def test_class_names_that_start_badly_are_escaped_into_identifiers(name: str) -> None:
    import tinycss2

    tokens = tinycss2.parse_component_value_list("." + css_ident(name))
    assert [t.type for t in tokens] == ["literal", "ident"] and tokens[1].value == name


@given(NAMES)
def test_xml_text_and_attributes_always_parse(name: str) -> None:
    doc = f"<svg><filter id={xml_attr(name)}><desc>{xml_text(name)}</desc></filter></svg>"
    _inert(doc)
    root = ET.fromstring(doc)
    assert root[0][0].text is not None or not name
