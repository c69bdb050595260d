"""CSS custom properties as design tokens: Tailwind v4 ``@theme``, palettes and theme sheets.

The CSS is tokenised by tinycss2 (CSS Syntax Level 3) and selectors are
parsed by cssselect2, never by regular expressions.  Every custom property
is read; ``var()`` is substituted as a browser does (fallbacks included) and
a property is a *colour token* when what it ends in is a colour.  Custom
properties are untyped, so a length stays a length: it only matters when a
config selects it, and then the error names its ``var()`` chain.

``--color-red-500`` is the token ``color.red.500`` (dashes to dots, the
inverse of the export's naming); the name is unescaped first (CSS Syntax 3,
4.3.7), so ``--color-icon\\2e fg`` is ``color-icon.fg`` and two properties
that map to one token path are an error naming both.

Modes are the states a browser can be in (:mod:`.cssmodes`): classes and
``data-*`` attributes on the root element (``:root``, ``html``, ``:host(...)``)
and on ``<body>``, ``prefers-color-scheme`` and a wide-gamut display.  Every
selector item of every rule gives the least state in which it matches (a
selector list is read item by item); a state whose rules set no colour is no
mode.  A mode's values are the custom properties ``<body>`` computes in that
state: every rule matching ``<html>`` (inherited) or ``<body>`` (its own
declarations win), in cascade order, so a compound theme
``:root:where(.dark.felt)`` gets ``:root:where(.dark)`` too.

- the page without conditions is the mode ``default`` (``@theme`` is the root);
- a state is named by its classes and attribute values (``dark``,
  ``pf-v6-theme-dark-pf-v6-theme-felt``); ``prefers-color-scheme: dark`` adds
  ``-dark`` (the page without conditions: ``dark``), a wide-gamut display
  ``-p3``; a name taken by another state is written out in full;
- a state that computes every property exactly as an earlier one (``.dark,
  .dark-theme``) is an alias of it (:attr:`~.model.TokenModes.aliases`);
- ``light-dark(a, b)`` values take ``a`` or ``b`` by the mode's scheme and give
  every state a dark variant;
- ``@layer`` blocks are read in layer order (CSS Cascade 5: later layers
  win, unlayered rules beat layered ones), then specificity, then source order;
- what a static state cannot decide (``:hover``, ``:has()``, a combinator, an
  element other than the root or body, other ``@media`` conditions such as
  widths, print or motion, ``@supports not``, ``@container``, ``@scope``) is no
  mode: its rules are skipped, and a selected token they would set is warned about.

Every ``var()`` substitution and every declaration applied to a mode is
counted (:data:`~.model.MAX_EXPANSION`, all modes together), a ``var()``
chain is at most :data:`~.model.MAX_ALIAS_CHAIN` long and a resolved value at
most :data:`MAX_VALUE_TOKENS` component values, so a few kilobytes of
properties that double at every level, or thousands of modes that each apply
every declaration, end in an error.  Modes, layers and selector lists are
indexed once, so the walk is linear in the sheet.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any, NamedTuple

from alpha_audit.errors import InputError
from alpha_audit.load.files import read_capped
from alpha_audit.load.names import check_name
from alpha_audit.load.spans import LineIndex
from alpha_audit.load.tokens.cssmodes import (
    Element,
    Item,
    analyse,
    least_conditions,
    matches,
    state_elements,
    state_keys,
    subsets,
)
from alpha_audit.load.tokens.model import (
    MAX_ALIAS_CHAIN,
    MAX_TOKENS,
    ModeConditions,
    Steps,
    Token,
    TokenModes,
    TokenPlace,
    check_mode_budget,
    too_long,
)
from alpha_audit.model import Span
from alpha_audit.safe_text import safe_text

__all__ = ["MAX_CSS_BYTES", "MAX_VALUE_TOKENS", "modes_from_stylesheet"]

MAX_CSS_BYTES = 4 << 20
# Component values in one resolved custom property: a colour is a handful,
# a shadow or a font stack a few dozen.
MAX_VALUE_TOKENS = 1_000
# Nested at-rules (@layer in @media in @supports ...) followed.
_MAX_AT_DEPTH = 16
_LAST = 1 << 30  # sorts after every layer index: unlayered rules and a layer's own rules

_ROOT_NAMES = frozenset({"html", ":root", "root", "host"})
_SKIPPED_AT = frozenset({"container", "scope", "starting-style", "keyframes", "font-face"})
_P3_FEATURES = frozenset({"color-gamut", "dynamic-range", "video-dynamic-range"})
_MEDIA_WORDS = frozenset({"screen", "all", "only", "and", "or"})


@dataclass(frozen=True)
class _Decl:
    """One custom property declaration of one rule."""

    name: str  # without the leading "--", unescaped
    value: tuple[Any, ...]  # tinycss2 component values, outer whitespace stripped
    line: int
    span: Span | None
    order: tuple[tuple[int, ...], tuple[int, int, int], int]  # layer, specificity, source
    literal: bool  # no var() or light-dark(): the value can be rewritten in place


@dataclass
class _Part:
    """The custom properties one selector item of a rule sets (``@theme``: the root)."""

    item: Item
    scheme: str | None  # only under this prefers-color-scheme
    p3: bool
    where: str  # for notes: "line 12 [data-theme=dark]"
    decls: list[_Decl] = field(default_factory=list)


@dataclass
class _Sheet:
    """What one walk over a stylesheet collects."""

    path: Path
    index: LineIndex | None
    parts: list[_Part] = field(default_factory=list)
    skipped: dict[str, str] = field(default_factory=dict)  # property -> why not read
    layer_ranks: dict[tuple[str, ...], int] = field(default_factory=dict)
    layer_children: dict[tuple[str, ...], int] = field(default_factory=dict)  # per parent
    anonymous: int = 0
    source: int = 0
    light_dark: bool = False

    def layer_key(self, layers: tuple[str, ...]) -> tuple[int, ...]:
        ranks = []
        for i in range(len(layers)):
            path = layers[: i + 1]
            if path not in self.layer_ranks:
                siblings = self.layer_children.get(path[:i], 0)
                self.layer_children[path[:i]] = siblings + 1
                self.layer_ranks[path] = siblings
            ranks.append(self.layer_ranks[path])
        return (*ranks, _LAST)


# ----------------------------------------------------------------- selectors
def _rule_items(prelude: Sequence[Any]) -> list[Item]:
    """The items of a rule's selector list that can match the root or body (item by item)."""
    from cssselect2 import parser as sel

    try:
        selectors = list(sel.parse(list(prelude)))
    except sel.SelectorError:
        return []
    return [item for s in selectors if (item := analyse(s)) is not None]


