"""Escaping for the export formats: token and mode names are untrusted text.

A token name may hold any character but ``.``, ``{`` and ``}``; written into
CSS or SVG unescaped, a ``;`` or ``}`` would end the declaration and inject
rules, and ``<`` would inject markup.  CSS identifiers and strings follow CSS
Syntax Level 3 (section 4.3.7, escaped code points as ``\\hex ``); XML
attributes go through :func:`xml.sax.saxutils.quoteattr`.
"""

from __future__ import annotations

import re
from xml.sax.saxutils import quoteattr

__all__ = ["css_comment", "css_ident", "css_string", "xml_attr", "xml_id"]

_IDENT_SAFE = re.compile(r"[A-Za-z0-9_-]")


def css_ident(name: str) -> str:
    """``name`` as a CSS identifier tail: safe ASCII kept, anything else hex-escaped.

    >>> css_ident("color-icon-ok")
    'color-icon-ok'
    >>> css_ident("a;}b")
    'a\\\\3b \\\\7d b'
    """
    return "".join(ch if _IDENT_SAFE.fullmatch(ch) else f"\\{ord(ch):x} " for ch in name)


def css_comment(text: str) -> str:
    """``text`` for the inside of a CSS comment, kept readable.

    A comment interprets no escapes (CSS Syntax Level 3, section 4.3.2), so
    :func:`css_ident` would show ``a\\2e json``; only ``*/`` can end it, and
    control or other unprintable characters become ``?``.

    >>> css_comment("system.resolver.json")
    'system.resolver.json'
    >>> css_comment("a*/b\\n")
    'a* /b?'
    """
    shown = "".join(ch if ch.isprintable() else "?" for ch in text)
    while "*/" in shown:
        shown = shown.replace("*/", "* /")
    return shown


def css_string(text: str) -> str:
    """``text`` as a double-quoted CSS string.

    >>> css_string('da"rk')
    '"da\\\\22 rk"'
    """
    return (
        '"'
        + "".join(f"\\{ord(ch):x} " if ch in '"\\\n\r\f' or ord(ch) < 32 else ch for ch in text)
        + '"'
    )


def xml_attr(text: str) -> str:
    """``text`` as a quoted XML attribute value."""
    return quoteattr(text)


def xml_id(text: str) -> str:
    """An XML id from untrusted text: letters, digits, ``-`` and ``_`` only."""
    cleaned = re.sub(r"[^A-Za-z0-9_-]", "_", text)
    return cleaned if cleaned[:1].isalpha() else f"x{cleaned}"
