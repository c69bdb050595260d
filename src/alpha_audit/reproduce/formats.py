"""The output formats of ``alpha-audit reproduce``, beside the paper's renderers.

It lives here, not in :mod:`alpha_audit.render`, because the core never
imports the paper (the layers in ``pyproject.toml``).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, assert_never

from alpha_audit.render import Format

if TYPE_CHECKING:
    from alpha_audit.render.common import Renderer
    from alpha_audit.reproduce.run import Reproduction

__all__ = ["ReproduceFormat"]


class ReproduceFormat(Format):
    """Output formats of ``alpha-audit reproduce`` (``--out`` writes JSON and Markdown)."""

    TABLE = "table"
    JSON = "json"
    MARKDOWN = "markdown"

    def renderer(self) -> Renderer[Reproduction]:
        """The render function for this format (the report module imported on first use)."""
        from alpha_audit.reproduce import report

        if self is ReproduceFormat.TABLE:
            return report.render_table
        if self is ReproduceFormat.JSON:
            return report.reproduction_json
        if self is ReproduceFormat.MARKDOWN:
            return report.reproduction_markdown
        assert_never(self)
