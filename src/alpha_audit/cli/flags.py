"""Library parameters as the command line spells them.

The library's errors name keyword parameters in backticks (```overwrite=True```,
```alphas```) so that they read right from Python; :func:`cli_message` words
them as the flags a command-line user types instead.
"""

from __future__ import annotations

import re

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


def cli_message(exc: AlphaAuditError) -> str:
    """``str(exc)`` with each known backticked parameter phrase replaced by its flag.

    >>> from alpha_audit.errors import UsageError
    >>> exc = UsageError("already exists; pass `overwrite=True` to replace it", path="r.json")
    >>> cli_message(exc)
    'r.json: already exists; pass --force to replace it'
    """
    where = exc.where()
    message = _PHRASE.sub(lambda m: FLAGS.get(m.group(1), m.group(0)), exc.message)
    return f"{where}: {message}" if where else message
