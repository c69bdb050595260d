"""The cascade walk on its own: the ranking rules of CSS Cascade 5 and what a trace follows.

Browser-free: declarations are written by hand, as the probe or devtools
report them.  The browsers' agreement is tests/pages/test_declarations.py's.
"""

from __future__ import annotations

import json

import pytest
from hypothesis import given
from hypothesis import strategies as st

from alpha_audit.browser.matched import LAST_LAYER, declarations
from alpha_audit.pages.cascade import Declaration, parse_styles, trace, winner

UNLAYERED = (LAST_LAYER,)


def rule(prop: str, value: str, position: int = 0, *, important: bool = False,
         layer: tuple[int, ...] = UNLAYERED, kind: str = "rule") -> Declaration:  # fmt: skip
    return Declaration(prop, prop, value, important, kind, layer, position)


def _as_reported(decl: Declaration) -> Declaration:
    """Hints and the engine's own colours come as devtools reports them: unlayered, at
    positions -1 and -2, and a hint is never ``!important`` (markup has no such flag)."""
    if decl.kind == "hint":
        return rule("color", decl.value, -1, kind="hint")
    if decl.kind == "ua":
        return rule("color", decl.value, -2, important=decl.important, kind="ua")
    return decl


_DECLS = st.builds(
    rule,
    st.just("color"),
    st.sampled_from(["red", "blue", "green", "navy"]),
    st.integers(0, 20),
    important=st.booleans(),
    layer=st.sampled_from([UNLAYERED, (0, LAST_LAYER), (1, LAST_LAYER), (0, 0, LAST_LAYER)]),
    kind=st.sampled_from(["rule", "rule", "attribute", "hint", "ua"]),
).map(_as_reported)


@given(st.lists(_DECLS, max_size=8, unique_by=lambda d: (d.kind, d.position)), st.randoms())
def test_the_winner_does_not_depend_on_the_order_reported(
    decls: list[Declaration], shuffle: object
) -> None:
    again = list(decls)
    shuffle.shuffle(again)
    assert winner(again, "color") == winner(decls, "color")


@given(st.lists(_DECLS, min_size=1, max_size=8))
def test_importance_then_attachment_decide_first(decls: list[Declaration]) -> None:
    won = winner(decls, "color")
    authored_important = [d for d in decls if d.important and d.kind != "ua"]
    assert won is not None
    if any(d.important and d.kind == "ua" for d in decls):
        assert won.important and won.kind == "ua"
    elif authored_important:
        assert won.important
        if any(d.kind == "attribute" for d in authored_important):
            assert won.kind == "attribute"
    else:
        assert not won.important
        kinds = {d.kind for d in decls if not d.important}
        for better, worse in (("attribute", "rule"), ("rule", "hint"), ("hint", "ua")):
            if better in kinds:
                assert won.kind != worse


def test_a_property_written_twice_in_a_rule_takes_the_later() -> None:
    twice = [rule("color", "red", 3), rule("color", "blue", 3), rule("color", "navy", 2)]
    assert winner(twice, "color").value == "blue"


def test_layers_order_normal_declarations_and_reverse_important_ones() -> None:
    first, second = (0, LAST_LAYER), (1, LAST_LAYER)
    normal = [rule("color", "a", 5, layer=first), rule("color", "b", 6, layer=second),
              rule("color", "c", 7)]  # fmt: skip
    assert winner(normal, "color").value == "c"
    important = [rule("color", "a", 5, important=True, layer=first),
                 rule("color", "b", 6, important=True, layer=second),
                 rule("color", "c", 7, important=True)]  # fmt: skip
    assert winner(important, "color").value == "a"
    nested = [rule("color", "outer", 1, important=True, layer=(0, LAST_LAYER)),
              rule("color", "inner", 0, important=True, layer=(0, 0, LAST_LAYER))]  # fmt: skip
    assert winner(nested, "color").value == "inner"


