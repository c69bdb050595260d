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

Modes come from where rules apply:

- ``@theme`` and rules for the root element (``:root``, ``html``,
  ``:host``, ``:where(html)``, ``*``) are the mode ``default``;
- a rule whose selector is a class or a ``[data-*="name"]`` attribute (alone
  or on the root: ``:root.dark``, ``html[data-theme=dark]``) names a mode,
  when it sets custom properties; a selector with a combinator
  (``.dark .card``), an element other than the root or a state (``:hover``,
  ``:has()``) applies to part of a page and is no mode;
- ``@media (prefers-color-scheme: dark)`` is the mode ``dark`` (a named
  mode inside it is ``<name>-dark``); ``light`` applies to every mode that is
  not dark; ``light-dark(a, b)`` values take ``a`` or ``b`` by the mode's
  scheme and add a ``dark`` mode when the sheet has none;
- ``@media (color-gamut: p3)``, ``(dynamic-range: high)`` and ``@supports``
  on ``display-p3`` hold what a wide-gamut display uses: the modes ``p3``
  and ``<name>-p3``;
- ``@layer`` blocks are read in layer order (CSS Cascade 5: later layers
  win, unlayered rules beat layered ones), then specificity, then source
  order, so each mode's value is the one a browser computes on the root;
- other ``@media`` conditions (widths, print, motion), ``@supports not``,
  ``@container`` and ``@scope`` are not a colour mode: their rules are
  skipped, and a selected token they would set is warned about.

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
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from alpha_audit.errors import InputError
from alpha_audit.load.files import read_capped
from alpha_audit.load.names import check_name
from alpha_audit.load.spans import LineIndex
from alpha_audit.load.tokens.model import (
    MAX_ALIAS_CHAIN,
    MAX_TOKENS,
    Steps,
    Token,
    TokenModes,
    TokenPlace,
    check_mode_budget,
    token_error,
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
class _Contribution:
    """The declarations a rule gives one mode (``default``: the root element)."""

    mode: str
    scheme: str | None  # only under this prefers-color-scheme
    p3: bool
    where: str  # for notes: "line 12 [data-theme=dark]"
    decls: list[_Decl] = field(default_factory=list)


@dataclass
class _Sheet:
    """What one walk over a stylesheet collects."""

    path: Path
    index: LineIndex | None
    parts: list[_Contribution] = field(default_factory=list)
    skipped: dict[str, str] = field(default_factory=dict)  # property -> why not read
    layer_ranks: dict[tuple[str, ...], int] = field(default_factory=dict)
    layer_children: dict[tuple[str, ...], int] = field(default_factory=dict)  # per parent
    anonymous: int = 0
    source: int = 0
    light_dark: bool = False
    parent: dict[str, str] = field(default_factory=dict)  # mode names of one selector list

    def find(self, name: str) -> str:
        root = name
        while self.parent.get(root, root) != root:
            root = self.parent[root]
        while name != root:  # path compression: the next find is one step
            self.parent[name], name = root, self.parent[name]
        return root

    def union(self, names: Sequence[str]) -> None:
        """One selector list is one mode (``.dark, .dark-theme``); with the root, the default."""
        roots = [self.find(n) for n in names]
        target = "default" if "default" in roots else roots[0]
        for r in roots:
            if r != target:
                self.parent[r] = target

    def finish(self) -> None:
        """Each contribution's mode by its canonical name (dark media renames it)."""
        for part in self.parts:
            name = self.find(part.mode)
            if part.scheme == "dark":
                name = (
                    "dark"
                    if name == "default"
                    else name
                    if name.endswith("dark")
                    else f"{name}-dark"
                )
            part.mode = name

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
def _simple_kind(simple: Any) -> tuple[str, str | None]:
    """``("root", None)``, ``("mode", name)``, ``("filter", None)`` or ``("no", None)``."""
    from cssselect2 import parser as sel

    if isinstance(simple, sel.LocalNameSelector):
        return ("root", None) if simple.lower_local_name == "html" else ("no", None)
    if isinstance(simple, sel.PseudoClassSelector):
        return ("root", None) if simple.name in _ROOT_NAMES else ("no", None)
    if isinstance(simple, sel.FunctionalPseudoClassSelector):
        return ("root", None) if simple.name == "host" else ("no", None)
    if isinstance(simple, sel.ClassSelector):
        return "mode", str(simple.class_name)
    if isinstance(simple, sel.AttributeSelector):
        if not str(simple.lower_name).startswith("data-"):
            return "no", None  # [role=search], [type=checkbox]: elements, not modes
        if simple.value is None or simple.operator not in ("=", "~="):
            return "filter", None  # [data-color-scheme] alone: present in every mode
        return "mode", str(simple.value)
    if isinstance(simple, sel.NegationSelector | sel.NamespaceSelector):
        return "filter", None  # :root:not([data-theme=dark]) is the root without that mode
    if isinstance(simple, sel.MatchesAnySelector | sel.SpecificityAdjustmentSelector):
        kinds = [_classify(getattr(s, "parsed_tree", s)) for s in simple.selector_list]
        found = [k for k in kinds if k is not None]
        if len(found) == 1:
            return ("root", None) if found[0] == "default" else ("mode", found[0])
        return "no", None
    return "no", None  # an id, :hover, :has(), ...


def _classify(tree: Any) -> str | None:
    """The mode a complex selector applies to on the root element, or None."""
    from cssselect2 import parser as sel

    if not isinstance(tree, sel.CompoundSelector):
        return None  # a combinator: part of the page, not the root
    names: list[str] = []
    root = not tree.simple_selectors  # "*" matches the root too
    for simple in tree.simple_selectors:
        kind, name = _simple_kind(simple)
        if kind == "no":
            return None
        root = root or kind == "root"
        if name is not None and name not in names:
            names.append(name)
    if names:
        return "-".join(names)
    return "default" if root else None


def _rule_modes(prelude: Sequence[Any]) -> dict[str, tuple[int, int, int]] | None:
    """``{mode: specificity}`` for a rule's selector list (None: not understood)."""
    from cssselect2 import parser as sel

    out: dict[str, tuple[int, int, int]] = {}
    try:
        for selector in sel.parse(list(prelude)):
            if selector.pseudo_element is not None:
                continue
            mode = _classify(selector.parsed_tree)
            if mode is not None:
                a, b, c = selector.specificity
                out[mode] = max(out.get(mode, (0, 0, 0)), (a, b, c))
    except sel.SelectorError:
        return None
    return out


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
    for rule in rules:
        if rule.type == "at-rule":
            keyword = rule.lower_at_keyword
            prelude = rule.prelude
            if keyword == "layer":
                names = _layer_names(sheet, prelude)
                if rule.content is None:  # "@layer a, b;" fixes the order
                    for name in names:
                        sheet.layer_key((*layers, *name))
                    continue
                inner_layers = (*layers, *(names[0] if names else ()))
                _walk(
                    sheet,
                    _rule_list(rule.content),
                    layers=inner_layers,
                    scheme=scheme,
                    p3=p3,
                    skip=skip,
                    depth=depth + 1,
                )
            elif rule.content is None:
                continue
            elif keyword == "theme":  # Tailwind v4: theme variables on :root
                _add(sheet, rule, {"default": (0, 1, 0)}, layers, scheme, p3, skip)
            elif keyword == "media":
                found = _media(prelude)
                why = skip or (
                    f"@media {tinycss2.serialize(prelude).strip()}" if found is None else None
                )
                s, is_p3 = found if found is not None else (None, False)
                _walk(
                    sheet,
                    _rule_list(rule.content),
                    layers=layers,
                    scheme=s or scheme,
                    p3=p3 or is_p3,
                    skip=why,
                    depth=depth + 1,
                )
            elif keyword == "supports":
                applies, is_p3 = _supports(prelude)
                why = skip or (
                    None if applies else f"@supports {tinycss2.serialize(prelude).strip()}"
                )
                _walk(
                    sheet,
                    _rule_list(rule.content),
                    layers=layers,
                    scheme=scheme,
                    p3=p3 or is_p3,
                    skip=why,
                    depth=depth + 1,
                )
            elif keyword in _SKIPPED_AT:
                _walk(
                    sheet,
                    _rule_list(rule.content) if keyword in ("container", "scope") else [],
                    layers=layers,
                    scheme=scheme,
                    p3=p3,
                    skip=skip or f"@{keyword}",
                    depth=depth + 1,
                )
        elif rule.type == "qualified-rule":
            modes = _rule_modes(rule.prelude)
            selector = " ".join(tinycss2.serialize(rule.prelude).split())
            if not modes:
                _add(sheet, rule, {}, layers, scheme, p3, skip or f"selector {selector[:60]}")
            else:
                if scheme is None and skip is None and _sets_properties(rule):
                    sheet.union(list(modes))
                _add(sheet, rule, modes, layers, scheme, p3, skip)


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


def _add(
    sheet: _Sheet,
    rule: Any,
    modes: dict[str, tuple[int, int, int]],
    layers: tuple[str, ...],
    scheme: str | None,
    p3: bool,
    skip: str | None,
) -> None:
    """Record the custom properties of ``rule`` for each of its modes (or as skipped)."""
    import tinycss2

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
    selector = " ".join(tinycss2.serialize(rule.prelude).split()) or "@theme"
    for mode, specificity in modes.items():
        media = f"@media (prefers-color-scheme: {scheme}) " if scheme else ""
        part = _Contribution(mode, scheme, p3, f"line {line} {media}{selector[:60]}")
        for node in decls:
            if "*" in node.name:  # Tailwind's "--color-*: initial" resets a namespace
                continue
            value = _strip(node.value)
            if len(value) == 1 and value[0].type == "ident" and value[0].lower_value == "initial":
                continue
            sheet.source += 1
            if not sheet.light_dark and _uses_light_dark(value):
                sheet.light_dark = True
            part.decls.append(
                _Decl(
                    node.name[2:],
                    tuple(value),
                    node.source_line,
                    _value_span(value, sheet.index),
                    (layer, specificity, sheet.source),
                    _literal(value),
                )
            )
        sheet.parts.append(part)


def _sets_properties(rule: Any) -> bool:
    return any(t.type == "ident" and t.value.startswith("--") for t in rule.content)


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


# ------------------------------------------------------------------- modes
def _scheme_of(mode: str) -> str:
    plain = mode.removesuffix("-p3") if mode != "p3" else "default"
    return "dark" if plain == "dark" or plain.endswith("-dark") else "light"


def _applies(part: _Contribution, mode: str) -> bool:
    """Whether a rule's declarations apply on the root in ``mode``."""
    is_p3 = mode == "p3" or mode.endswith("-p3")
    plain = "default" if mode == "p3" else mode.removesuffix("-p3") if is_p3 else mode
    if part.p3 and not is_p3:
        return False
    if part.scheme is not None and part.scheme != _scheme_of(plain):
        return False
    return part.mode in ("default", plain)


def _mode_names(sheet: _Sheet) -> list[str]:
    # A sheet of one theme (Primer's dark.css, Radix's blue-dark.css) has no root rule.
    has_root = any(part.mode == "default" for part in sheet.parts) or sheet.light_dark
    names: dict[str, None] = {"default": None} if has_root else {}
    for part in sheet.parts:
        if not part.p3:
            names.setdefault(part.mode, None)
    if sheet.light_dark:
        names.setdefault("dark", None)
    wide = {p.mode for p in sheet.parts if p.p3}
    out = []
    for name in names:
        out.append(name)
        if name in wide:
            out.append("p3" if name == "default" else f"{name}-p3")
    return out


# --------------------------------------------------------------- resolving
class _Resolver:
    """``var()`` substitution for one mode, memoised, every step counted."""

    def __init__(self, sheet: _Sheet, props: dict[str, _Decl], scheme: str, steps: Steps):
        self.sheet = sheet
        self.props = props
        self.scheme = scheme
        self.steps = steps  # shared across modes
        self.done: dict[str, tuple[list[Any] | None, tuple[str, ...]]] = {}
        self.texts: dict[str, str] = {}  # serialised value per property (see _token)
        self.active: list[str] = []
        self.cycles: dict[str, str] = {}

    def count(self, n: int, name: str) -> None:
        def place() -> TokenPlace:
            return {"file": self.sheet.path, "line": self.props[name].line, "path": _dots(name)}

        self.steps.take(n, "var() substitution", place)

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
            raise token_error(
                f"var() chain longer than {MAX_ALIAS_CHAIN}: "
                f"{' -> '.join(_dots(n) for n in self.active[:4])} -> ...",
                file=self.sheet.path,
                line=self.props[self.active[0]].line,
                path=_dots(self.active[0]),
            )
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
                and target in self.props
                and not _var_fallback(value[0])
            ):
                resolved, rest = self.resolve(target)
                if len(rest) >= MAX_ALIAS_CHAIN:
                    raise token_error(
                        f"var() chain longer than {MAX_ALIAS_CHAIN}: {_dots(name)} -> "
                        f"{' -> '.join(_dots(n) for n in (target, *rest[:2]))} -> ...",
                        file=self.sheet.path,
                        line=decl.line,
                        path=_dots(name),
                    )
                chain = (target, *rest)
                out = resolved
            else:
                out = self.substitute(name, value)
        finally:
            self.active.pop()
        if out is not None and len(out) > MAX_VALUE_TOKENS:
            raise token_error(
                f"resolves to more than {MAX_VALUE_TOKENS} CSS tokens; not a design token",
                file=self.sheet.path,
                line=self.props[name].line,
                path=_dots(name),
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
                got = self.resolve(target)[0] if target in self.props else None
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


def _modes(p: Path) -> TokenModes:
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
    sheet.finish()
    names: set[str] = {d.name for part in sheet.parts for d in part.decls}
    if not sheet.parts:
        raise InputError(
            "has no @theme block and no rule for the root element (:root, html, "
            ":where(html)) or a theme ([data-theme=dark], .dark) with custom properties",
            path=p,
        )
    if len(names) > MAX_TOKENS:
        raise InputError(f"more than {MAX_TOKENS} custom properties", path=p)
    paths = _token_paths(sheet, names)
    modes = _mode_names(sheet)
    check_mode_budget(p, len(modes), len(names))
    steps = Steps()
    colors: dict[str, bool] = {}  # _is_color per value text: modes share most values
    out: dict[str, dict[str, Token]] = {}
    notes = []
    by_mode: dict[str, list[_Contribution]] = {}
    for part in sheet.parts:
        by_mode.setdefault(part.mode, []).append(part)
    for mode in modes:
        plain_mode = mode.removesuffix("-p3")
        # The first declaration of the first rule that names the mode.
        line = next(
            (d.line for part in sheet.parts if part.mode == plain_mode for d in part.decls), None
        )
        check_name(mode, path=p, line=line, what="mode name")
        plain = "default" if mode == "p3" else mode.removesuffix("-p3")
        candidates = by_mode.get("default", []) + (
            by_mode.get(plain, []) if plain != "default" else []
        )
        applied = [part for part in candidates if _applies(part, mode)]
        # Each mode applies every root declaration again: counted before the sort.
        steps.take(
            len(candidates) + sum(len(part.decls) for part in applied),
            "cascading modes",
            lambda: {"file": p, "line": None, "path": None},
        )
        decls = sorted((d for part in applied for d in part.decls), key=lambda d: d.order)
        props = {d.name: d for d in decls}  # the last in cascade order wins
        resolver = _Resolver(sheet, props, _scheme_of(mode), steps)
        out[mode] = {paths[name]: _token(sheet, resolver, name, colors) for name in props}
        own = [part.where for part in applied if part.mode != "default" or part.scheme or part.p3]
        if mode != "default":
            found = "; ".join(dict.fromkeys(own)) or "light-dark() values"
            notes.append(f"mode {mode} from {p.name}: {found}")
    if not any(t.type == "color" for tokens in out.values() for t in tokens.values()):
        raise InputError(
            "has no custom property that is a colour in a @theme block or a rule for the root "
            "element (:root, html, :where(html))",
            path=p,
        )
    skipped = {paths.get(n, _dots(n)): why for n, why in sheet.skipped.items()}
    return TokenModes(p, "css", out, next(iter(out)), notes=tuple(notes), skipped=skipped)


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
            raise token_error(
                f"--{safe_text(seen[path])} and --{safe_text(name)} (line "
                f"{first_line[seen[path]]}) both name the token {path}; rename one "
                "(a CSS escape such as \\2e is read as the character it stands for)",
                file=sheet.path,
                line=first_line[name],
                path=path,
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
            f"{tinycss2.serialize(decl.value).strip()[:60]} names a custom property this "
            "sheet does not set (and gives no fallback)"
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