def _theme_item() -> Item:
    """Tailwind's ``@theme``: the root, with the specificity of ``:root``."""
    from cssselect2 import parser as sel

    item = analyse(next(iter(sel.parse(":root"))))
    assert item is not None
    return item


# -------------------------------------------------------------- conditions
def _media(prelude: Sequence[Any]) -> tuple[str | None, bool] | None:
    """``(scheme, p3)`` of a media query, or None when it is no colour mode."""
    scheme: str | None = None
    p3 = False
    for token in prelude:
        if token.type in ("whitespace", "comment") or (
            token.type == "literal" and token.value == ","
        ):
            continue
        if token.type == "ident" and token.lower_value in _MEDIA_WORDS:
            continue
        if token.type != "() block":
            return None  # print, not, a media type we do not draw
        parts = [t for t in token.content if t.type not in ("whitespace", "comment")]
        if len(parts) != 3 or parts[0].type != "ident" or parts[2].type != "ident":
            return None
        feature, value = parts[0].lower_value, parts[2].lower_value
        if feature == "prefers-color-scheme" and value in ("light", "dark"):
            scheme = value
        elif feature in _P3_FEATURES and value in ("p3", "rec2020", "high"):
            p3 = True
        else:
            return None
    return scheme, p3


def _supports(prelude: Sequence[Any]) -> tuple[bool, bool]:
    """``(applies, p3)`` of an ``@supports`` condition."""
    import tinycss2

    text = tinycss2.serialize(prelude).lower()
    first = next((t for t in prelude if t.type not in ("whitespace", "comment")), None)
    if first is not None and first.type == "ident" and first.lower_value == "not":
        return False, False
    return True, "display-p3" in text


# ------------------------------------------------------------------ walking
class _Scope(NamedTuple):
    """Where a rule sits: its layers, the colour scheme and P3 of the @media around it,
    and why its properties are skipped (None: they are read)."""

    layers: tuple[str, ...] = ()
    scheme: str | None = None
    p3: bool = False
    skip: str | None = None


