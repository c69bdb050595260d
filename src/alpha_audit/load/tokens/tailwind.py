"""CSS custom properties as colour tokens: Tailwind v4 ``@theme`` and plain ``:root`` sheets.

The CSS is tokenised by tinycss2 (CSS Syntax Level 3), never by regular
expressions.  ``--color-red-500: oklch(63.7% 0.237 25.331)`` becomes the
colour token ``color.red.500`` (dashes to dots, the inverse of the export's
naming); ``var(--color-x)`` is an alias; ``initial`` (Tailwind's namespace
reset) and non-colour namespaces are skipped.  ``@theme`` (and a rule whose
selector list has ``:root``) is the mode ``default``; a top-level rule whose
selectors are ``.<mode>`` or ``[data-theme="<mode>"]`` overrides it in that
mode (how Tailwind sites switch dark mode; ``.dark, .dark-theme`` is the mode
``dark``).

Outside ``@theme`` (palettes such as Radix Colors write ``--blue-9: #0090ff``
in ``:root``), any custom property whose value starts as a colour does
(a hash, ``rgb()`` ... ``color()``, or ``var()``): custom properties are
untyped, and guessing more would make a length a colour.  Rules inside
``@supports (color: color(display-p3 ...))`` or ``@media (color-gamut: p3)``
are the wide-gamut variant a P3 display uses: they form the modes ``p3`` and
``<mode>-p3``, each the cascade of default, p3, mode and mode-p3 in that
order, so they follow the gamut policy like any colour outside sRGB.
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import Any

from alpha_audit.errors import InputError
from alpha_audit.load.files import read_capped
from alpha_audit.load.spans import LineIndex
from alpha_audit.load.tokens.model import (
    MAX_ALIAS_CHAIN,
    MAX_TOKENS,
    Token,
    TokenModes,
    token_error,
)
from alpha_audit.model import Span

__all__ = ["MAX_CSS_BYTES", "modes_from_tailwind"]

# (value, line, exact span of the value or None) of one custom property.
_Prop = tuple[str, int, Span | None]

MAX_CSS_BYTES = 4 << 20
_VAR = re.compile(r"var\(\s*--([A-Za-z0-9_-]+)\s*\)")
_MODE_SELECTOR = re.compile(r"""\.([A-Za-z][\w-]*)|\[data-theme=["']?([\w-]+)["']?\]""")


# The CSS Color 4 functions a colour value can start with (section 4, "Representing
# Colors"), plus var() for an alias.
_COLOR_FUNCTIONS = frozenset(
    {"rgb", "rgba", "hsl", "hsla", "hwb", "lab", "lch", "oklab", "oklch", "color", "var"}
)
_OTHER_NEWLINE = re.compile(r"\r(?!\n)|\f")
_P3 = re.compile(r"display-p3|color-gamut\s*:\s*p3", re.IGNORECASE)


def _starts_as_color(node: Any) -> bool:
    """Whether a declaration's value starts with a hash or a colour function."""
    first = next((t for t in node.value if t.type not in ("whitespace", "comment")), None)
    if first is None:
        return False
    if first.type == "hash":
        return True
    return first.type == "function" and first.lower_name in _COLOR_FUNCTIONS


def _value_span(node: Any, value: str, index: LineIndex | None) -> Span | None:
    """The value's span, when the source holds exactly the serialised value there.

    tinycss2 gives where the value's first token starts (1-based line and
    code-point column) but no end; the span is kept only when the text at
    that start is the serialisation itself (no comment or escape inside).
    """
    if index is None:
        return None
    first = next((t for t in node.value if t.type not in ("whitespace", "comment")), None)
    if first is None or first.source_line > len(index.starts):
        return None
    start = index.starts[first.source_line - 1] + first.source_column - 1
    if index.text[start : start + len(value)] != value:
        return None
    return index.span(start, start + len(value))


def _declarations(
    rule: Any, index: LineIndex | None, *, any_color: bool = False
) -> list[tuple[str, str, int, Span | None]]:
    """``(name without --, value, line, span)`` of the colour properties of a block.

    ``any_color``: every custom property whose value starts as a colour
    (plain stylesheets), else only Tailwind's ``--color-*`` namespace.
    """
    import tinycss2

    out = []
    for node in tinycss2.parse_blocks_contents(
        rule.content, skip_comments=True, skip_whitespace=True
    ):
        if node.type != "declaration" or not node.name.startswith("--"):
            continue
        if node.name.startswith("--color-") or (any_color and _starts_as_color(node)):
            value = tinycss2.serialize(node.value).strip()
            if value != "initial":
                span = _value_span(node, value, index)
                out.append((node.name[2:], value, node.source_line, span))
    return out


def _rule_mode(selector: str) -> str | None:
    """``default`` for a selector list with ``:root``, the first class or theme name, or None."""
    parts = [p.strip() for p in selector.split(",")]
    if ":root" in parts:
        return "default"
    for part in parts:
        match = _MODE_SELECTOR.fullmatch(part)
        if match:
            return match.group(1) or match.group(2)
    return None


def _collect(
    rules: list[Any], layers: dict[str, dict[str, _Prop]], index: LineIndex | None, *, p3: bool
) -> None:
    """Add each rule's colour properties to its mode's layer (``<mode>-p3`` inside P3 blocks)."""
    import tinycss2

    for rule in rules:
        if rule.type == "at-rule" and rule.content is not None:
            keyword = rule.lower_at_keyword
            if keyword == "theme" and not p3:
                layers.setdefault("default", {}).update(
                    {n: (v, line, sp) for n, v, line, sp in _declarations(rule, index)}
                )
            elif keyword in ("supports", "media") and _P3.search(tinycss2.serialize(rule.prelude)):
                inner = tinycss2.parse_rule_list(
                    rule.content, skip_comments=True, skip_whitespace=True
                )
                _collect(inner, layers, index, p3=True)
        elif rule.type == "qualified-rule" and rule.content:
            mode = _rule_mode(tinycss2.serialize(rule.prelude).strip())
            if mode is None:
                continue
            name = ("p3" if mode == "default" else f"{mode}-p3") if p3 else mode
            layers.setdefault(name, {}).update(
                {n: (v, line, sp) for n, v, line, sp in _declarations(rule, index, any_color=True)}
            )


def modes_from_tailwind(path: str | Path) -> TokenModes:
    """Colour tokens per mode from a Tailwind v4 stylesheet or a ``:root`` palette sheet."""
    import tinycss2

    p = Path(path)
    raw = read_capped(p, MAX_CSS_BYTES, InputError, "a stylesheet")
    try:
        text = raw.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise InputError(f"not UTF-8 text (byte {exc.start})", path=p) from exc
    rules = tinycss2.parse_stylesheet(text, skip_comments=True, skip_whitespace=True)
    layers: dict[str, dict[str, _Prop]] = {}
    # CSS Syntax 3.3 counts a lone CR or a form feed as a newline, SARIF does
    # not (its default newlineSequences are LF and CRLF): lines would disagree.
    index = None if _OTHER_NEWLINE.search(text) else LineIndex(text, p, "css")
    _collect(rules, layers, index, p3=False)
    base = layers.get("default", {})
    if not base:
        raise InputError(
            "has no @theme block with --color-* properties and no :root rule with colour "
            "custom properties",
            path=p,
        )
    if sum(len(layer) for layer in layers.values()) > MAX_TOKENS:
        raise InputError(f"more than {MAX_TOKENS} colour properties", path=p)
    modes = {"default": _resolve(p, base)}
    for mode in layers:
        if mode == "default":
            continue
        # The cascade in source order: default, p3, the mode, its p3 variant.
        plain = mode.removesuffix("-p3") if mode != "p3" else "default"
        order = ["default", "p3", plain, f"{plain}-p3"] if plain != "default" else ["default", "p3"]
        if not mode.endswith("p3"):
            order = ["default", mode]
        merged: dict[str, _Prop] = {}
        for name in dict.fromkeys(order):
            merged.update(layers.get(name, {}))
        modes[mode] = _resolve(p, merged)
    return TokenModes(p, "tailwind", modes, "default")


def _resolve(path: Path, props: dict[str, _Prop]) -> dict[str, Token]:
    tokens = {}
    for name, (value, line, span) in props.items():
        chain: list[str] = []
        current, current_line, current_span = value, line, span
        while match := _VAR.fullmatch(current):
            target = match.group(1)
            if target in chain or target == name:
                cycle = " -> ".join(_dots(n) for n in [name, *chain, target])
                raise token_error(f"alias cycle: {cycle}", file=path, line=line, path=_dots(name))
            if target not in props or len(chain) > MAX_ALIAS_CHAIN:
                raise token_error(
                    f"var(--{target}) names no --color-* property of the theme",
                    file=path,
                    line=line,
                    path=_dots(name),
                )
            chain.append(target)
            current, current_line, current_span = props[target]
        tokens[_dots(name)] = Token(
            path=_dots(name),
            type="color",
            value=current,
            file=path,
            line=current_line,
            chain=tuple(_dots(c) for c in chain),
            alias_file=path if chain else None,
            alias_line=line if chain else None,
            span=current_span,
        )
    return tokens


def _dots(name: str) -> str:
    """``color-red-500`` to the token path ``color.red.500``."""
    return name.replace("-", ".")
