"""Matched CSS declarations from the DevTools protocol, in the shape of the page probe's walk.

``CSS.getMatchedStylesForNode`` answers with the rules matching a node in
the order the engine cascades them (CSS Cascade 5, 6: layers in layer
order, unlayered rules last, then specificity, then order of appearance: the
order DevTools' Styles pane shows them in, reversed), its ``style``
attribute and its presentational hints (SVG ``fill=``, ``stroke=``).  Each
written declaration has a source range in its style sheet; an inline sheet's
(``<style>``) ranges count from the sheet's own start, which its header
(``CSS.styleSheetAdded``) places in the page.

:func:`declarations` turns one answer into the list ``pages/probe.js``'s
``cascade()`` gives per element, so that one walker
(:mod:`alpha_audit.pages.cascade`) reads both: ``property`` (what the
declaration sets: a colour property, a background longhand, a custom
property), ``name`` as written, ``value``, ``important``, ``kind`` (``rule``,
``attribute``, ``hint``, ``ua``), ``layer`` (a sort key of its cascade
layer), ``position`` (its rank among the matched rules) and, for rules,
``sheet`` (an index into ``sheets``), ``line`` and ``column`` (0-based, UTF-16
code units, in the served file) and ``text`` (the declaration as written).
"""

from __future__ import annotations

import re
from typing import Any

__all__ = ["LAST_LAYER", "declarations", "sheet_entry"]

# A layer's own rules sort after its sublayers; unlayered rules after every layer
# (the probe's LAST: one sort key for both routes).
LAST_LAYER = 1 << 30
_TRACED = frozenset({"color", "fill", "stroke", "background-color", "background-image"})
_BACKGROUND = ("background-color", "background-image")
_HINTS = frozenset({"fill", "stroke", "color"})
_IMPORTANT = re.compile(r"\s*!\s*important\s*$", re.IGNORECASE)
MAX_VALUE = 2000  # characters of a declared value kept (a data: URL can be huge)


def _sets(name: str) -> tuple[str, ...]:
    """The traced properties a written declaration sets (a shorthand sets its longhands)."""
    if name.startswith("--"):
        return (name,)
    lower = name.lower()
    if lower == "background":
        return _BACKGROUND
    return (lower,) if lower in _TRACED else ()


def _value(prop: dict[str, Any]) -> tuple[str, bool]:
    value = str(prop.get("value", ""))
    important = bool(prop.get("important"))
    if important:
        value = _IMPORTANT.sub("", value)
    return value.strip()[:MAX_VALUE], important


def sheet_entry(header: dict[str, Any] | None) -> dict[str, Any]:
    """A ``sheets`` entry (``url``, ``inline``) from a ``CSSStyleSheetHeader``."""
    if header is None:
        return {"url": None, "inline": False, "text": None}
    return {"url": header.get("sourceURL") or None, "inline": bool(header.get("isInline"))}


def _written(style: dict[str, Any]) -> list[dict[str, Any]]:
    """The declarations a style holds as written (those with a source range), valid ones."""
    return [
        p
        for p in style.get("cssProperties", ())
        if "range" in p and p.get("parsedOk", True) and not p.get("disabled")
    ]


def declarations(
    matched: dict[str, Any],
    pseudo: str | None,
    headers: dict[str, dict[str, Any]],
    sheets: dict[str, int],
    attributes: dict[str, str] | None = None,
) -> list[dict[str, Any]]:
    """One node's declarations of traced properties, from a ``getMatchedStylesForNode`` reply.

    ``pseudo`` takes the rules of that pseudo-element of the node instead;
    ``headers`` are the style sheet headers by id, ``sheets`` the index of
    each id in the answer's ``sheets`` list (added to as sheets are met).
    ``attributes`` are the node's attributes as written (``DOM.getAttributes``):
    a presentational hint's value is the engine's serialisation
    (``rgb(170, 51, 0)`` for ``stroke="#a30"``), the attribute says what the
    markup holds.
    """
    if pseudo is None:
        rules = matched.get("matchedCSSRules") or []
    else:
        pseudos = matched.get("pseudoElements") or []
        rules = next((p.get("matches") or [] for p in pseudos if p.get("pseudoType") == pseudo), [])
    out: list[dict[str, Any]] = []
    layers: dict[tuple[str, ...], int] = {}
    position = 0
    for match in rules:
        rule = match.get("rule") or {}
        origin = rule.get("origin")
        if origin == "user-agent":
            # The engine's own colours (links, form controls, <mark>): where they win,
            # the colour is nobody's declaration in the project.
            for prop in rule.get("style", {}).get("cssProperties", ()):
                if prop.get("name") == "color":
                    out.append(_declared("color", "color", str(prop.get("value")), "ua", -2))
        elif origin == "regular":  # injected (extensions) and inspector rules are no page's
            out += _rule_declarations(rule, position, layers, headers, sheets)
            position += 1
    if pseudo is None:
        out += _inline_and_hints(matched, position, attributes or {})
    return out


def _declared(
    target: str, name: str, value: str, kind: str, position: int, *, important: bool = False
) -> dict[str, Any]:
    return {"property": target, "name": name, "value": value, "important": important,
            "kind": kind, "layer": [LAST_LAYER], "position": position}  # fmt: skip


def _rule_declarations(
    rule: dict[str, Any],
    position: int,
    layers: dict[tuple[str, ...], int],
    headers: dict[str, dict[str, Any]],
    sheets: dict[str, int],
) -> list[dict[str, Any]]:
    """The traced declarations of one author rule, with their sheet, line and column."""
    path = tuple(str(layer.get("text", "")) for layer in reversed(rule.get("layers") or []))
    layer = [layers.setdefault(path, len(layers)), LAST_LAYER] if path else [LAST_LAYER]
    sheet_id = str(rule.get("styleSheetId", ""))
    header = headers.get(sheet_id) or {}
    sheets.setdefault(sheet_id, len(sheets))
    start_line, start_column = int(header.get("startLine", 0)), int(header.get("startColumn", 0))
    selector = str(rule.get("selectorList", {}).get("text", ""))
    out = []
    for prop in _written(rule.get("style", {})):
        value, important = _value(prop)
        line = int(prop["range"]["startLine"])
        column = int(prop["range"]["startColumn"]) + (start_column if line == 0 else 0)
        for target in _sets(str(prop.get("name", ""))):
            out.append(
                _declared(target, str(prop["name"]), value, "rule", position, important=important)
                | {"layer": layer, "sheet": sheets[sheet_id], "line": start_line + line,
                   "column": column, "text": str(prop.get("text", "")), "selector": selector}
            )  # fmt: skip
    return out


def _inline_and_hints(
    matched: dict[str, Any], position: int, attributes: dict[str, str]
) -> list[dict[str, Any]]:
    """The node's ``style=`` declarations and its presentational hints (``fill="…"``)."""
    out = []
    inline = matched.get("inlineStyle") or {}
    for prop in _written(inline):
        value, important = _value(prop)
        for target in _sets(str(prop.get("name", ""))):
            out.append(
                _declared(target, str(prop["name"]), value, "attribute", position,
                          important=important)
                | {"text": str(inline.get("cssText", ""))[:MAX_VALUE]}
            )  # fmt: skip
    for prop in (matched.get("attributesStyle") or {}).get("cssProperties", ()):
        name = str(prop.get("name", ""))
        if name in _HINTS:
            value = attributes.get(name, str(prop.get("value", "")))
            out.append(_declared(name, name, value[:MAX_VALUE], "hint", -1))
    return out
