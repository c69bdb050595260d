"""The shared helpers: escaping, the JSON policy, name lists, extensions."""

from __future__ import annotations

import json
import math
from dataclasses import dataclass

import pytest
from hypothesis import given
from hypothesis import strategies as st
from markdown_it import MarkdownIt

from alpha_audit.render.common import dumps, escape_markdown, records, shorten_names

json_values = st.recursive(
    st.none()
    | st.booleans()
    | st.integers()
    | st.floats(allow_nan=False, allow_infinity=False)
    | st.text(),
    lambda children: (
        st.lists(children, max_size=4) | st.dictionaries(st.text(max_size=5), children, max_size=4)
    ),
    max_leaves=20,
)


@given(json_values)
def test_dumps_round_trips_any_document(doc: object) -> None:
    text = dumps(doc)
    assert text.endswith("\n") and text.isascii()
    assert json.loads(text) == doc


def test_dumps_keeps_key_order_and_writes_flat_records_on_one_line() -> None:
    text = dumps({"b": 1, "a": {"rows": [{"x": 0.1, "y": [1, 2]}, {"x": 2.5, "y": []}]}})
    assert text.index('"b"') < text.index('"a"')
    assert '{"x": 0.1, "y": [1, 2]},' in [line.strip() for line in text.splitlines()]


@pytest.mark.parametrize("bad", [math.nan, math.inf, -math.inf])
def test_dumps_refuses_what_is_not_json(bad: float) -> None:
    with pytest.raises(ValueError):
        dumps({"rows": [{"x": bad}]})


def test_dumps_never_fails_on_a_lone_surrogate() -> None:
    assert json.loads(dumps({"name": "\ud800"})) == {"name": "\ud800"}


def test_records_match_field_by_field() -> None:
    @dataclass(frozen=True)
    class Row:
        a: float
        b: str

    assert records([Row(1.5, "x"), Row(2.0, "y")]) == [{"a": 1.5, "b": "x"}, {"a": 2.0, "b": "y"}]
    assert records([]) == []


_MD = MarkdownIt("commonmark").enable("table")


@given(st.text(max_size=40))
def test_an_escaped_cell_is_one_cell_of_plain_text(text: str) -> None:
    cell = escape_markdown(text)
    html = _MD.render(f"| h |\n|---|\n| {cell} |\n")
    assert "\n" not in cell
    assert html.count("<td") == 1  # a pipe never opens another cell
    for tag in ("<img", "<a ", "<em", "<strong", "<code", "<script", "<details"):
        assert tag not in html
    assert "@" not in cell  # never a mention


@pytest.mark.parametrize(
    "url", ["https://evil.example/x", "http://a.b", "HTTPS://A.B", "www.evil.example", "ftp://x"]
)
def test_bare_urls_are_not_left_for_github_to_autolink(url: str) -> None:
    cell = escape_markdown(f"see {url} now")
    assert "://" not in cell and "www." not in cell.lower()


def test_shorten_names() -> None:
    assert shorten_names(["a", "b", "c"]) == "a, b, c"
    assert shorten_names(["a", "b", "c", "d", "e"]) == "a, b, c +2 more"


def test_bidi_overrides_cannot_reorder_a_cell() -> None:
    cell = escape_markdown("icon\u202eevil\u2066x\u2069")
    assert not any(c in cell for c in "\u202e\u2066\u2069")
    assert escape_markdown("a\u200dxb") == "a\u200dxb"  # a zero-width joiner (emoji) stays
