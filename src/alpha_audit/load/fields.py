"""Typed field readers for YAML documents: each failure names file, line, key and value."""

from __future__ import annotations

import difflib
import math
from collections.abc import Iterable
from typing import Any

import numpy as np

from alpha_audit.color import PIPELINES, GamutPolicy, Pipeline, parse_color
from alpha_audit.color.css import parse_css_color
from alpha_audit.constants import GAMUT_POLICIES
from alpha_audit.errors import ColorSyntaxError
from alpha_audit.load.names import check_name
from alpha_audit.load.yamldoc import KeyPath, YamlDoc, format_key
from alpha_audit.model import GamutAdjustment
from alpha_audit.ranges import NumberRange

__all__ = [
    "check_keys",
    "read_color",
    "read_gamut",
    "read_mapping",
    "read_name",
    "read_number",
    "read_pipeline",
]

_TYPE_NAMES = {
    bool: "a boolean",
    int: "a number",
    float: "a number",
    str: "a string",
    list: "a list",
    dict: "a mapping",
    type(None): "empty",
}


def describe(value: Any) -> str:
    """``'abc' (a string)`` style description of a YAML value."""
    kind = _TYPE_NAMES.get(type(value), type(value).__name__)
    if value is None:
        return "empty"
    text = repr(value)
    if len(text) > 40:
        text = text[:37] + "..."
    return f"{text} ({kind})"


def check_keys(
    doc: YamlDoc, keys: KeyPath, mapping: dict[str, Any], allowed: Iterable[str]
) -> None:
    """Reject unknown keys, suggesting the closest allowed one."""
    allowed = sorted(allowed)
    for key in mapping:
        if key not in allowed:
            close = difflib.get_close_matches(key, allowed, n=1)
            hint = f"did you mean {close[0]!r}? " if close else ""
            raise doc.error(
                (*keys, key), f"unknown key {key!r}; {hint}allowed: {', '.join(allowed)}"
            )


def read_mapping(doc: YamlDoc, keys: KeyPath, value: Any, what: str) -> dict[str, Any]:
    """``value`` must be a mapping."""
    if not isinstance(value, dict):
        raise doc.error(keys, f"expected {what} (a mapping of keys), got {describe(value)}")
    return value


def read_name(doc: YamlDoc, keys: KeyPath, value: Any) -> str:
    """A non-empty one-line name (numbers are accepted and turned into text)."""
    if isinstance(value, bool) or not isinstance(value, str | int | float):
        raise doc.error(keys, f"expected a name (text), got {describe(value)}")
    text = str(value).strip()
    # Control, format (bidi) and surrogate characters would forge report lines,
    # drive the reviewer's terminal or crash UTF-8 output; names reach every
    # format.  The one name policy of every input (alpha_audit.safe_text).
    return check_name(text, path=doc.path, line=doc.line(keys), key=format_key(keys), what="")


def read_number(
    doc: YamlDoc,
    keys: KeyPath,
    value: Any,
    *,
    low: float = -math.inf,
    high: float = math.inf,
    what: str = "a finite number",
    allowed: NumberRange | None = None,
) -> float:
    """A finite real in ``allowed`` (else ``[low, high]``); booleans, strings and NaN are refused.

    ``allowed`` is the range a key shares with its command-line flag
    (:mod:`alpha_audit.ranges`), refused in the same words.
    """
    allowed = allowed or NumberRange(low, high, what)
    if isinstance(value, bool) or not isinstance(value, int | float):
        hint = " (quote-free, e.g. 1.1)" if isinstance(value, str) else ""
        raise doc.error(keys, f"expected {allowed.what}{hint}, got {describe(value)}")
    if not allowed.allows(float(value)):
        raise doc.error(keys, allowed.refusal(repr(value)))
    return float(value)


def read_gamut(doc: YamlDoc, keys: KeyPath, value: Any) -> GamutPolicy:
    """A gamut policy: ``clip``, ``map`` or ``error`` (:mod:`alpha_audit.color.css`)."""
    if value not in GAMUT_POLICIES:
        raise doc.error(
            keys,
            f"{describe(value)} is not a gamut policy; use one of: {', '.join(GAMUT_POLICIES)}",
        )
    return value  # type: ignore[no-any-return]  # checked against GAMUT_POLICIES above


def read_color(
    doc: YamlDoc,
    keys: KeyPath,
    value: Any,
    *,
    gamut: GamutPolicy = "error",
    adjusted: list[GamutAdjustment] | None = None,
    owner: str = "",
) -> str:
    """A colour string accepted by :func:`alpha_audit.color.parse_color`.

    A colour outside sRGB follows ``gamut``: under ``clip`` or ``map`` the
    result is the exact fitted ``color(srgb ...)`` and a
    :class:`~alpha_audit.model.GamutAdjustment` (``owner`` naming the theme or
    icon set) is appended to ``adjusted``.  In-gamut colours come back as
    written, so their numbers do not change.
    """
    if value is None:
        raise doc.error(
            keys,
            'colour is empty; an unquoted #hex starts a YAML comment: quote it, e.g. "#0d1117"',
        )
    if not isinstance(value, str):
        raise doc.error(keys, f"expected a colour string, got {describe(value)}")
    try:
        parse_color(value)
    except ColorSyntaxError as exc:
        if gamut == "error":
            raise doc.error(keys, exc.message) from exc
        try:  # outside sRGB (or not a colour at all, which raises again)
            parsed = parse_css_color(value, gamut=gamut)
        except ColorSyntaxError as again:
            raise doc.error(keys, again.message) from again
        if not parsed.adjusted:
            raise doc.error(keys, exc.message) from exc
        r, g, b = (int(v) for v in np.rint(parsed.array * 255))
        if adjusted is not None:
            adjusted.append(
                GamutAdjustment(
                    mode=owner,
                    token=format_key(keys),
                    text=value.strip(),
                    policy=gamut,
                    output=f"#{r:02x}{g:02x}{b:02x}",
                    delta_e=parsed.delta_e,
                    file=doc.path,
                    line=doc.line(keys),
                )
            )
        return parsed.css
    return value


def read_pipeline(doc: YamlDoc, keys: KeyPath, value: Any) -> Pipeline:
    """``linear`` or ``css`` (docs/model.md, "Pipelines")."""
    name = value.strip().lower() if isinstance(value, str) else None
    if name not in PIPELINES:
        raise doc.error(
            keys, f"{describe(value)} is not a pipeline; use one of: {', '.join(PIPELINES)}"
        )
    return name
