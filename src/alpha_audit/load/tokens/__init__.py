"""Design tokens as input: DTCG 2025.10 (with the Resolver Module), Tokens Studio,
Style Dictionary, Figma Variables and CSS (Tailwind v4 ``@theme``, palette and theme sheets).

:func:`load_token_modes` detects the format from the file and returns
:class:`TokenModes`: resolved tokens per mode, each remembering the file and
JSON line that set it.  :func:`token_color` turns a colour token into sRGB
under a gamut policy.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import Any

from alpha_audit.load.tokens.colors import token_color
from alpha_audit.load.tokens.dtcg import TokenTree, tokens_from_docs
from alpha_audit.load.tokens.figma import is_figma, modes_from_figma
from alpha_audit.load.tokens.jsondoc import JsonDoc, load_json, parse_json
from alpha_audit.load.tokens.model import ModeConditions, Token, TokenModes
from alpha_audit.load.tokens.resolver import is_resolver, modes_from_resolver
from alpha_audit.load.tokens.studio import is_studio_file, modes_from_studio
from alpha_audit.load.tokens.stylesheet import modes_from_stylesheet

__all__ = [
    "TOKEN_FORMATS",
    "JsonDoc",
    "ModeConditions",
    "Token",
    "TokenModes",
    "TokenTree",
    "load_json",
    "load_token_modes",
    "parse_json",
    "token_color",
    "tokens_from_docs",
]

TOKEN_FORMATS = (
    "auto",
    "dtcg",
    "resolver",
    "tokens-studio",
    "style-dictionary",
    "figma",
    "css",
    "tailwind",  # the CSS reader, under the name it had first
)


def _has_dollar_value(data: Any, depth: int = 0) -> bool:
    if depth > 64 or not isinstance(data, dict):
        return False
    return "$value" in data or any(_has_dollar_value(v, depth + 1) for v in data.values())


def _not_read(doc: JsonDoc) -> str | None:
    """What a JSON file that is no token format alpha-audit reads looks like, if known."""
    data = doc.data
    if is_studio_file(doc):
        return None
    if isinstance(data, list):
        if data and isinstance(data[0], dict) and {"name", "value", "mode"} <= set(data[0]):
            return "a list of variables per mode (Primer's dist/figma importer format)"
        return "a JSON list, not an object of token groups"
    if not isinstance(data, dict):
        return "a single JSON value, not an object of token groups"
    flat = data.get("tokens")
    if isinstance(data.get("name"), str) and isinstance(flat, dict) and flat:
        first = next(iter(flat))
        if "/" in first and isinstance(flat[first], dict) and "value" in flat[first]:
            return (
                'Atlassian\'s Figma sync JSON ({"name", "tokens": {"<theme>/<path>": {value, '
                "attributes}}}, @atlaskit/tokens figma/*.json)"
            )
    for value in list(data.values())[:50]:
        sets = value.get("sets") if isinstance(value, dict) else None
        if isinstance(sets, dict) and any(isinstance(v, dict) for v in sets.values()):
            return "per-token sets ({token: {sets: {light: {value}, dark: ...}}}, Adobe Spectrum)"
    return None


def detect_format(doc: JsonDoc) -> str:
    """The token format of a parsed JSON file.

    A file in a shape no reader takes is refused naming that shape, not with
    a structural error deep inside a reader.
    """
    shape = _not_read(doc)
    if shape is not None:
        from alpha_audit.errors import InputError

        raise InputError(
            f"this looks like {shape}, which alpha-audit does not read; formats read: DTCG, "
            "Resolver, Tokens Studio, Style Dictionary, Figma Variables (REST) and CSS",
            path=doc.path,
        )
    if is_figma(doc.data):
        return "figma"
    if is_resolver(doc.data):
        return "resolver"
    if is_studio_file(doc):
        return "tokens-studio"
    return "dtcg" if _has_dollar_value(doc.data) else "style-dictionary"


def load_token_modes(
    path: str | Path,
    *,
    root: str | Path | None = None,
    modifier: str | None = None,
    format: str = "auto",
    groups: Sequence[str] | None = None,
) -> TokenModes:
    """Load a token file of any supported format.

    ``root`` bounds the files a resolver or ``$themes.json`` may name
    (default: the file's folder).  ``modifier`` picks the Resolver modifier
    (or Figma collection) whose contexts are the modes; ``groups`` the Tokens
    Studio theme groups combined into modes (default: every group; ``()``: none).
    """
    p = Path(path)
    bound = Path(root).resolve() if root is not None else p.resolve().parent
    if format in ("css", "tailwind") or (format == "auto" and p.suffix.lower() == ".css"):
        return modes_from_stylesheet(p)
    doc = load_json(p)
    kind = detect_format(doc) if format == "auto" else format
    try:
        return _modes_of(doc, kind, bound, modifier, groups)
    except RecursionError as exc:  # $ref or $extends chains through values nested deep
        from alpha_audit.errors import InputError

        raise InputError(
            "references nest too deeply ($ref or $extends through nested values)", path=p
        ) from exc


def _modes_of(
    doc: JsonDoc, kind: str, bound: Path, modifier: str | None, groups: Sequence[str] | None
) -> TokenModes:
    p = doc.path
    if kind == "figma":
        return modes_from_figma(doc, collection=modifier)
    if kind == "resolver":
        return modes_from_resolver(doc, root=bound, modifier=modifier)
    if kind == "tokens-studio":
        return modes_from_studio(doc, root=bound, groups=groups)
    if kind in ("dtcg", "style-dictionary"):
        tokens = tokens_from_docs([doc], legacy=kind == "style-dictionary")
        return TokenModes(p, kind, {"default": tokens}, "default")
    from alpha_audit.errors import UsageError

    raise UsageError(f"token format {kind!r} is not one of {', '.join(TOKEN_FORMATS)}")