def _styles(*nodes: list[Declaration]) -> list[list[Declaration]]:
    return list(nodes)


@pytest.mark.parametrize(
    ("nodes", "prop", "values", "complete"),
    [
        # Inherited: the nearest declaration up the tree.
        (([], [rule("color", "red")], [rule("color", "blue")]), "color", ["red"], True),
        # Not inherited: the element's own, or nothing.
        (([], [rule("background-color", "red")]), "background-color", [], False),
        # inherit climbs one more; currentColor as a colour is inherit.
        (
            ([rule("color", "inherit")], [rule("color", "currentColor")], [rule("color", "red")]),
            "color",
            ["red"],
            True,
        ),
        # currentColor in a paint resolves with the colour where the paint is used.
        (
            ([rule("color", "green")], [rule("fill", "currentColor"), rule("color", "red")]),
            "fill",
            ["currentColor", "green"],
            True,
        ),
        # var() is looked up from the element that declares it, up.
        (
            ([rule("color", "var(--a)")], [rule("--a", "#123")], [rule("--a", "#456")]),
            "color",
            ["var(--a)", "#123"],
            True,
        ),
        # An alias chain to its end.
        (
            ([rule("color", "var(--a)")], [rule("--a", "var(--b)")], [rule("--b", "#123")]),
            "color",
            ["var(--a)", "var(--b)", "#123"],
            True,
        ),
        # An undefined property with a fallback ends at the declaration holding it.
        (([rule("color", "var(--none, #abc)")],), "color", ["var(--none, #abc)"], True),
        (([rule("color", "var(--none)")],), "color", ["var(--none)"], False),
        # The engine's own colour (a button's) ends the walk: no project line sets it.
        (
            ([], [rule("color", "buttontext", kind="ua")], [rule("color", "red")]),
            "color",
            ["buttontext"],
            False,
        ),
        # A cycle stops.
        (
            ([rule("color", "var(--a)")], [rule("--a", "var(--b)"), rule("--b", "var(--a)")]),
            "color",
            None,
            False,
        ),
    ],
)
def test_what_a_trace_follows(
    nodes: tuple[list[Declaration], ...], prop: str, values: list[str] | None, complete: bool
) -> None:
    got = trace(list(nodes), list(range(len(nodes))), prop)
    if values is not None:
        assert [d.value for d in got.hops] == values
    assert got.complete is complete


@pytest.mark.parametrize(
    "answer",
    [
        None,
        [],
        "x",
        {"nodes": "x"},
        {"nodes": [None, 3, ["x", {"property": 1}], [{"property": "color"}]]},
        {
            "sheets": [{"url": 5}],
            "nodes": [
                [
                    {
                        "property": "color",
                        "value": "red",
                        "sheet": 9,
                        "layer": ["a", None],
                        "line": "1",
                    }
                ]
            ],
        },
        {"error": "TypeError: x"},
    ],
)
def test_any_answer_of_a_page_is_read_without_failing(answer: object) -> None:
    """In WebKit the probe runs in the page's world: the page can hand back anything."""
    styles = parse_styles(json.loads(json.dumps(answer)), "http://127.0.0.1:1/0/p.html")
    if styles is not None:
        for node in styles:
            for d in node:
                trace(styles, [0], d.property)


