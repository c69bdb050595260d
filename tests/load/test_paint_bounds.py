"""The paint reader's bounds hold before the work: counted, never timed (issue 21)."""

from __future__ import annotations

from collections.abc import Iterable, Iterator
from pathlib import Path

import cssselect2
import pytest

from alpha_audit.errors import SvgError
from alpha_audit.load import paints as module
from alpha_audit.load.paints import (
    MAX_DEPTH,
    MAX_MATCH_WORK,
    MAX_SELECTORS,
    extract_paints,
    paints_and_isolates,
)

NS = 'xmlns="http://www.w3.org/2000/svg"'


@pytest.fixture
def matches(monkeypatch: pytest.MonkeyPatch) -> list[int]:
    """How many elements cssselect2 was asked to match (one entry each)."""
    calls: list[int] = []
    real = cssselect2.Matcher.match

    def spy(self: cssselect2.Matcher, element: object) -> object:
        calls.append(1)
        return real(self, element)

    monkeypatch.setattr(cssselect2.Matcher, "match", spy)
    return calls


def nested(depth: int, leaves: str = "<rect/>") -> str:
    return '<g class="a">' * depth + leaves + "</g>" * depth


HOSTILE = {
    # every combination of 8 ancestors out of 60 before a rect is refused (C(60, 8) ~ 2.6e9)
    "backtracking descendants": (
        "<style>.a .a .a .a .a .a .a .a rect { fill: red }</style>" + nested(60),
        "element tests",
    ),
    # :has() walks every descendant of every element
    ":has() nested in :has()": (
        "<style>g:has(g:has(g:has(rect))) { fill: red }</style>" + nested(40, "<rect/>" * 500),
        "element tests",
    ),
    # a few rules, each applying its declarations to every element
    "declarations on every element": (
        "<style>"
        + "".join(f"* {{ fill: #{i:06x}; stroke: #{i:06x}; opacity: .5 }}" for i in range(150))
        + "</style>"
        + "<rect/>" * 5000,
        "element tests",
    ),
    "too many selectors": (
        "<style>" + ",".join(f".c{i}" for i in range(MAX_SELECTORS + 1)) + "{fill:red}</style>",
        f"more than {MAX_SELECTORS} CSS selectors",
    ),
    "selectors nested beyond the recursion limit": (
        "<style>" + ":is(" * 3000 + "a" + ")" * 3000 + "{fill:red}</style><rect/>",
        "nests CSS selectors too deeply",
    ),
}


@pytest.mark.parametrize("case", HOSTILE)
def test_hostile_stylesheets_are_refused_before_any_element_is_matched(
    case: str, matches: list[int]
) -> None:
    body, message = HOSTILE[case]
    svg = f"<svg {NS}>{body}</svg>".encode()
    with pytest.raises(SvgError, match=message) as info:
        extract_paints(svg, path="hostile.svg")
    assert matches == []  # refused before the cascade began
    assert "hostile.svg" in str(info.value)
    if "element tests" in message:
        assert f"{MAX_MATCH_WORK}" in info.value.message and "refused" in info.value.message


def test_depth_is_refused_while_parsing_before_the_cascade(matches: list[int]) -> None:
    svg = f"<svg {NS}><style>g {{ fill: red }}</style>{nested(MAX_DEPTH + 5)}</svg>".encode()
    with pytest.raises(SvgError, match=f"deeper than {MAX_DEPTH}") as info:
        extract_paints(svg)
    assert matches == []
    assert info.value.line == 1


def test_ordinary_stylesheets_stay_well_inside_the_bound() -> None:
    """An icon set's stylesheet (classes, descendant selectors) is nowhere near the bound."""
    rules = "".join(
        f".cls-{i} {{ fill: #{i:06x} }} svg g .cls-{i} {{ stroke: none }}" for i in range(40)
    )
    body = "".join(f'<g><path class="cls-{i % 40}" d="M0 0h1v1z"/></g>' for i in range(400))
    svg = f"<svg {NS}><style>{rules}</style>{body}</svg>".encode()
    assert len(extract_paints(svg).groups()) == 40


def _counting(items: Iterable[object], seen: list[int]) -> Iterator[object]:
    """``items``, counting each one the matcher walks over in ``seen``."""
    for item in items:
        seen.append(1)
        yield item


SELECTORS = [
    ".a",
    "g rect",
    ".a .a .a rect",
    "g > g > rect",
    "rect ~ rect",
    "rect + circle",
    "g:has(circle)",
    "g:has(> rect ~ circle)",
    ":not(.a .a) rect",
    "rect:nth-child(2n + 1 of .b)",
    "rect:first-of-type",
    ":is(g g, g > rect) rect",
]


@pytest.mark.parametrize("selector", SELECTORS)
def test_the_counted_bound_is_at_least_the_elements_cssselect2_walks(
    selector: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The bound is an upper bound: the elements visited while matching never exceed it."""
    from cssselect2.tree import ElementWrapper

    tree = nested(6, '<rect class="b"/><circle/><rect/>' * 4 + nested(3, "<rect/><circle/>"))
    svg = f"<svg {NS}><style>{selector} {{ fill: red }}</style>{tree}</svg>".encode()
    root, _, extent = module._parse(svg, None)
    (parsed,) = cssselect2.parser.parse(selector)
    bound = extent.elements * module._match_cost(parsed.parsed_tree, extent)
    compiled = cssselect2.compiler.CompiledSelector(parsed)
    wrappers = list(cssselect2.ElementWrapper.from_xml_root(root).iter_subtree())
    seen: list[int] = []
    for name in ("ancestors", "previous_siblings"):
        real = getattr(ElementWrapper, name)
        monkeypatch.setattr(
            ElementWrapper,
            name,
            property(lambda self, real=real: _counting(real.__get__(self), seen)),
        )
    for name in ("iter_subtree", "iter_next_siblings", "iter_children", "iter_siblings"):
        method = getattr(ElementWrapper, name)
        monkeypatch.setattr(
            ElementWrapper, name, lambda self, method=method: _counting(method(self), seen)
        )
    for element in wrappers:
        compiled.test(element)
    assert len(seen) <= bound
    assert bound < MAX_MATCH_WORK  # and an icon-sized tree stays far inside the limit


def test_paints_and_isolates_counts_its_variants_before_writing_them() -> None:
    many = "".join(f'<rect fill="#{i:06x}" width="1" height="1"/>' for i in range(20))
    svg = f"<svg {NS}>{many * 300}</svg>".encode()
    with pytest.raises(SvgError, match="element renders; refused"):
        paints_and_isolates(svg)


def test_the_render_workers_refuse_a_hostile_stylesheet_with_the_bound_named(
    tmp_path: Path,
) -> None:
    """Through the pool (where paints are read): a problem naming the bound, the rest goes on."""
    from alpha_audit.load.paint_masks import measure_paints

    folder = tmp_path
    body, _ = HOSTILE["backtracking descendants"]
    (folder / "hostile.svg").write_text(f"<svg {NS}>{body}</svg>")
    (folder / "fine.svg").write_text(
        f'<svg {NS} viewBox="0 0 4 4"><rect width="4" height="4"/></svg>'
    )
    icons = [("hostile", folder / "hostile.svg"), ("fine", folder / "fine.svg")]
    result = measure_paints(icons, [8], cache=False)
    (problem,) = result.problems
    assert problem.icon == "hostile"
    assert f"{MAX_MATCH_WORK}" in problem.message and "refused before matching" in problem.message
    assert list(result.icons) == ["fine"]
