"""Escaping for the export formats: token and mode names are untrusted text.

A token name may hold any character but ``.``, ``{`` and ``}``; written into
CSS or SVG unescaped, a ``;`` or ``}`` would end the declaration and inject
rules, and ``<`` would inject markup.  CSS names, identifiers and strings
follow CSS Syntax Level 3 (section 4.3.7, escaped code points as ``\\hex ``;
an identifier's start as CSSOM's "serialize an identifier" has it); XML text
and attributes go through :func:`~alpha_audit.render.common.xml_safe` (the
one name policy's escapes, nothing XML forbids) and :mod:`xml.sax.saxutils`.
"""

from __future__ import annotations

import re
from xml.sax.saxutils import escape, quoteattr

from alpha_audit.render.common import xml_safe

__all__ = [
    "css_comment",
    "css_ident",
    "css_name",
    "css_string",
    "xml_attr",
    "xml_id",
    "xml_text",
]

_NAME_SAFE = re.compile(r"[A-Za-z0-9_-]")


def _hex(ch: str) -> str:
    return f"\\{ord(ch):x} "


def css_name(name: str) -> str:
    """``name`` as a CSS name (what follows ``--`` or ``#``): safe ASCII kept, the rest escaped.

    >>> css_name("color-icon-ok")
    'color-icon-ok'
    >>> css_name("a;}b")
    'a\\\\3b \\\\7d b'
    >>> css_name("1x")
    '1x'
    """
    return "".join(ch if _NAME_SAFE.fullmatch(ch) else _hex(ch) for ch in name)


def css_ident(name: str) -> str:
    """``name`` as a whole CSS identifier (a class name, an unquoted attribute value).

    An identifier may not start with a digit, nor with ``-`` and a digit, and
    is not ``-`` alone (CSS Syntax Level 3, 4.3.9; CSSOM, "serialize an
    identifier"): such a start is escaped; the rest is :func:`css_name`.

    >>> css_ident("dark")
    'dark'
    >>> css_ident("1dark")
    '\\\\31 dark'
    >>> css_ident("-2x")
    '-\\\\32 x'
    >>> css_ident("-")
    '\\\\-'
    """
    if name == "-":
        return "\\-"
    if name[:1].isdigit() and name[:1].isascii():
        return _hex(name[0]) + css_name(name[1:])
    if name[:1] == "-" and name[1:2].isdigit() and name[1:2].isascii():
        return "-" + _hex(name[1]) + css_name(name[2:])
    return css_name(name)


def css_comment(text: str) -> str:
    """``text`` for the inside of a CSS comment, kept readable.

    A comment interprets no escapes (CSS Syntax Level 3, section 4.3.2), so
    :func:`css_name` would show ``a\\2e json``; only ``*/`` can end it, and
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

    Quotes, backslashes and ``<`` (a ``</style>`` when the sheet is inlined)
    are escaped, and so is every character that is not printable: controls,
    bidi and other format characters, lone surrogates (which CSS reads back as
    U+FFFD).

    >>> css_string('da"rk')
    '"da\\\\22 rk"'
    >>> css_string("</style>")
    '"\\\\3c /style\\\\3e "'
    """
    return (
        '"'
        + "".join(_hex(ch) if ch in '"\\<>' or not ch.isprintable() else ch for ch in text)
        + '"'
    )


def xml_attr(text: str) -> str:
    """``text`` as a quoted XML attribute value."""
    return quoteattr(xml_safe(text))


def xml_text(text: str) -> str:
    """``text`` as XML character data (element content).

    >>> xml_text("a<b & c\\x1b")
    'a&lt;b &amp; c\\\\x1b'
    """
    return escape(xml_safe(text))


def xml_id(text: str) -> str:
    """An XML id from untrusted text: letters, digits, ``-`` and ``_`` only."""
    cleaned = re.sub(r"[^A-Za-z0-9_-]", "_", text)
    return cleaned if cleaned[:1].isalpha() else f"x{cleaned}"
