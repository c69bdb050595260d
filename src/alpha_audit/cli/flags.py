"""Library parameters as the command line spells them.

The library's errors name keyword parameters in backticks (```overwrite=True```,
```alphas```) so that they read right from Python; :func:`cli_message` words
them as the flags a command-line user types instead.
"""

from __future__ import annotations

import os
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


def cli_message(exc: AlphaAuditError) -> str:
    """``str(exc)`` with each known backticked parameter phrase replaced by its flag.

    >>> from alpha_audit.errors import UsageError
    >>> exc = UsageError("already exists; pass `overwrite=True` to replace it", path="r.json")
    >>> cli_message(exc)
    'r.json: already exists; pass --force to replace it'
    """
    where = exc.where(_shown_path(exc.path))
    message = _PHRASE.sub(lambda m: FLAGS.get(m.group(1), m.group(0)), exc.message)
    return f"{where}: {message}" if where else message


def _shown_path(path: Path | None) -> str | None:
    """A file of the project written relative to the working folder (``../x.yaml`` from a
    subfolder), as the user would type it; anything outside the project as it is."""
    from alpha_audit.load.paths import project_root

    if path is None or not path.is_absolute():
        return None
    here = Path.cwd()
    if not path.is_relative_to(project_root(here)):
        return None
    return os.path.relpath(path, here)
