"""One exception family for the whole library.

Every error says *where* (file and line or key), *what* (the bad value) and
*what is allowed*, so the CLI can print it on one line and exit 2.  Only
:mod:`alpha_audit.cli.root` turns these into exit codes.  A message names a
keyword parameter in backticks (```overwrite=True```), which the command line
rewords as its flag (:mod:`alpha_audit.cli.flags`).
"""

from __future__ import annotations

from pathlib import Path

__all__ = [
    "AlphaAuditError",
    "ColorSyntaxError",
    "InputError",
    "SvgError",
    "UsageError",
]


class AlphaAuditError(Exception):
    """Base of every error alpha-audit raises on purpose.

    ``path`` is the file at fault (if any), ``location`` a line number or a key
    path such as ``canvases[2].color``.
    """

    def __init__(
        self,
        message: str,
        *,
        path: str | Path | None = None,
        line: int | None = None,
        key: str | None = None,
    ) -> None:
        from alpha_audit.safe_text import safe_text

        # Keys, paths and values come from untrusted files: ``message`` and
        # :meth:`where` are escaped here, once, so every way of printing an
        # error (``str()``, the CLI's one line) sends no control character.
        super().__init__(message)
        self.message = safe_text(message)
        self.path = None if path is None else Path(path)
        self.line = line
        self.key = key

    def where(self, shown_path: str | None = None) -> str:
        """``file:line: key`` prefix, omitting what is unknown (escaped like the message).

        ``shown_path`` names the file instead of ``path`` as given (the command
        line shows it relative to the project).
        """
        from alpha_audit.safe_text import safe_text

        parts = []
        if self.path is not None:
            file = shown_path or str(self.path)
            parts.append(f"{file}:{self.line}" if self.line else file)
        if self.key:
            parts.append(self.key)
        return safe_text(": ".join(parts))

    def __str__(self) -> str:
        where = self.where()
        return f"{where}: {self.message}" if where else self.message


class InputError(AlphaAuditError):
    """A theme, manifest, config or colour the user supplied is invalid."""


class UsageError(AlphaAuditError):
    """Options that cannot be combined or a file that cannot be found."""


class ColorSyntaxError(InputError, ValueError):
    """A colour string that is not one of the accepted sRGB notations."""


class SvgError(InputError):
    """An SVG that cannot be rasterised; reported per file, not fatal by default."""
