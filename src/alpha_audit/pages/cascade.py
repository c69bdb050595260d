"""Which declarations set an icon's colour and its backdrop's: the cascade, walked.

The page probe (``probe.js``) names, for each paint of each icon, the element
whose ``fill``, ``stroke`` or ``background-color`` draws it and the elements
it inherits through, and for each icon the nearest element at or above it
that paints a background.  The declarations that match those elements come
from the engine's devtools where it has them
(:meth:`~alpha_audit.browser.Browser.matched_styles`: Chromium's
``CSS.getMatchedStylesForNode``), else from the probe's own walk over
``document.styleSheets``; both give, per element, every declaration of a
colour, a background and a custom property with its rank in the cascade.

:func:`trace` then follows what the engine does (CSS Cascade 5, 6.1 to 6.4;
CSS Color 4, 4.4 ``currentcolor``; CSS Variables 1, 3): the winning
declaration of the paint's property on its element, or up the tree while the
property inherits (``fill``, ``stroke``, ``color`` and custom properties do,
backgrounds do not) or a declaration says ``inherit``; ``currentColor`` to
the winning ``color`` of the element that uses it; ``var(--x)`` to the
winning ``--x`` of the element that declares the ``var()``, and so on to a
value.  The result is a :class:`Trace`: the declarations followed, in order,
each with where the engine says it is written (a served URL and, from
devtools, a line and column); :mod:`alpha_audit.pages.declarations` turns
those into files and lines of the project.

Nothing here decides a verdict: a trace only says where a colour is written.
"""

from __future__ import annotations

import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from alpha_audit.browser import Browser, JSONValue

__all__ = [
    "Declaration",
    "IconSources",
    "ServedPlace",
    "Trace",
    "collect_sources",
    "trace",
    "winner",
]

# Hops followed in one trace: var() chains are short (a role, a token, a palette entry);
# a cycle (the engine makes it invalid) or a pathological chain stops here.
MAX_HOPS = 32
_INHERITED = frozenset({"color", "fill", "stroke"})  # and custom properties (CSS Variables 1, 2)
# Declared-value ranks among normal declarations (CSS Cascade 5, 6.1 and 6.3): the
# engine's own, then presentational hints (author level, before every author rule:
# SVG 2, 6.8), then author rules, then the element's style attribute.
_KIND_RANK = {"ua": 0, "hint": 1, "rule": 2, "attribute": 3}
_VAR = re.compile(r"var\(\s*(--[A-Za-z0-9_\-\u0080-\uffff]+)\s*(,?)", re.IGNORECASE)
_CURRENT = re.compile(r"(?<![\w-])currentcolor(?![\w-])", re.IGNORECASE)
_INHERIT_WORDS = frozenset({"inherit"})


@dataclass(frozen=True)
class ServedPlace:
    """Where the engine says a declaration is written, in what the page server served.

    ``url`` is the style sheet's URL, or the page's for a ``<style>`` element
    or ``style`` attribute (``inline``).  From devtools: ``line`` and
    ``column`` (0-based, UTF-16 code units) in that file and ``text``, the
    declaration as written there.  From the probe's walk: ``rule``, the
    rule's index among the sheet's style rules (depth first), ``selector``
    as the CSSOM serialises it, and for a ``<style>`` element
    ``sheet_text``, its text, to find in the page; for a ``style``
    attribute, ``text`` is the attribute's value.
    """

    url: str
    inline: bool = False
    line: int | None = None
    column: int | None = None
    text: str | None = None
    rule: int | None = None
    selector: str | None = None
    sheet_text: str | None = None


@dataclass(frozen=True)
class Declaration:
    """One declaration matching an element: what it sets, its value, its rank.

    ``property`` is what it sets (``color``, ``fill``, ``stroke``,
    ``background-color``, ``background-image``, or a custom property),
    ``name`` the property as written (``background`` for the shorthand).
    ``kind`` is ``rule``, ``attribute`` (the element's ``style``), ``hint``
    (an SVG presentation attribute such as ``fill="currentColor"``) or
    ``ua`` (the engine's own style sheet).  ``layer`` sorts cascade layers
    (a layer's own rules after its sublayers, unlayered rules last) and
    ``position`` ranks the matched rules in cascade order.
    """

    property: str
    name: str
    value: str
    important: bool
    kind: str
    layer: tuple[int, ...]
    position: int
    place: ServedPlace | None = None


@dataclass(frozen=True)
class Trace:
    """How one paint's or backdrop's colour comes about, as the cascade decides it.

    ``property`` is the one traced first (``fill``, ``stroke``,
    ``background-color``, ``background-image``); ``hops`` the winning
    declarations followed, in order: the property's own, then through
    ``currentColor`` the ``color`` one, then each custom property its value
    reads.  ``computed`` is the colour the engine computed for it (the
    probe's paint colour, the backdrop element's background colour), for a
    check.  ``complete`` is true when the last hop declares a value (no
    ``var()`` or ``currentColor`` left to follow, and not the engine's own).
    """

    property: str
    hops: tuple[Declaration, ...]
    computed: str | None
    complete: bool