def _walk(
    sheet: _Sheet,
    rules: Iterable[Any],
    *,
    layers: tuple[str, ...],
    scheme: str | None,
    p3: bool,
    skip: str | None,
    depth: int,
) -> None:
    import tinycss2

    if depth > _MAX_AT_DEPTH:
        raise InputError(f"at-rules nested deeper than {_MAX_AT_DEPTH} levels", path=sheet.path)
    scope = _Scope(layers, scheme, p3, skip)
    for rule in rules:
        if rule.type == "at-rule":
            inner = _at_rule(sheet, rule, scope)
            if inner is not None:
                _walk(sheet, inner[0], **inner[1]._asdict(), depth=depth + 1)
        elif rule.type == "qualified-rule":
            items = _rule_items(rule.prelude)
            selector = " ".join(tinycss2.serialize(rule.prelude).split())
            why = skip or (None if items else f"selector {selector[:60]}")
            _add(sheet, rule, items, scope._replace(skip=why))


def _at_rule(sheet: _Sheet, rule: Any, scope: _Scope) -> tuple[list[Any], _Scope] | None:
    """An at-rule read: the rules inside it to walk and their scope, or None (nothing)."""
    import tinycss2

    keyword = rule.lower_at_keyword
    prelude = rule.prelude
    if keyword == "layer":
        names = _layer_names(sheet, prelude)
        if rule.content is None:  # "@layer a, b;" fixes the order
            for name in names:
                sheet.layer_key((*scope.layers, *name))
            return None
        inner_layers = (*scope.layers, *(names[0] if names else ()))
        return _rule_list(rule.content), scope._replace(layers=inner_layers)
    if rule.content is None:
        return None
    if keyword == "theme":  # Tailwind v4: theme variables on :root
        _add(sheet, rule, [_theme_item()], scope)
        return None
    if keyword == "media":
        found = _media(prelude)
        why = scope.skip or (
            f"@media {tinycss2.serialize(prelude).strip()}" if found is None else None
        )
        s, is_p3 = found if found is not None else (None, False)
        inner = _Scope(scope.layers, s or scope.scheme, scope.p3 or is_p3, why)
        return _rule_list(rule.content), inner
    if keyword == "supports":
        applies, is_p3 = _supports(prelude)
        why = scope.skip or (
            None if applies else f"@supports {tinycss2.serialize(prelude).strip()}"
        )
        return _rule_list(rule.content), scope._replace(p3=scope.p3 or is_p3, skip=why)
    if keyword in _SKIPPED_AT:
        inner_rules = _rule_list(rule.content) if keyword in ("container", "scope") else []
        return inner_rules, scope._replace(skip=scope.skip or f"@{keyword}")
    return None


def _rule_list(content: Sequence[Any]) -> list[Any]:
    import tinycss2

    return list(tinycss2.parse_rule_list(content, skip_comments=True, skip_whitespace=True))


def _layer_names(sheet: _Sheet, prelude: Sequence[Any]) -> list[tuple[str, ...]]:
    """``@layer a.b, c`` -> ``[("a", "b"), ("c",)]``; an anonymous layer gets its own name."""
    names: list[tuple[str, ...]] = [()]
    for token in prelude:
        if token.type == "ident":
            names[-1] = (*names[-1], token.value)
        elif token.type == "literal" and token.value == ",":
            names.append(())
    if names == [()]:
        sheet.anonymous += 1
        return [(f" anonymous {sheet.anonymous}",)]
    return [n for n in names if n]


def _add(sheet: _Sheet, rule: Any, items: Sequence[Item], scope: _Scope) -> None:
    """Record the custom properties of ``rule`` for each of its items (or as skipped)."""
    import tinycss2

    layers, scheme, p3, skip = scope.layers, scope.scheme, scope.p3, scope.skip

    decls = [
        node
        for node in tinycss2.parse_blocks_contents(
            rule.content, skip_comments=True, skip_whitespace=True
        )
        if node.type == "declaration" and node.name.startswith("--")
    ]
    if not decls:
        return
    line = rule.source_line
    if skip is not None:
        for node in decls:
            sheet.skipped.setdefault(node.name[2:], f"line {node.source_line}, {skip}")
        return
    layer = sheet.layer_key(layers)
    read = []  # (node, value, source order): the same for every item of the list
    for node in decls:
        if "*" in node.name:  # Tailwind's "--color-*: initial" resets a namespace
            continue
        value = _strip(node.value)
        if len(value) == 1 and value[0].type == "ident" and value[0].lower_value == "initial":
            continue
        sheet.source += 1
        if not sheet.light_dark and _uses_light_dark(value):
            sheet.light_dark = True
        read.append((node, value, sheet.source))
    media = f"@media (prefers-color-scheme: {scheme}) " if scheme else ""
    shown = tinycss2.serialize(rule.prelude).split() if rule.type == "qualified-rule" else []
    where = f"line {line} {media}{' '.join(shown)[:60] or '@theme'}"
    for item in items:
        part = _Part(item, scheme, p3, where)
        for node, value, source in read:
            part.decls.append(
                _Decl(
                    node.name[2:],
                    tuple(value),
                    node.source_line,
                    _value_span(value, sheet.index),
                    (layer, item.specificity, source),
                    _literal(value),
                )
            )
        sheet.parts.append(part)


