"""The one sanitiser for text from input files that reaches a terminal or a CI log.

Every file of a pull request is attacker-controlled, and what we print lands
in a reviewer's terminal and in the Actions log.  Characters that are not
text but instructions are shown as escapes instead of being sent:

- ``Cc`` control characters: C0 (newline starts a forged ``::error`` or
  ``::stop-commands::`` line), DEL, and C1 (``U+009B`` is a one-byte CSI);
  ESC starts CSI/OSC sequences (OSC 52 writes the clipboard, OSC 8 links).
- ``Cf`` format characters: the bidi embeddings, overrides and isolates
  ``U+202A-202E``, ``U+2066-2069`` (Trojan Source, CVE-2021-42574), the BOM and
  the invisible tag characters.  The zero-width joiner and non-joiner
  (``U+200D``, ``U+200C``) are not: they join emoji sequences (``👩‍💻``) and
  shape Persian and Indic text, and steer nothing.
- ``Cs`` lone surrogates: legal in YAML escapes, unencodable in UTF-8 (every
  report crashed with ``UnicodeEncodeError``).
- ``Zl``/``Zp`` line and paragraph separators: new lines to some renderers.

Categories are Unicode's General_Category (Unicode Standard, section 4.5),
read through :mod:`unicodedata`.

:func:`alpha_audit.load.names.check_name` is the load-side half: every name read from any input
(YAML names, token paths, CSS custom properties, Figma variables, Resolver
contexts, Tokens Studio themes and sets) is refused there, with one message
naming the file and the place, if it holds such a character.
"""

from __future__ import annotations

import unicodedata

__all__ = [
    "JOINERS",
    "MAX_NAME",
    "UNSAFE_CATEGORIES",
    "escape_char",
    "first_unsafe",
    "is_safe",
    "safe_text",
]

# Unicode General_Category values that are instructions rather than text.
UNSAFE_CATEGORIES = frozenset({"Cc", "Cf", "Cs", "Zl", "Zp"})
# Format characters that are text: ZERO WIDTH NON-JOINER and ZERO WIDTH JOINER
# (Unicode Standard, section 23.2); neither is a bidi control (UAX #9, 2.1-2.7).
JOINERS = frozenset({"\u200c", "\u200d"})
MAX_NAME = 200  # characters: a name is a label, not a document


def _unsafe(ch: str) -> bool:
    return ch not in JOINERS and unicodedata.category(ch) in UNSAFE_CATEGORIES


def escape_char(ch: str) -> str:
    """``\\x1b``, ``\\u202e``, ``\\ud800``: the Python escape, readable and inert."""
    code = ord(ch)
    if code < 0x100:
        return f"\\x{code:02x}"
    if code < 0x10000:
        return f"\\u{code:04x}"
    return f"\\U{code:08x}"


def first_unsafe(text: str) -> str | None:
    """The first character :func:`safe_text` would escape, or ``None``.

    >>> first_unsafe("ok name") is None
    True
    >>> first_unsafe("evil\\u202etxt.svg")
    '\\u202e'
    """
    return next((ch for ch in text if _unsafe(ch)), None)


def is_safe(text: str) -> bool:
    """True when ``text`` has nothing :func:`safe_text` would escape."""
    return first_unsafe(text) is None


def safe_text(text: object, *, newlines: bool = False) -> str:
    """``str(text)`` with every control, format, surrogate or separator character escaped.

    ``newlines=True`` keeps ``\\n`` (for callers that escape it themselves, as
    GitHub workflow commands do); everything else unsafe is always escaped.

    >>> safe_text("a\\x1b]52;c;SGVsbG8=\\x07b")
    'a\\\\x1b]52;c;SGVsbG8=\\\\x07b'
    >>> safe_text("line\\n::error::forged")
    'line\\\\x0a::error::forged'
    >>> safe_text("\\ud800").encode("utf-8")
    b'\\\\ud800'
    """
    s = text if isinstance(text, str) else str(text)
    if is_safe(s):
        return s
    return "".join(
        escape_char(ch) if _unsafe(ch) and not (newlines and ch == "\n") else ch for ch in s
    )