@dataclass(frozen=True)
class IconSources:
    """Where one icon's colours come from: a trace per paint (``FoundIcon.paints``'s
    order; ``None`` where the probe named no element for it) and the backdrop's."""

    paints: tuple[Trace | None, ...]
    backdrop: Trace | None


def winner(declarations: Sequence[Declaration], prop: str) -> Declaration | None:
    """The declaration of ``prop`` that wins the cascade on one element, or ``None``.

    Important declarations beat normal ones (the engine's own first); among
    authors' the style attribute wins, then earlier layers (the layer order
    reversed, unlayered last), then the normal order; among normal ones the
    style attribute beats rules, rules beat presentational hints, hints beat
    the engine's own.  A tie (a property written twice in one rule) goes to
    the later declaration.

    >>> d = lambda v, pos, imp=False, kind="rule": Declaration("color", "color", v, imp, kind,
    ...     (1 << 30,), pos)
    >>> winner([d("red", 0), d("blue", 1)], "color").value
    'blue'
    >>> winner([d("red", 0, True), d("blue", 1), d("navy", 2, kind="attribute")], "color").value
    'red'
    """
    # A rule may write a property twice: the later one (later in the list) wins a tie.
    found = [(k, d) for k, d in enumerate(declarations) if d.property == prop]
    engine = [(k, d) for k, d in found if d.important and d.kind == "ua"]
    if engine:  # the engine's own !important beats every author's (6.2)
        return max(engine, key=lambda kd: (kd[1].position, kd[0]))[1]
    important = [(k, d) for k, d in found if d.important]
    if important:
        return max(
            important,
            key=lambda kd: (
                kd[1].kind == "attribute",
                tuple(-x for x in kd[1].layer),
                kd[1].position,
                kd[0],
            ),
        )[1]
    normal = [(k, d) for k, d in found if not d.important]
    if not normal:
        return None
    return max(normal, key=lambda kd: (_KIND_RANK.get(kd[1].kind, 0), kd[1].position, kd[0]))[1]


def _inherits(prop: str) -> bool:
    return prop in _INHERITED or prop.startswith("--")


def _first_var(value: str) -> tuple[str, bool] | None:
    """The first custom property ``value`` reads, and whether it has a fallback."""
    match = _VAR.search(value)
    return (match.group(1), bool(match.group(2))) if match else None


def _follow(
    styles: Sequence[Sequence[Declaration]],
    chain: Sequence[int],
    start: int,
    prop: str,
    hops: list[Declaration],
) -> bool:
    """Append the winning declarations of ``prop`` from ``chain[start]`` on; True at a value."""
    for k in range(start, len(chain)):
        if len(hops) >= MAX_HOPS:
            return False
        found = winner(styles[chain[k]], prop)
        if found is None:
            if _inherits(prop):
                continue
            return False  # the initial value: nothing in the project sets it
        word = found.value.strip().lower()
        if word in _INHERIT_WORDS or (word == "unset" and _inherits(prop)):
            continue
        if prop == "color" and word == "currentcolor":
            continue  # CSS Color 4, 4.4: "color: currentcolor" is "color: inherit"
        hops.append(found)
        if found.kind == "ua":
            return False  # the engine's own colour (a link, a button)
        referenced = _first_var(found.value)
        if referenced is not None:
            name, fallback = referenced
            before = len(hops)
            if _follow(styles, chain, k, name, hops):
                return True
            # An undefined custom property: the var()'s fallback is the value.
            return fallback and len(hops) == before
        if prop != "color" and _CURRENT.search(found.value):
            # currentColor is inherited as a keyword and resolved where it is used.
            return _follow(styles, chain, 0, "color", hops)
        return True
    return False


def trace(
    styles: Sequence[Sequence[Declaration]],
    chain: Sequence[int],
    prop: str,
    computed: str | None = None,
) -> Trace:
    """Follow ``prop`` from ``chain[0]`` (indices into ``styles``, up the tree) to a value.

    >>> rule = lambda p, v, pos=0: Declaration(p, p, v, False, "rule", (1 << 30,), pos)
    >>> hint = Declaration("stroke", "stroke", "currentColor", False, "hint", (1 << 30,), -1)
    >>> styles = [[], [hint], [rule("color", "var(--icon)")], [rule("--icon", "#8b949e")]]
    >>> t = trace(styles, [0, 1, 2, 3], "stroke")
    >>> [(d.property, d.value) for d in t.hops], t.complete
    ([('stroke', 'currentColor'), ('color', 'var(--icon)'), ('--icon', '#8b949e')], True)
    """
    hops: list[Declaration] = []
    complete = _follow(styles, chain, 0, prop, hops) if chain else False
    return Trace(prop, tuple(hops), computed, complete)