def _strip(tokens: Sequence[Any]) -> list[Any]:
    out = [t for t in tokens if t.type != "comment"]
    while out and out[0].type == "whitespace":
        out.pop(0)
    while out and out[-1].type == "whitespace":
        out.pop()
    return out


def _uses_light_dark(tokens: Iterable[Any]) -> bool:
    return any(
        t.type == "function" and (t.lower_name == "light-dark" or _uses_light_dark(t.arguments))
        for t in tokens
    )


def _value_span(value: Sequence[Any], index: LineIndex | None) -> Span | None:
    """The value's span, when the source holds exactly the serialised value there.

    tinycss2 gives where the value's first token starts (1-based line and
    code-point column) but no end; the span is kept only when the text at
    that start is the serialisation itself (no comment or escape inside).
    """
    import tinycss2

    if index is None or not value or value[0].source_line > len(index.starts):
        return None
    text = tinycss2.serialize(value)
    start = index.starts[value[0].source_line - 1] + value[0].source_column - 1
    if index.text[start : start + len(text)] != text:
        return None
    return index.span(start, start + len(text))


# --------------------------------------------------------------- resolving
class _Resolver:
    """``var()`` substitution for one mode, memoised, every step counted."""

    def __init__(
        self,
        sheet: _Sheet,
        props: dict[str, _Decl],
        scheme: str,
        steps: Steps,
        parent: _Resolver | None = None,
    ):
        self.sheet = sheet
        self.props = props  # the declarations that win on this element
        self.scheme = scheme
        # The parent element's resolver: a property this element does not set
        # inherits the parent's computed value (CSS Variables 1, 2: custom
        # properties inherit), already substituted there.
        self.parent = parent
        self.steps = steps  # shared across modes
        self.done: dict[str, tuple[list[Any] | None, tuple[str, ...]]] = {}
        self.texts: dict[str, str] = {}  # serialised value per property (see _token)
        self.active: list[str] = []
        self.cycles: dict[str, str] = {}

    def owner(self, name: str) -> _Resolver | None:
        """The resolver of the element whose declaration of ``--name`` applies here."""
        if name in self.props:
            return self
        return self.parent.owner(name) if self.parent is not None else None

    def decl(self, name: str) -> _Decl:
        """The declaration of ``--name`` that applies here (on this element or inherited)."""
        owner = self.owner(name)
        assert owner is not None
        return owner.props[name]

    def place(self, name: str) -> TokenPlace:
        """Where ``--name`` is declared on this element."""
        return {"path": self.sheet.path, "line": self.props[name].line, "key": _dots(name)}

    def count(self, n: int, name: str) -> None:
        self.steps.take(n, "var() substitution", lambda: self.place(name))

    def resolve(self, name: str) -> tuple[list[Any] | None, tuple[str, ...]]:
        """The substituted value of ``--name`` (None: invalid) and its alias chain."""
        if name in self.done:
            return self.done[name]
        if name in self.active:
            # CSS Variables 1, 2.3: every property in a cycle is invalid at
            # computed-value time (not an error of the sheet).
            loop = [*self.active[self.active.index(name) :], name]
            for n in loop[:-1]:
                self.cycles.setdefault(n, " -> ".join(_dots(x) for x in loop))
            return None, ()
        if len(self.active) >= MAX_ALIAS_CHAIN:
            raise too_long("var()", self.active, self.place(self.active[0]), _dots)
        self.count(1, name)
        self.active.append(name)
        try:
            decl = self.props[name]
            value = list(decl.value)
            chain: tuple[str, ...] = ()
            if (
                len(value) == 1
                and value[0].type == "function"
                and value[0].lower_name == "var"
                and (target := _var_name(value[0])) is not None
                and (owner := self.owner(target)) is not None
                and not _var_fallback(value[0])
            ):
                resolved, rest = owner.resolve(target)
                if len(rest) >= MAX_ALIAS_CHAIN:
                    raise too_long("var()", [name, target, *rest], self.place(name), _dots)
                chain = (target, *rest)
                out = resolved
            else:
                out = self.substitute(name, value)
        finally:
            self.active.pop()
        if out is not None and len(out) > MAX_VALUE_TOKENS:
            raise InputError(
                f"resolves to more than {MAX_VALUE_TOKENS} CSS tokens; not a design token",
                **self.place(name),
            )
        if name in self.cycles:
            out = None
        self.done[name] = (out, chain)
        return out, chain

    def substitute(self, name: str, tokens: Sequence[Any]) -> list[Any] | None:
        """``tokens`` with every ``var()`` replaced and ``light-dark()`` picked."""
        from tinycss2.ast import FunctionBlock

        out: list[Any] = []
        self.count(len(tokens), name)
        for t in tokens:
            if t.type != "function":
                out.append(t)
                continue
            if t.lower_name == "var":
                target = _var_name(t)
                if target is None:
                    return None
                owner = self.owner(target)
                got = owner.resolve(target)[0] if owner is not None else None
                if got is None:
                    fallback = _var_fallback(t)
                    if fallback is None:
                        return None  # guaranteed-invalid (CSS Variables 1, 3)
                    got = self.substitute(name, _strip(fallback))
                    if got is None:
                        return None
                self.count(len(got), name)
                out.extend(got)
            elif t.lower_name == "light-dark":
                parts = _split_top(t.arguments)
                if len(parts) != 2:
                    return None
                got = self.substitute(name, _strip(parts[0 if self.scheme == "light" else 1]))
                if got is None:
                    return None
                out.extend(got)
            else:
                inner = self.substitute(name, t.arguments)
                if inner is None:
                    return None
                out.append(FunctionBlock(t.source_line, t.source_column, t.name, inner))
        return out


