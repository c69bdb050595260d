"""Colour token values to sRGB: DTCG colour objects and CSS colour strings."""

from __future__ import annotations

import re
from typing import Any

from alpha_audit.color.css import ParsedColor, color_from_components, parse_css_color
from alpha_audit.constants import GamutPolicy
from alpha_audit.errors import ColorSyntaxError, InputError
from alpha_audit.load.tokens.model import Token, TokenPlace

__all__ = ["token_color"]

_OBJECT_KEYS = frozenset({"colorSpace", "components", "alpha", "hex"})
# The fallback is #rrggbb (DTCG Color Module 2025.10, hex); shorter and alpha forms seen in
# the wild are let through, anything else is a malformed value.
_HEX = re.compile(r"#(?:[0-9a-fA-F]{3,4}|[0-9a-fA-F]{6}|[0-9a-fA-F]{8})")


def token_color(
    token: Token, *, gamut: GamutPolicy = "error", allow_alpha: bool = False
) -> ParsedColor:
    """The sRGB colour of a ``color`` token under ``gamut``.

    Accepts the DTCG Color Module object ``{colorSpace, components, alpha?,
    hex?}`` (``hex`` is only a fallback for tools without the space, so the
    components decide) and any CSS Color 4 string, which many files in the
    wild still use.  Errors name the token's file, line and path.
    """
    where: TokenPlace = {"path": token.file, "line": token.line, "key": token.path}
    if token.problem is not None:
        raise InputError(token.problem, **where)
    if token.type != "color":
        via = f" (via {' -> '.join(token.chain)})" if token.chain else ""
        raise InputError(f"is a {token.type!r} token{via}, not a color token", **where)
    value: Any = token.value
    try:
        if isinstance(value, str):
            return parse_css_color(value, gamut=gamut, allow_alpha=allow_alpha)
        if isinstance(value, dict):
            unknown = sorted(set(value) - _OBJECT_KEYS)
            if unknown or "colorSpace" not in value or "components" not in value:
                raise ColorSyntaxError(
                    "a colour object has colorSpace, components, alpha (optional) and hex "
                    f"(optional); got keys {', '.join(sorted(value))}"
                )
            fallback = value.get("hex", "#000000")
            if not isinstance(fallback, str):  # named by its type: a big value is never printed
                raise ColorSyntaxError(
                    "hex must be a #rrggbb string (DTCG Color Module), got a "
                    f"{type(fallback).__name__}"
                )
            if not _HEX.fullmatch(fallback):
                raise ColorSyntaxError(
                    f"hex must be a #rrggbb string (DTCG Color Module), got {fallback[:40]!r}"
                )
            components = value["components"]
            if not isinstance(components, list):
                raise ColorSyntaxError(f"components must be a list, got {components!r:.40}")
            return color_from_components(
                value["colorSpace"],
                components,
                value.get("alpha", 1.0),
                gamut=gamut,
                allow_alpha=allow_alpha,
                text=f"{value['colorSpace']} {components}",
            )
    except ColorSyntaxError as exc:
        raise InputError(exc.message, **where) from exc
    raise InputError(f"expected a colour object or string, got {value!r:.40}", **where)
