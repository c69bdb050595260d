"""The one name policy: which characters of untrusted text are instructions, not text.

Every file of a pull request is attacker-controlled, and what we print lands
in a reviewer's terminal, in the Actions log and in every report.  Characters
that are not text but instructions are refused in names at load
(:func:`alpha_audit.load.names.check_name`) and shown as escapes by every
renderer (:func:`safe_text`):

- ``Cc`` control characters: C0 (newline starts a forged ``::error`` or
  ``::stop-commands::`` line), DEL, and C1 (``U+009B`` is a one-byte CSI);
  ESC starts CSI/OSC sequences (OSC 52 writes the clipboard, OSC 8 links).
- ``Cf`` format characters: the bidi controls :data:`BIDI_CONTROLS`
  (Trojan Source, CVE-2021-42574), the BOM, zero-width spaces and the
  invisible tag characters.  Two kinds are text: the zero-width joiner and
  non-joiner (``U+200D``, ``U+200C``: emoji ZWJ sequences such as ``👩‍💻``,
  Persian and Indic shaping), and tag characters inside an emoji tag
  sequence (the subdivision flags such as ``🏴󠁧󠁢󠁳󠁣󠁴󠁿``).
- ``Cs`` lone surrogates: legal in YAML and JSON escapes and in file names
  that are not UTF-8, unencodable in UTF-8 (a report would crash on them).
- ``Zl``/``Zp`` line and paragraph separators: new lines to some renderers.

Categories are Unicode's General_Category (Unicode Standard, section 4.5),
read through :mod:`unicodedata`.
"""

from __future__ import annotations

import re
import unicodedata

__all__ = [
    "BIDI_CONTROLS",
    "JOINERS",
    "MAX_NAME",
    "UNSAFE_CATEGORIES",
    "describe_char",
    "escape_char",
    "first_unsafe",
    "is_safe",
    "safe_text",
    "shorten",
]

# Unicode General_Category values that are instructions rather than text.
UNSAFE_CATEGORIES = frozenset({"Cc", "Cf", "Cs", "Zl", "Zp"})
# Format characters that are text: ZERO WIDTH NON-JOINER and ZERO WIDTH JOINER
# (Unicode Standard, section 23.2); neither is a bidi control (UAX #9, 2.1-2.7).
JOINERS = frozenset({"\u200c", "\u200d"})
# The explicit directional formatting characters and the implicit marks
# (UAX #9, sections 2.1-2.6): ALM, LRM, RLM, LRE-RLO, LRI-PDI.
BIDI_CONTROLS = frozenset(
    "\u061c\u200e\u200f\u202a\u202b\u202c\u202d\u202e\u2066\u2067\u2068\u2069"
)
MAX_NAME = 200  # characters: a name is a label, not a document
# An emoji tag sequence (UTS #51, ED-14a and annex C): WAVING BLACK FLAG, the
# tag letters and digits of a subdivision id (CLDR unicode_subdivision_id: a
# region of 2 letters or 3 digits and a suffix of 1-4, so 3-7 tags), CANCEL TAG.
_EMOJI_TAG_SEQUENCE = re.compile(
    "\U0001f3f4[\U000e0030-\U000e0039\U000e0061-\U000e007a]{3,7}\U000e007f"
)
_FLAG = "\U0001f3f4"


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


def describe_char(ch: str) -> str:
    """What an unsafe character is, by kind and code point, for an error message.

    >>> describe_char("\\x1b")
    'the control character U+001B'
    >>> describe_char("\\u202e")
    'the bidi control U+202E (RIGHT-TO-LEFT OVERRIDE)'
    >>> describe_char("\\ud800")
    'the lone surrogate U+D800'
    """
    category = unicodedata.category(ch)
    if ch in BIDI_CONTROLS:
        kind = "bidi control"
    else:
        kind = {
            "Cc": "control character",
            "Cf": "invisible format character",
            "Cs": "lone surrogate",
            "Zl": "line separator",
            "Zp": "paragraph separator",
        }.get(category, "character")
    name = unicodedata.name(ch, "") if category == "Cf" else ""
    return f"the {kind} U+{ord(ch):04X}" + (f" ({name})" if name else "")


def first_unsafe(text: str) -> str | None:
    """The first character :func:`safe_text` would escape, or ``None``.

    >>> first_unsafe("ok name") is None
    True
    >>> first_unsafe("evil\\u202etxt.svg")
    '\\u202e'
    """
    if text.isprintable():  # C speed: no Cc, Cf, Cs, Zl or Zp (nor any other invisible)
        return None
    if _FLAG in text:
        text = _EMOJI_TAG_SEQUENCE.sub(_FLAG, text)
    return next((ch for ch in text if _unsafe(ch)), None)


def is_safe(text: str) -> bool:
    """True when ``text`` has nothing :func:`safe_text` would escape."""
    return first_unsafe(text) is None


def _escape_run(text: str, newlines: bool) -> str:
    return "".join(
        escape_char(ch) if _unsafe(ch) and not (newlines and ch == "\n") else ch for ch in text
    )


def safe_text(text: object, *, newlines: bool = False) -> str:
    """``str(text)`` with every control, format, surrogate or separator character escaped.

    ``newlines=True`` keeps ``\\n`` (for callers that escape it themselves, as
    GitHub workflow commands do, or that lay out lines); everything else unsafe
    is always escaped.

    >>> safe_text("a\\x1b]52;c;SGVsbG8=\\x07b")
    'a\\\\x1b]52;c;SGVsbG8=\\\\x07b'
    >>> safe_text("line\\n::error::forged")
    'line\\\\x0a::error::forged'
    >>> safe_text("\\ud800").encode("utf-8")
    b'\\\\ud800'
    """
    s = text if isinstance(text, str) else str(text)
    if first_unsafe(s) is None:
        return s
    if _FLAG not in s:
        return _escape_run(s, newlines)
    out, pos = [], 0
    for match in _EMOJI_TAG_SEQUENCE.finditer(s):
        out += [_escape_run(s[pos : match.start()], newlines), match.group()]
        pos = match.end()
    return "".join([*out, _escape_run(s[pos:], newlines)])


def shorten(text: str, limit: int = MAX_NAME) -> str:
    """``text`` if it has at most ``limit`` characters, else its start and end around ``…``.

    For names an untrusted page or file supplies that are shown, not matched
    (a DOM path, a script's error): the start and the end are what tell one
    from another; the result has exactly ``limit`` characters.

    >>> shorten("html > body > div#" + "x" * 300 + " > svg", 40)
    'html > body > div#xx…xxxxxxxxxxxxx > svg'
    >>> shorten("short", 40)
    'short'
    """
    if len(text) <= limit:
        return text
    tail = (limit - 1) // 2
    return text[: limit - 1 - tail] + "…" + text[len(text) - tail :]
