"""Resolved design tokens: one record per token path, with where it was set."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Literal, TypedDict

from alpha_audit.errors import InputError
from alpha_audit.model import Span

__all__ = [
    "MAX_ALIAS_CHAIN",
    "MAX_EXPANSION",
    "MAX_MODES",
    "MAX_MODE_TOKENS",
    "MAX_TOKENS",
    "ModeConditions",
    "Steps",
    "Token",
    "TokenModes",
    "TokenPlace",
    "Unresolved",
    "check_mode_budget",
    "follow",
    "too_long",
]

MAX_TOKENS = 100_000  # a large design system has a few thousand tokens
MAX_ALIAS_CHAIN = 64  # longer chains are a generator bug or an attack
# Modes are themes: the same cap as a YAML theme's canvases (load/theme.py).
MAX_MODES = 4096
# Tokens resolved over all modes (modes x tokens): Primer's 9 themes x ~1,000
# colours is 9,000 and daisyUI's 35 themes x 28 is 980, so a million is a
# hundred times the largest real set while bounding a small file that asks
# for thousands of modes of thousands of tokens (each mode re-resolves them).
MAX_MODE_TOKENS = 1_000_000
# Steps of one expansion (JSON Pointer and alias lookups, groups walked,
# $extends copies, CSS var() substitutions and declarations applied) in one
# token source, all its modes together: every step is counted, so a few
# kilobytes that double at every level, or that a thousand modes each walk
# again, stop here with an error, never hang.  Twice MAX_MODE_TOKENS: each
# resolution is a step, and a real source takes one or two per token.
MAX_EXPANSION = 2_000_000


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
    # Why the token cannot be used (an alias to a token the file does not
    # have, no type, a CSS value that is not a colour): raised only where the
    # token is selected, so one broken token nobody selects does not stop a load.
    problem: str | None = field(default=None, compare=False)


@dataclass(frozen=True)
class ModeConditions:
    """The browser state a CSS mode stands for: what a page sets to show it.

    Classes and ``data-*`` attributes on the root element (``<html>``, or a
    shadow host) and on ``<body>``, the ``prefers-color-scheme`` and whether the
    display is wide-gamut (``color-gamut: p3``).  A page in this state computes
    the mode's values on ``<body>``.

    >>> ModeConditions(root_classes=("dark", "felt")).selector()
    ':root.dark.felt'
    >>> ModeConditions(body_attributes=(("data-theme", "dark"),), scheme="dark").selector()
    'body[data-theme="dark"] @media (prefers-color-scheme: dark)'
    """

    root_classes: tuple[str, ...] = ()
    root_attributes: tuple[tuple[str, str], ...] = ()
    body_classes: tuple[str, ...] = ()
    body_attributes: tuple[tuple[str, str], ...] = ()
    scheme: Literal["light", "dark"] = "light"
    p3: bool = False

    def selector(self) -> str:
        """The state as a selector for the element the values are read on, then the media."""

        def side(classes: tuple[str, ...], attributes: tuple[tuple[str, str], ...]) -> str:
            return "".join(f".{c}" for c in classes) + "".join(
                f"[{a}]" if not v else f'[{a}="{v}"]' for a, v in attributes
            )

        root = side(self.root_classes, self.root_attributes)
        body = side(self.body_classes, self.body_attributes)
        parts = [f":root{root}"] if root or not body else []
        parts += [f"body{body}"] if body else []
        text = " ".join(parts)
        media = []
        if self.scheme == "dark":
            media.append("(prefers-color-scheme: dark)")
        if self.p3:
            media.append("(color-gamut: p3)")
        return text + (f" @media {' and '.join(media)}" if media else "")


@dataclass(frozen=True)
class TokenModes:
    """Tokens per mode (a Resolver context, a Figma mode, a Tokens Studio theme).

    ``modes`` keeps the source's order; a source without modes has one mode
    named ``default``.  ``source`` is the file that was loaded and ``kind``
    the detected format (``dtcg``, ``resolver``, ``tokens-studio``, ...).
    ``notes`` say how the source became modes (which CSS rules are which
    mode) for a line on stderr; ``skipped`` maps a token path to where a rule
    that was not read would also set it (a ``min-width`` media query, a
    ``:has()`` state), so a selected token can be warned about.
    ``conditions`` gives, for a CSS source, the browser state of each mode and
    alias; ``aliases`` maps a state that computes exactly what an earlier mode
    computes (``.dark-theme`` beside ``.dark``) to that mode.
    """

    source: Path
    kind: str
    modes: dict[str, dict[str, Token]]
    default: str | None = None
    notes: tuple[str, ...] = ()
    skipped: dict[str, str] = field(default_factory=dict)
    conditions: dict[str, ModeConditions] = field(default_factory=dict)
    aliases: dict[str, str] = field(default_factory=dict)


@dataclass
class Steps:
    """Expansion steps taken for one token source, shared by every mode it resolves.

    The one counter behind :data:`MAX_EXPANSION`: each reader takes its steps
    *before* the work they stand for, so the refusal comes first.
    """

    taken: int = 0

    def take(self, n: int, what: str, place: Callable[[], TokenPlace]) -> None:
        """Take ``n`` steps of ``what``; past :data:`MAX_EXPANSION`, an error at ``place()``
        (called only then: a step costs an addition)."""
        self.taken += n
        if self.taken > MAX_EXPANSION:
            raise InputError(
                f"{what} takes more than {MAX_EXPANSION:,} steps; the file expands without bound",
                **place(),
            )


def check_mode_budget(path: Path, modes: int, tokens: int) -> None:
    """Refuse more than :data:`MAX_MODES` modes or :data:`MAX_MODE_TOKENS` resolutions.

    Called before any mode is resolved, so the refusal costs nothing.
    """
    if modes > MAX_MODES:
        raise InputError(
            f"{modes} modes; at most {MAX_MODES} (the cap on a theme's canvases)", path=path
        )
    if modes * tokens > MAX_MODE_TOKENS:
        raise InputError(
            f"{modes} modes x {tokens} tokens = {modes * tokens:,} to resolve; at most "
            f"{MAX_MODE_TOKENS:,} per token source",
            path=path,
        )


class TokenPlace(TypedDict):
    """Where a token error points: :class:`InputError`'s keywords, to pass as ``**place``."""

    path: Path | None
    line: int | None
    key: str | None


