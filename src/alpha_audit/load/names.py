"""The load-side half of the name policy: every name read from any input is checked here.

YAML names and keys, token paths, CSS custom properties and modes, Figma
variables, collections and modes, Resolver sets, modifiers and contexts,
Tokens Studio themes and sets pass :func:`check_name`, which refuses what
:func:`~alpha_audit.safe_text.safe_text` would escape, with one message naming
the file, the place and the character.
"""

from __future__ import annotations

from pathlib import Path

from alpha_audit.errors import InputError
from alpha_audit.safe_text import MAX_NAME, describe_char, first_unsafe, safe_text

__all__ = ["check_name"]


def check_name(
    text: str,
    *,
    path: object = None,
    line: int | None = None,
    key: str | None = None,
    what: str = "name",
) -> str:
    """``text`` if it is a usable name, else an :class:`~alpha_audit.errors.InputError`.

    A usable name has 1-:data:`MAX_NAME` characters and none that
    :func:`safe_text` escapes (controls, bidi and other format characters,
    lone surrogates, line separators); emoji joiners are fine.  The error
    names ``path``, ``line`` and ``key``, shows the name escaped and says which
    character is refused, by code point.

    >>> check_name("👩\u200d💻")
    '👩\u200d💻'
    >>> try:
    ...     check_name("a\u202eb", key="color.x")
    ... except Exception as exc:
    ...     print(str(exc)[:67])
    color.x: name 'a\\u202eb' has the bidi control U+202E (RIGHT-TO-LEFT
    """
    bad = first_unsafe(text)
    if bad is None and 0 < len(text) <= MAX_NAME:
        return text
    shown = safe_text(text[:40]) + ("..." if len(text) > 40 else "")
    named = f"{what} '{shown}'" if what else f"'{shown}'"
    if bad is None:
        message = f"{named} is empty or longer than {MAX_NAME} characters; a name has 1-{MAX_NAME}"
    else:
        message = (
            f"{named} has {describe_char(bad)}; names may not hold control, bidi, "
            "invisible format or surrogate characters"
        )
    raise InputError(
        message,
        path=None if path is None else Path(str(path)),
        line=line,
        key=None if key is None else safe_text(key),
    )