def _var_name(fn: Any) -> str | None:
    first = next((a for a in fn.arguments if a.type not in ("whitespace", "comment")), None)
    if first is None or first.type != "ident" or not first.value.startswith("--"):
        return None
    return str(first.value[2:])


def _var_fallback(fn: Any) -> list[Any] | None:
    args = list(fn.arguments)
    for i, a in enumerate(args):
        if a.type == "literal" and a.value == ",":
            return args[i + 1 :]
    return None


def _split_top(tokens: Sequence[Any]) -> list[list[Any]]:
    parts: list[list[Any]] = [[]]
    for t in tokens:
        if t.type == "literal" and t.value == ",":
            parts.append([])
        else:
            parts[-1].append(t)
    return parts


def _is_color(text: str) -> bool:
    from alpha_audit.color.css import parse_css_color
    from alpha_audit.errors import ColorSyntaxError

    if not text or text[0] in "0123456789.-+'\"" or len(text) > 1000:
        return False
    try:
        parse_css_color(text, gamut="clip", allow_alpha=True)
    except ColorSyntaxError:
        return False
    return True


def modes_from_stylesheet(path: str | Path) -> TokenModes:
    """Tokens per mode from a Tailwind v4 stylesheet, a palette sheet or a theme sheet."""
    p = Path(path)
    try:
        return _modes(p)
    except RecursionError as exc:  # blocks or functions nested thousands deep
        raise InputError("CSS nested too deeply", path=p) from exc


def _read_sheet(p: Path) -> _Sheet:
    """The sheet's custom properties by rule, refused when it has none to read."""
    import tinycss2

    raw = read_capped(p, MAX_CSS_BYTES, InputError, "a stylesheet")
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise InputError(f"not UTF-8 text (byte {exc.start})", path=p) from exc
    bom = text.startswith("\ufeff")  # dropped; line 1's columns still count it
    text = text.removeprefix("\ufeff")
    # CSS Syntax 3.3 counts a lone CR or a form feed as a newline, SARIF does
    # not (its default newlineSequences are LF and CRLF): lines would disagree.
    lf_only = "\r" not in text.replace("\r\n", "\n") and "\f" not in text
    sheet = _Sheet(p, LineIndex(text, p, "css", bom=bom) if lf_only else None)
    rules = tinycss2.parse_stylesheet(text, skip_comments=True, skip_whitespace=True)
    _walk(sheet, rules, layers=(), scheme=None, p3=False, skip=None, depth=0)
    if not sheet.parts:
        raise InputError(
            "has no @theme block and no rule for the root element (:root, html, "
            ":where(html)), body or a theme ([data-theme=dark], .dark) with custom properties",
            path=p,
        )
    return sheet


