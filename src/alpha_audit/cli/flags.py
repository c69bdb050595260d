"""Library parameters as the command line spells them.

The library's errors name keyword parameters in backticks (```overwrite=True```,
```alphas```) so that they read right from Python; :func:`cli_message` words
them as the flags a command-line user types instead.
"""

from __future__ import annotations

import re
from pathlib import Path

from alpha_audit.errors import AlphaAuditError

__all__ = ["FLAGS", "cli_message"]

FLAGS: dict[str, str] = {
    "overwrite=True": "--force",
    "alphas": "--alpha",
    "alpha": "--alpha",
    "rules": "--fail-on",
    "sizes": "--size",
    "out_dir": "-o DIR",
    "html_path": "--html FILE",
    "baseline_document": "--write-baseline",
    "icons": "--icons",
    "gamut": "--gamut",
    "engines": "--engine",
    "pipeline": "--pipeline",
    "max_combinations": "max-combinations (--max-combinations)",
    "base": "--base",
    "globals": "--globals",
}
"""Backticked phrase in a library message -> what the command line says instead."""

_PHRASE = re.compile(r"`([^`\n]+)`")


def cli_message(exc: AlphaAuditError, base: Path | None = None) -> str:
    """``str(exc)`` with each known backticked parameter phrase replaced by its flag.

    The file is named relative to ``base`` (the project root) when it lies
    inside it, however it was found (a config resolves its paths):

    >>> from alpha_audit.errors import UsageError
    >>> exc = UsageError("already exists; pass `overwrite=True` to replace it", path="/p/r.json")
    >>> cli_message(exc, Path("/p"))
    'r.json: already exists; pass --force to replace it'
    """
    from alpha_audit.render.common import display_path

    where = exc.where(display_path(exc.path, base))
    message = _PHRASE.sub(lambda m: FLAGS.get(m.group(1), m.group(0)), exc.message)
    return f"{where}: {message}" if where else message
