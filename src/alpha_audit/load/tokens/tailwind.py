"""Tailwind CSS v4 ``@theme`` blocks: ``--color-*`` custom properties as colour tokens.

The CSS is tokenised by tinycss2 (CSS Syntax Level 3), never by regular
expressions.  ``--color-red-500: oklch(63.7% 0.237 25.331)`` becomes the
colour token ``color.red.500`` (dashes to dots, the inverse of the export's
naming); ``var(--color-x)`` is an alias; ``initial`` (Tailwind's namespace
reset) and non-colour namespaces are skipped.  Top-level rules whose
selector is ``.<mode>`` or ``[data-theme="<mode>"]`` override the theme's
properties in that mode (how Tailwind sites switch dark mode); ``@theme``
alone is the mode ``default``.
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import Any

from alpha_audit.errors import InputError
from alpha_audit.load.files import read_capped
from alpha_audit.load.tokens.model import (
    MAX_ALIAS_CHAIN,
    MAX_TOKENS,
    Token,
    TokenModes,
    token_error,
)

__all__ = ["MAX_CSS_BYTES", "modes_from_tailwind"]

MAX_CSS_BYTES = 4 << 20
_VAR = re.compile(r"var\(\s*--([A-Za-z0-9_-]+)\s*\)")
_MODE_SELECTOR = re.compile(r"""\.([A-Za-z][\w-]*)|\[data-theme=["']?([\w-]+)["']?\]""")


def _declarations(rule: Any) -> list[tuple[str, str, int]]:
    import tinycss2

    out = []
    for node in tinycss2.parse_blocks_contents(
        rule.content, skip_comments=True, skip_whitespace=True
    ):
        if node.type == "declaration" and node.name.startswith("--color-"):
            value = tinycss2.serialize(node.value).strip()
            if value != "initial":
                out.append((node.name[2:], value, node.source_line))
    return out


def modes_from_tailwind(path: str | Path) -> TokenModes:
    """Colour tokens per mode from a Tailwind v4 stylesheet."""
    import tinycss2

    p = Path(path)
    raw = read_capped(p, MAX_CSS_BYTES, InputError, "a stylesheet")
    try:
        text = raw.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise InputError(f"not UTF-8 text (byte {exc.start})", path=p) from exc
    rules = tinycss2.parse_stylesheet(text, skip_comments=True, skip_whitespace=True)
    base: dict[str, tuple[str, int]] = {}
    overrides: dict[str, dict[str, tuple[str, int]]] = {}
    for rule in rules:
        if rule.type == "at-rule" and rule.lower_at_keyword == "theme" and rule.content:
            base.update({n: (v, line) for n, v, line in _declarations(rule)})
        elif rule.type == "qualified-rule":
            selector = tinycss2.serialize(rule.prelude).strip()
            match = _MODE_SELECTOR.fullmatch(selector)
            if match and rule.content:
                mode = match.group(1) or match.group(2)
                overrides.setdefault(mode, {}).update(
                    {n: (v, line) for n, v, line in _declarations(rule)}
                )
    if not base:
        raise InputError("has no @theme block with --color-* properties", path=p)
    if len(base) > MAX_TOKENS:
        raise InputError(f"more than {MAX_TOKENS} colour properties", path=p)
    modes = {"default": _resolve(p, base)}
    for mode, props in overrides.items():
        modes[mode] = _resolve(p, {**base, **props})
    return TokenModes(p, "tailwind", modes, "default")


def _resolve(path: Path, props: dict[str, tuple[str, int]]) -> dict[str, Token]:
    tokens = {}
    for name, (value, line) in props.items():
        chain: list[str] = []
        current, current_line = value, line
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
            current, current_line = props[target]
        tokens[_dots(name)] = Token(
            path=_dots(name),
            type="color",
            value=current,
            file=path,
            line=current_line,
            chain=tuple(_dots(c) for c in chain),
            alias_file=path if chain else None,
            alias_line=line if chain else None,
        )
    return tokens


def _dots(name: str) -> str:
    """``color-red-500`` to the token path ``color.red.500``."""
    return name.replace("-", ".")