# ------------------------------------------------------------------ engine data
def _int(value: object, default: int = 0) -> int:
    return int(value) if isinstance(value, int | float) and not isinstance(value, bool) else default


def _text(value: object) -> str | None:
    return value if isinstance(value, str) else None


def _declaration(raw: Mapping[str, Any], sheets: Sequence[Mapping[str, Any]], page: str) -> (
    Declaration | None
):  # fmt: skip
    prop, value = raw.get("property"), raw.get("value")
    if not isinstance(prop, str) or not isinstance(value, str):
        return None
    kind = str(raw.get("kind", "rule"))
    layer = raw.get("layer")
    place = None
    if kind == "rule":
        k = raw.get("sheet")
        sheet = sheets[k] if isinstance(k, int) and 0 <= k < len(sheets) else None
        url = _text(sheet.get("url")) if sheet is not None else None
        if url:
            place = ServedPlace(
                url,
                inline=bool(sheet.get("inline")) if sheet is not None else False,
                line=_int(raw["line"]) if isinstance(raw.get("line"), int) else None,
                column=_int(raw["column"]) if isinstance(raw.get("column"), int) else None,
                text=_text(raw.get("text")),
                rule=_int(raw["rule"]) if isinstance(raw.get("rule"), int) else None,
                selector=_text(raw.get("selector")),
                sheet_text=_text(sheet.get("text")) if sheet is not None else None,
            )
    elif kind in ("attribute", "hint") and page:
        place = ServedPlace(page, inline=True, text=_text(raw.get("text")))
    return Declaration(
        prop,
        str(raw.get("name", prop)),
        value,
        bool(raw.get("important")),
        kind,
        tuple(_int(x) for x in layer) if isinstance(layer, list) else (0,),
        _int(raw.get("position")),
        place,
    )


def parse_styles(data: JSONValue, page: str) -> list[list[Declaration]] | None:
    """The per-element declarations of a ``cascade()`` or ``matched_styles`` answer."""
    if not isinstance(data, dict) or not isinstance(data.get("nodes"), list):
        return None
    answer: dict[str, Any] = data
    sheets = [s for s in answer.get("sheets") or [] if isinstance(s, dict)]
    return [
        [
            d
            for raw in (node if isinstance(node, list) else [])
            if isinstance(raw, dict) and (d := _declaration(raw, sheets, page)) is not None
        ]
        for node in answer["nodes"]
    ]


def _chain(value: object, count: int) -> list[int]:
    if not isinstance(value, list):
        return []
    return [int(k) for k in value if isinstance(k, int) and 0 <= k < count]


def _icon_sources(
    styles: Sequence[Sequence[Declaration]], found: object, paints: Sequence[Mapping[str, Any]]
) -> IconSources | None:
    """One icon's traces from the probe's ``targets()`` entry for it."""
    if not isinstance(found, dict):
        return None
    chains: list[Any] = found["paints"] if isinstance(found.get("paints"), list) else []
    traced: list[Trace | None] = []
    for k, paint in enumerate(paints):
        per: dict[str, Any] = chains[k] if k < len(chains) and isinstance(chains[k], dict) else {}
        first = next(iter(per), None)
        traced.append(
            None
            if first is None
            else trace(styles, _chain(per[first], len(styles)), first, _text(paint.get("color")))
        )
    backdrop: Any = found.get("backdrop")
    back = None
    if isinstance(backdrop, dict) and isinstance(backdrop.get("property"), str):
        chain = _chain(backdrop.get("chain"), len(styles))
        back = trace(styles, chain, backdrop["property"], _text(backdrop.get("color")))
    return IconSources(tuple(traced), back)


def collect_sources(
    browser: Browser, probe: str, paints: Sequence[Sequence[Mapping[str, Any]]], page: str
) -> tuple[IconSources | None, ...]:
    """The sources of every icon the probe found last (``probe`` names its global).

    ``paints`` are the probe's paints of each icon (their ``color`` is the
    computed colour a trace is checked against); ``page`` is the page's URL.
    An answer that does not fit the icons gives ``None`` for each: no trace
    is better than a wrong one.
    """
    isolated = browser.ISOLATED_SCRIPTS
    none: tuple[IconSources | None, ...] = tuple(None for _ in paints)
    targets: Any = browser.evaluate(f"{probe}.targets()", isolated=isolated)
    if not isinstance(targets, dict) or not isinstance(targets.get("icons"), list):
        return none
    pseudos = [p if isinstance(p, str) else None for p in targets.get("pseudos") or []]
    data: JSONValue = browser.matched_styles(f"{probe}.nodes()", pseudos)
    if data is None:
        data = browser.evaluate(f"{probe}.cascade()", isolated=isolated)
    styles = parse_styles(data, page)
    icons: list[Any] = targets["icons"]
    if styles is None or len(styles) != len(pseudos) or len(icons) != len(paints):
        return none
    return tuple(_icon_sources(styles, f, own) for f, own in zip(icons, paints, strict=True))