class Unresolved(Exception):
    """A reference the source cannot resolve (an alias to a token or variable it does not
    hold): the token loads with it as its :attr:`Token.problem`, an error only where selected."""

    def __init__(self, problem: str, line: int | None) -> None:
        super().__init__(problem)
        self.problem = problem
        self.line = line


def too_long(
    what: str, chain: Sequence[str], place: TokenPlace, label: Callable[[str], str] = str
) -> InputError:
    """The error for a ``what`` chain (alias, ``$ref``, ``var()``) past :data:`MAX_ALIAS_CHAIN`."""
    shown = " -> ".join(label(n) for n in chain[:4])
    return InputError(f"{what} chain longer than {MAX_ALIAS_CHAIN}: {shown} -> ...", **place)


def follow(
    stack: Sequence[str],
    name: str,
    what: str,
    place: Callable[[], TokenPlace],
    label: Callable[[str], str] = str,
) -> None:
    """Refuse following a reference to ``name`` from the chain ``stack`` when it closes a
    cycle or makes the chain longer than :data:`MAX_ALIAS_CHAIN`: every token format's one
    guard.  The error is at ``place()`` (called only then) and names the chain by ``label``.
    """
    if name in stack:
        loop = " -> ".join(label(n) for n in [*stack[stack.index(name) :], name])
        raise InputError(f"{what} cycle: {loop}", **place())
    if len(stack) >= MAX_ALIAS_CHAIN:
        raise too_long(what, stack, place(), label)
