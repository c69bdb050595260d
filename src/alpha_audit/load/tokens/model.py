"""Resolved design tokens: one record per token path, with where it was set."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, TypedDict

from alpha_audit.errors import InputError
from alpha_audit.model import Span

__all__ = ["MAX_ALIAS_CHAIN", "MAX_TOKENS", "Token", "TokenModes", "TokenPlace", "token_error"]

MAX_TOKENS = 100_000  # a large design system has a few thousand tokens
MAX_ALIAS_CHAIN = 64  # longer chains are a generator bug or an attack


@dataclass(frozen=True)
class Token:
    """A design token after alias resolution.

    ``value`` is the resolved ``$value`` (plain JSON data); ``chain`` the
    token paths followed to reach it (empty for a literal value).  ``file``
    and ``line`` locate the token that *sets* the value: the end of the
    chain, so a report points at the line to edit; ``span`` is the exact
    place of that token's value when it is a string written in the file (a
    colour object, a ``$ref`` or a value the format does not locate has none).
    """

    path: str
    type: str
    value: Any
    file: Path | None = None
    line: int | None = None
    extensions: dict[str, Any] = field(default_factory=dict, compare=False)
    description: str | None = field(default=None, compare=False)
    deprecated: bool | str = field(default=False, compare=False)
    chain: tuple[str, ...] = field(default=(), compare=False)
    alias_line: int | None = field(default=None, compare=False)
    alias_file: Path | None = field(default=None, compare=False)
    span: Span | None = field(default=None, compare=False, repr=False)


@dataclass(frozen=True)
class TokenModes:
    """Tokens per mode (a Resolver context, a Figma mode, a Tokens Studio theme).

    ``modes`` keeps the source's order; a source without modes has one mode
    named ``default``.  ``source`` is the file that was loaded and ``kind``
    the detected format (``dtcg``, ``resolver``, ``tokens-studio``, ...).
    """

    source: Path
    kind: str
    modes: dict[str, dict[str, Token]]
    default: str | None = None


class TokenPlace(TypedDict):
    """Where a token error points: :func:`token_error`'s keywords, to pass as ``**place``."""

    file: Path | None
    line: int | None
    path: str | None


def token_error(
    message: str, *, file: Path | None, line: int | None, path: str | None
) -> InputError:
    """An input error naming the token file, its JSON line and the token path."""
    return InputError(message, path=file, line=line, key=path)