def _modes(p: Path) -> TokenModes:
    sheet = _read_sheet(p)
    names: set[str] = {d.name for part in sheet.parts for d in part.decls}
    if len(names) > MAX_TOKENS:
        raise InputError(f"more than {MAX_TOKENS} custom properties", path=p)
    paths = _token_paths(sheet, names)
    cascade = _Cascade(sheet, Steps())
    states = cascade.candidates()
    check_mode_budget(p, len(states), len(names))
    base = ModeConditions()
    default = cascade.resolve(base, paths)
    out: dict[str, dict[str, Token]] = {}
    conditions: dict[str, ModeConditions] = {}
    aliases: dict[str, str] = {}
    same: dict[tuple[Any, ...], str] = {}  # every computed value -> the first mode with them
    wheres: dict[str, str] = {}
    kept: dict[ModeConditions, tuple[_Part, tuple[str, ...], dict[str, Token]]] = {}
    for state, (first, words) in states.items():
        tokens = default if state == base else cascade.resolve(state, paths)
        if cascade.sets_colour(state, tokens, default):  # else sizes, fonts: no mode
            kept[state] = (first, words, tokens)
    # States named by their own rules first, then the scheme and P3 variants.
    named: dict[ModeConditions, str] = {}
    taken: set[str] = set()
    for state in sorted(kept, key=lambda s: s.scheme == "dark" or s.p3):
        first, words, _ = kept[state]
        named[state] = _mode_name(state, words, taken)
        taken.add(named[state])
        line = first.decls[0].line if first.decls else None
        check_name(named[state], path=p, line=line, what="mode name")
    for state, (_, _, tokens) in kept.items():
        name = named[state]
        conditions[name] = state
        if state != base:
            wheres[name] = "; ".join(dict.fromkeys(part.where for part in cascade.own(state)))
        # Another state computing every property alike (".dark, .dark-theme", Primer's
        # "auto" forms) is the same theme under another name: an alias of the first.
        signature = tuple((n, t.type, t.value, t.line) for n, t in tokens.items())
        if signature in same:
            aliases[name] = same[signature]
            continue
        same[signature] = name
        out[name] = {paths[n]: t for n, t in tokens.items()}
    notes = []
    for name in out:
        if name in wheres:
            also = [a for a, m in aliases.items() if m == name]
            shown = f" (the same as {', '.join(also)})" if also else ""
            notes.append(
                f"mode {name} from {p.name}: {wheres[name] or 'light-dark() values'}{shown}"
            )
    if not any(t.type == "color" for tokens in out.values() for t in tokens.values()):
        raise InputError(
            "has no custom property that is a colour in a @theme block or a rule for the root "
            "element (:root, html, :where(html)), body or a theme",
            path=p,
        )
    skipped = {paths.get(n, _dots(n)): why for n, why in sheet.skipped.items()}
    return TokenModes(
        p,
        "css",
        out,
        "default" if "default" in out else next(iter(out)),
        notes=tuple(notes),
        skipped=skipped,
        conditions=conditions,
        aliases=aliases,
    )


