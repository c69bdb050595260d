"""Which browser states a stylesheet's rules describe, and which rules match in each.

A CSS *mode* is a state a page can be in: classes and ``data-*`` attributes on
the root element (``<html>``, or a shadow host: ``:host(...)`` is read as the
root) and on ``<body>``, the ``prefers-color-scheme`` and a wide-gamut
display.  Its values are the custom properties as ``<body>`` computes them:
every rule matching ``<html>`` or ``<body>`` in that state, in cascade order,
the body's own declarations winning over what it inherits.

Selectors are matched here as a browser matches them (Selectors Level 4),
item by item of a selector list, on two elements whose classes and
attributes the state gives; nothing is inferred from names.  So a compound
theme ``:root:where(.dark.felt)`` is the state with both classes, and in it
``:root:where(.dark)`` matches too.  What a static state cannot decide
(``:hover``, ``:has()``, an element other than the root or body, a
combinator) makes the selector item match nothing: such rules are not modes.

Each selector item that can match gives the *least* state in which it does
(its classes and attributes, and for ``:is()`` one state per alternative):
these are the candidate modes.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator
from dataclasses import dataclass
from itertools import combinations, product
from typing import Any

from alpha_audit.load.tokens.model import ModeConditions

__all__ = [
    "Element",
    "Item",
    "analyse",
    "least_conditions",
    "matches",
    "state_elements",
    "state_keys",
    "subsets",
]

# Conditions per item kept when computing its least states (an :is() of :is()
# multiplies alternatives): more is a generated selector, not a theme.
_MAX_ALTERNATIVES = 64


@dataclass(frozen=True)
class Element:
    """``<html>`` or ``<body>`` in one state: what a selector can test."""

    tag: str  # "html" or "body"
    classes: frozenset[str]
    attributes: dict[str, str]  # lower-case name -> value

    @property
    def root(self) -> bool:
        return self.tag == "html"


def state_elements(state: ModeConditions) -> tuple[Element, Element]:
    """The ``<html>`` and ``<body>`` of ``state``."""
    return (
        Element("html", frozenset(state.root_classes), dict(state.root_attributes)),
        Element("body", frozenset(state.body_classes), dict(state.body_attributes)),
    )


# A least state's conditions on one element: classes and attributes.
_Side = tuple[frozenset[str], tuple[tuple[str, str], ...]]


@dataclass(frozen=True)
class Item:
    """One selector of a selector list: its tree, specificity and least states.

    ``states`` holds ``(root side, body side)`` pairs and ``words`` the class
    names and attribute values of each in selector order (a mode's name);
    ``keys`` the class and attribute names each needs (to find, for a state,
    the items that may match).
    """

    tree: Any
    specificity: tuple[int, int, int]
    states: tuple[tuple[_Side, _Side], ...]
    words: tuple[tuple[str, ...], ...]

    @property
    def keys(self) -> tuple[frozenset[str], ...]:
        return tuple(_keys(root) | _keys(body) for root, body in self.states)


def _keys(side: _Side) -> frozenset[str]:
    classes, attributes = side
    return frozenset({f".{c}" for c in classes} | {f"[{a}" for a, _ in attributes})


def state_keys(state: ModeConditions) -> frozenset[str]:
    """The keys of :attr:`Item.keys` that ``state`` provides."""
    return _keys((frozenset(state.root_classes), state.root_attributes)) | _keys(
        (frozenset(state.body_classes), state.body_attributes)
    )


def subsets(keys: frozenset[str]) -> Iterator[frozenset[str]]:
    """Every subset of ``keys`` (a state has a handful of conditions)."""
    ordered = sorted(keys)
    for n in range(len(ordered) + 1):
        for chosen in combinations(ordered, n):
            yield frozenset(chosen)


# ------------------------------------------------------------------ matching
def matches(tree: Any, element: Element) -> bool | None:
    """Whether a selector tree matches ``element`` (None: not decidable from a state)."""
    from cssselect2 import parser as sel

    if not isinstance(tree, sel.CompoundSelector):
        return None  # a combinator: about elements other than the root and body
    result: bool | None = True
    for simple in tree.simple_selectors:
        got = _simple(simple, element)
        if got is False:
            return False
        if got is None:
            result = None
    return result


def _any(trees: Iterable[Any], element: Element) -> bool | None:
    result: bool | None = False
    for tree in trees:
        got = matches(tree, element)
        if got:
            return True
        if got is None:
            result = None
    return result


def _simple(simple: Any, element: Element) -> bool | None:
    from cssselect2 import parser as sel

    if isinstance(simple, sel.LocalNameSelector):
        return bool(simple.lower_local_name == element.tag)
    if isinstance(simple, sel.ClassSelector):
        return str(simple.class_name) in element.classes
    if isinstance(simple, sel.AttributeSelector):
        return _attribute(simple, element)
    if isinstance(simple, sel.PseudoClassSelector):
        if simple.name in ("root", "host", "scope"):
            return element.root
        return None  # :hover, :checked, :first-child ...: a state of the page
    if isinstance(simple, sel.FunctionalPseudoClassSelector):
        if simple.name == "host":  # :host(X): the root, when it matches X
            inner = _host_argument(simple)
            return None if inner is None else (element.root and _any(inner, element))
        return None  # :nth-child(), :lang(), :dir() ...
    if isinstance(simple, sel.NegationSelector):
        got = _any(_trees(simple.selector_list), element)
        return None if got is None else not got
    if isinstance(simple, sel.MatchesAnySelector | sel.SpecificityAdjustmentSelector):
        return _any(_trees(simple.selector_list), element)
    if isinstance(simple, sel.NamespaceSelector):
        return True  # the HTML namespace: every element we match is in it
    return None  # an id, :has() ...


def _attribute(simple: Any, element: Element) -> bool:
    name = str(simple.lower_name)
    if name not in element.attributes:
        return False
    if simple.operator is None:
        return True
    have, want = element.attributes[name], str(simple.value)
    if simple.case_sensitive is False:
        have, want = have.lower(), want.lower()
    op = simple.operator
    if op == "=":
        return have == want
    if op == "~=":
        return want in have.split()
    if op == "|=":
        return have == want or have.startswith(f"{want}-")
    if not want:
        return False  # [a^=""], [a$=""], [a*=""] match nothing (Selectors 4, 6.2)
    if op == "^=":
        return have.startswith(want)
    if op == "$=":
        return have.endswith(want)
    return want in have  # *=


def _trees(selector_list: Iterable[Any]) -> list[Any]:
    return [getattr(s, "parsed_tree", s) for s in selector_list]


def _host_argument(simple: Any) -> list[Any] | None:
    from cssselect2 import parser as sel

    try:
        return [s.parsed_tree for s in sel.parse(list(simple.arguments))]
    except sel.SelectorError:
        return None


# ------------------------------------------------------------ least states
# classes, attributes, element ("html", "body" or "any") and the names in selector order
_Least = tuple[frozenset[str], tuple[tuple[str, str], ...], str, tuple[str, ...]]


def analyse(selector: Any) -> Item | None:
    """The item of one parsed selector, or None when it matches neither root nor body."""
    if selector.pseudo_element is not None:
        return None
    tree = selector.parsed_tree
    states: list[tuple[_Side, _Side]] = []
    words: list[tuple[str, ...]] = []
    empty: _Side = (frozenset(), ())
    for classes, attributes, on, named in _least(tree):
        # A condition of an item that names no element (".dark") goes on the root.
        side: _Side = (classes, tuple(sorted(attributes)))
        state = (empty, side) if on == "body" else (side, empty)
        html, body = state_elements(least_conditions(state))
        if matches(tree, body if on == "body" else html) and state not in states:
            states.append(state)
            words.append(named)
    if not states:
        return None
    return Item(tree, _specificity(selector), tuple(states), tuple(words))


def least_conditions(state: tuple[_Side, _Side]) -> ModeConditions:
    """A least state (:attr:`Item.states`) as the conditions of a mode (light, no P3)."""
    (rc, ra), (bc, ba) = state
    return ModeConditions(tuple(sorted(rc)), ra, tuple(sorted(bc)), ba)


def _least(tree: Any) -> list[_Least]:
    """The least states (one per alternative) in which a compound selector can match."""
    from cssselect2 import parser as sel

    if not isinstance(tree, sel.CompoundSelector):
        return []
    alternatives: list[tuple[frozenset[str], dict[str, str], str, tuple[str, ...]]] = [
        (frozenset(), {}, "any", ())
    ]
    for simple in tree.simple_selectors:
        options = _least_simple(simple)
        if options is None:
            return []
        merged = []
        for (classes, attrs, on, named), (c2, a2, on2, n2) in product(alternatives, options):
            where = on if on2 == "any" else on2 if on in ("any", on2) else None
            if where is None:
                continue  # html and body at once
            joined = dict(attrs)
            for k, v in a2:
                if joined.get(k, "") == "":  # a value beats mere presence ([data-x])
                    joined[k] = v
            merged.append((classes | c2, joined, where, named + n2))
        alternatives = merged[:_MAX_ALTERNATIVES]
    return [
        (c, tuple(a.items()), "html" if on == "any" else on, named)
        for c, a, on, named in alternatives
    ]


def _least_simple(simple: Any) -> list[_Least] | None:
    """What a simple selector asks of a state, per alternative (None: no state has it)."""
    from cssselect2 import parser as sel

    if isinstance(simple, sel.LocalNameSelector):
        tag = simple.lower_local_name
        return [(frozenset(), (), tag, ())] if tag in ("html", "body") else None
    if isinstance(simple, sel.ClassSelector):
        name = str(simple.class_name)
        return [(frozenset({name}), (), "any", (name,))]
    if isinstance(simple, sel.AttributeSelector):
        name = str(simple.lower_name)
        if not name.startswith("data-"):
            return None  # [role=search], [type=checkbox], [dir=rtl]: elements, not modes
        if simple.operator is None:
            return [(frozenset(), ((name, ""),), "any", ())]  # presence: no name of a mode
        return [(frozenset(), ((name, str(simple.value)),), "any", (str(simple.value),))]
    if isinstance(simple, sel.PseudoClassSelector):
        root = simple.name in ("root", "host", "scope")
        return [(frozenset(), (), "html", ())] if root else None
    if isinstance(simple, sel.FunctionalPseudoClassSelector):
        inner = _host_argument(simple) if simple.name == "host" else None
        found = [x for tree in inner or [] for x in _least(tree) if x[2] == "html"]
        return found or None
    if isinstance(simple, sel.MatchesAnySelector | sel.SpecificityAdjustmentSelector):
        return [x for tree in _trees(simple.selector_list) for x in _least(tree)] or None
    if isinstance(simple, sel.NegationSelector | sel.NamespaceSelector):
        # :not() asks for an absence: the least state has none of it
        return [(frozenset(), (), "any", ())]
    return None


def _specificity(selector: Any) -> tuple[int, int, int]:
    """Selectors 4 specificity; ``:host(X)`` counts X as well (CSS Scoping 1, 3.5)."""
    from cssselect2 import parser as sel

    a, b, c = selector.specificity
    tree = selector.parsed_tree
    for simple in getattr(tree, "simple_selectors", ()):
        if isinstance(simple, sel.FunctionalPseudoClassSelector) and simple.name == "host":
            try:
                found = [s.specificity for s in sel.parse(list(simple.arguments))]
            except sel.SelectorError:
                found = []
            if found:
                x, y, z = max(found)
                a, b, c = a + x, b + y, c + z
    return (a, b, c)