def test_devtools_answers_become_the_walks_shape() -> None:
    """A ``getMatchedStylesForNode`` reply: layers ranked by first appearance, the inline
    sheet's ranges moved by its header, shorthands split, hints taken as written."""
    rule_ = {
        "origin": "regular",
        "styleSheetId": "s1",
        "layers": [{"text": "theme"}],
        "selectorList": {"text": ".a"},
        "style": {
            "cssProperties": [
                {"name": "background", "value": "var(--bg) !important", "important": True,
                 "text": "background: var(--bg) !important;",
                 "range": {"startLine": 0, "startColumn": 4, "endLine": 0, "endColumn": 30}},
                {"name": "background-color", "value": "red"},  # a longhand: not written
                {"name": "color", "value": "x", "parsedOk": False, "range": {
                    "startLine": 1, "startColumn": 2, "endLine": 1, "endColumn": 9}},
            ]
        },
    }  # fmt: skip
    reply = {
        "matchedCSSRules": [{"rule": {"origin": "user-agent", "style": {"cssProperties": [
            {"name": "color", "value": "buttontext"}]}}}, {"rule": rule_}],
        "inlineStyle": {"cssText": "color: blue", "cssProperties": [
            {"name": "color", "value": "blue", "range": {"startLine": 0, "startColumn": 0}}]},
        "attributesStyle": {"cssProperties": [{"name": "stroke", "value": "rgb(170, 51, 0)"}]},
    }  # fmt: skip
    headers = {"s1": {"sourceURL": "http://h/0/p.html", "isInline": True, "startLine": 7,
                      "startColumn": 11}}  # fmt: skip
    sheets: dict[str, int] = {}
    out = declarations(reply, None, headers, sheets, {"stroke": "#a30"})
    by = [(d["property"], d["kind"], d.get("line"), d.get("column"), d["value"]) for d in out]
    assert by == [
        ("color", "ua", None, None, "buttontext"),
        ("background-color", "rule", 7, 15, "var(--bg)"),
        ("background-image", "rule", 7, 15, "var(--bg)"),
        ("color", "attribute", None, None, "blue"),
        ("stroke", "hint", None, None, "#a30"),
    ]
    assert out[1]["layer"] == [0, LAST_LAYER] and out[1]["important"] is True
    assert sheets == {"s1": 0}


SELECTORS = [
    "span",
    ".c",
    "#t .c",
    "div#t.a.b[data-x] > span.c:first-child",
    ":is(#t, .a) .c",
    ":where(#t) .c",
    ":not(.zz, #yy) .c",
    "div:has(> .c) .c",
    ".c:nth-child(1 of .c, #q)",
    "*|span.c",
    "html body div span",
    "[data-x='1'] .c:not(:where(#nope))",
    ":is(div, #t.a) > :is(span, .c.c)",
    "div :is(.c)",
]


def test_the_walks_specificity_is_the_engines() -> None:
    """Blink's own specificity of each selector (devtools reports it) and the probe's agree."""
    from alpha_audit.browser import Chromium
    from alpha_audit.pages.capture import _probe_source

    if Chromium.find() is None:
        pytest.skip("Chromium is not installed")
    css = "".join(f"{s} {{ color: red }}\n" for s in SELECTORS)  # one rule a line
    html = (f"<!doctype html><style>{css}</style>"
            '<div id="t" class="a b" data-x="1"><span class="c">x</span></div>')  # fmt: skip
    with Chromium() as browser:
        browser.open_html(html)
        ours = browser.evaluate(
            f"(() => {{ const probe = {_probe_source()};"
            f" return {json.dumps(SELECTORS)}.map((s) => probe.specificity(s)); }})()",
            isolated=True,
        )
        call = browser._call
        call("DOM.enable")
        call("CSS.enable")
        root = call("DOM.getDocument", {"depth": -1})["root"]["nodeId"]
        node = call("DOM.querySelector", {"nodeId": root, "selector": "span.c"})["nodeId"]
        matched = call("CSS.getMatchedStylesForNode", {"nodeId": node})
    blink: dict[int, list[int]] = {}
    for match in matched["matchedCSSRules"]:
        if match["rule"]["origin"] != "regular":
            continue
        (selector,) = match["rule"]["selectorList"]["selectors"]
        spec = selector["specificity"]
        blink[selector["range"]["startLine"]] = [spec["a"], spec["b"], spec["c"]]
    assert sorted(blink) == list(range(len(SELECTORS)))  # every selector matched the <span>
    assert ours == [blink[k] for k in range(len(SELECTORS))]