class _Cascade:
    """The rules that match ``<html>`` and ``<body>`` in a state, and what they compute.

    Parts are indexed by the class and attribute names their items need, so a
    state looks only at the parts it can match (a state has a handful of
    conditions: every subset of them is one look-up).
    """

    def __init__(self, sheet: _Sheet, steps: Steps) -> None:
        self.sheet = sheet
        self.steps = steps
        self.by_keys: dict[frozenset[str], list[int]] = {}
        for i, part in enumerate(sheet.parts):
            for keys in dict.fromkeys(part.item.keys):
                self.by_keys.setdefault(keys, []).append(i)
        self.colors: dict[str, bool] = {}  # _is_color per value text: modes share most values
        self.applied: dict[ModeConditions, tuple[list[_Part], list[_Part]]] = {}

    def parts(self, state: ModeConditions) -> tuple[list[_Part], list[_Part]]:
        """The parts that apply on ``<html>`` and on ``<body>`` in ``state``, in source order."""
        if state in self.applied:
            return self.applied[state]
        keys = state_keys(state)
        if len(keys) <= 10:
            found = sorted({i for sub in subsets(keys) for i in self.by_keys.get(sub, ())})
        else:  # not reached by a least state of a real selector; still exact
            found = list(range(len(self.sheet.parts)))
        html, body = state_elements(state)
        on_root: list[_Part] = []
        on_body: list[_Part] = []
        for i in found:
            part = self.sheet.parts[i]
            if part.p3 and not state.p3:
                continue
            if part.scheme is not None and part.scheme != state.scheme:
                continue
            if matches(part.item.tree, html):
                on_root.append(part)
            if matches(part.item.tree, body):
                on_body.append(part)
        self.steps.take(
            len(found) + sum(len(part.decls) for part in (*on_root, *on_body)),
            "cascading modes",
            lambda: {"path": self.sheet.path, "line": None, "key": None},
        )
        self.applied[state] = (on_root, on_body)
        return on_root, on_body

    def own(self, state: ModeConditions) -> list[_Part]:
        """The parts that apply in ``state`` and not in the page without conditions."""
        base = set(map(id, (p for side in self.parts(ModeConditions()) for p in side)))
        return [p for side in self.parts(state) for p in side if id(p) not in base]

    def candidates(self) -> dict[ModeConditions, tuple[_Part, tuple[str, ...]]]:
        """Every least state of an item, with its scheme and gamut variants (first part each).

        The page without conditions comes first.  A state gets a dark variant
        when a rule under ``prefers-color-scheme`` applies in it (or the sheet
        uses ``light-dark()``), and a wide-gamut one when a P3 rule does.
        """
        first: dict[ModeConditions, tuple[_Part, tuple[str, ...]]] = {}
        sheet = self.sheet
        if not sheet.parts:
            return first
        base = ModeConditions()
        first[base] = (sheet.parts[0], ())
        for part in sheet.parts:
            for least, words in zip(part.item.states, part.item.words, strict=True):
                first.setdefault(least_conditions(least), (part, words))
        schemed = [p for p in sheet.parts if p.scheme is not None]
        wide = [p for p in sheet.parts if p.p3]
        ordered: dict[ModeConditions, tuple[_Part, tuple[str, ...]]] = {}
        for state, (part, words) in first.items():
            ordered[state] = (part, words)
            elements = state_elements(state)

            def applies(parts: list[_Part], elements: tuple[Element, Element] = elements) -> Any:
                return next(
                    (p for p in parts if any(matches(p.item.tree, e) for e in elements)), None
                )

            found, found_wide = applies(schemed), applies(wide)
            dark = replace(state, scheme="dark")
            variants: list[tuple[ModeConditions, _Part | None]] = [
                (replace(state, p3=True), found_wide)
            ]
            if found is not None or sheet.light_dark:
                variants += [(dark, found or part), (replace(dark, p3=True), found_wide)]
            for variant, cause in variants:
                if cause is not None:
                    ordered.setdefault(variant, (cause, words))
        return ordered

    def resolve(self, state: ModeConditions, paths: dict[str, str]) -> dict[str, Token]:
        """Every custom property as ``<body>`` computes it in ``state``, by property name."""
        on_root, on_body = self.parts(state)

        def winners(parts: list[_Part]) -> dict[str, _Decl]:
            decls = sorted((d for part in parts for d in part.decls), key=lambda d: d.order)
            return {d.name: d for d in decls}  # the last in cascade order wins

        root = _Resolver(self.sheet, winners(on_root), state.scheme, self.steps)
        body = _Resolver(self.sheet, winners(on_body), state.scheme, self.steps, parent=root)
        names = dict.fromkeys([*root.props, *body.props])
        return {
            n: _token(self.sheet, body if n in body.props else root, n, self.colors) for n in names
        }

    def sets_colour(
        self, state: ModeConditions, tokens: dict[str, Token], default: dict[str, Token]
    ) -> bool:
        """Whether ``state`` is a mode: some colour comes from its own rules or differs.

        The page without conditions is a mode when it has any colour.  Another
        state is one when a colour token wins by a declaration of a rule that
        does not apply without its conditions, or computes another value
        (``.x { --hue: 200 }`` changes ``--bg: oklch(... var(--hue))``).
        """
        if state == ModeConditions():
            return any(t.type == "color" for t in tokens.values())
        own = {id(d) for part in self.own(state) for d in part.decls}
        if not own and state.scheme == "light" and not state.p3:
            return False
        root, body = self.parts(state)
        won = {}
        for part in (*root, *body):
            for d in part.decls:
                won[d.name] = d
        for name, token in tokens.items():
            if token.type != "color":
                continue
            before = default.get(name)
            if before is None or before.value != token.value or before.line != token.line:
                return True
            if name in won and id(won[name]) in own:
                return True
        return False


