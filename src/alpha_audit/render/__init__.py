"""Renderers: pure functions from audit results to text, chosen by name.

Each format lives in its own module with a ``render_check(result, options)``
function; :data:`FORMATS` is the registry the CLI reads.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from enum import StrEnum
from typing import assert_never

from alpha_audit.audit import AuditResult

__all__ = ["CheckFormat", "RenderOptions", "render_check"]


@dataclass(frozen=True)
class RenderOptions:
    """What a renderer may know about its destination (never probed inside)."""

    width: int = 100
    color: bool = False


class CheckFormat(StrEnum):
    """Output formats of ``alpha-audit check``."""

    TABLE = "table"
    JSON = "json"

    def renderer(self) -> Callable[[AuditResult, RenderOptions], str]:
        """The render function for this format."""
        if self is CheckFormat.TABLE:
            from alpha_audit.render.table import render_check as table

            return table
        if self is CheckFormat.JSON:
            from alpha_audit.render.json import render_check as as_json

            return as_json
        assert_never(self)


def render_check(result: AuditResult, fmt: CheckFormat | str, options: RenderOptions) -> str:
    """Render ``result`` in ``fmt``."""
    return CheckFormat(fmt).renderer()(result, options)