def _mode_name(state: ModeConditions, words: tuple[str, ...], taken: set[str]) -> str:
    """A short name for ``state`` (``dark``, ``pf-v6-theme-dark-pf-v6-theme-felt``).

    The words are the class names and attribute values of the selector that
    gave the state, in its order, each once; a dark scheme adds ``-dark`` (the page
    without conditions is ``dark``), a wide-gamut display ``-p3``.  A name an
    earlier state has already taken is written out in full instead
    (``data-color-mode=auto+data-dark-theme=dark+prefers-dark``).
    """
    name = "-".join(dict.fromkeys(words)) or "default"
    if state.scheme == "dark":
        name = "dark" if name == "default" else name if name.endswith("dark") else f"{name}-dark"
    if state.p3:
        name = "p3" if name == "default" else f"{name}-p3"
    if name not in taken:
        return name
    full = [
        *(f".{c}" for c in state.root_classes),
        *(f"{a}={v}" if v else a for a, v in state.root_attributes),
        *(f"body.{c}" for c in state.body_classes),
        *(f"body:{a}={v}" if v else f"body:{a}" for a, v in state.body_attributes),
        *(["prefers-dark"] if state.scheme == "dark" else []),
        *(["p3"] if state.p3 else []),
    ]
    name = "+".join(full) or "default"
    n, unique = 2, name
    while unique in taken:
        unique, n = f"{name}+{n}", n + 1
    return unique


def _token_paths(sheet: _Sheet, names: set[str]) -> dict[str, str]:
    """Token path of each property name; two names giving one path are an error."""
    first_line: dict[str, int] = {}
    for d in sorted((d for part in sheet.parts for d in part.decls), key=lambda d: d.order[2]):
        first_line.setdefault(d.name, d.line)
    seen: dict[str, str] = {}
    for name in first_line:  # in source order
        check_name(name, path=sheet.path, line=first_line[name], what="custom property")
        path = _dots(name)
        if path in seen:
            raise InputError(
                f"--{safe_text(seen[path])} and --{safe_text(name)} (line "
                f"{first_line[seen[path]]}) both name the token {path}; rename one "
                "(a CSS escape such as \\2e is read as the character it stands for)",
                path=sheet.path,
                line=first_line[name],
                key=path,
            )
        seen[path] = name
    return {name: path for path, name in seen.items()}


def _token(sheet: _Sheet, resolver: _Resolver, name: str, colors: dict[str, bool]) -> Token:
    """One property of one mode as a token (a colour, or a non-colour with its reason).

    An alias shares its target's value: serialised once per mode (a thousand
    aliases of a long value are not a thousand serialisations), and whether a
    text is a colour is decided once per sheet (``colors``).
    """
    import tinycss2

    decl = resolver.props[name]
    value, chain = resolver.resolve(name)
    end_name = chain[-1] if chain else name
    end = resolver.props[end_name]
    if end_name not in resolver.texts:
        resolver.texts[end_name] = tinycss2.serialize(value).strip() if value is not None else ""
    text = resolver.texts[end_name]
    if text not in colors:
        colors[text] = _is_color(text)
    path = _dots(name)
    problem = None
    if name in resolver.cycles:
        problem = f"var() cycle: {resolver.cycles[name]} (every property in it is invalid)"
    elif value is None:
        problem = (
            f"{tinycss2.serialize(decl.value).strip()[:60]} names a custom property no "
            "rule of this sheet sets in this mode (and gives no fallback)"
        )
    elif not colors[text]:
        via = " -> ".join(_dots(n) for n in (name, *chain))
        problem = f"is {text[:40]!r}" + (f" (via {via})" if chain else "") + ", not a colour"
    return Token(
        path=path,
        type="color" if problem is None else "css",
        value=text,
        file=sheet.path,
        line=end.line,
        chain=tuple(_dots(c) for c in chain),
        alias_file=sheet.path if chain else None,
        alias_line=decl.line if chain else None,
        # Only a value written out literally can be rewritten in place.
        span=end.span if end.literal else None,
        problem=problem,
    )


def _literal(value: Sequence[Any]) -> bool:
    return not any(t.type == "function" and t.lower_name in ("var", "light-dark") for t in value)


def _dots(name: str) -> str:
    """``color-red-500`` to the token path ``color.red.500``."""
    return name.replace("-", ".")
