"""Renderers: pure functions from a result to text, chosen by a format enum.

Every result type has the same frame: an enum of its formats whose
``renderer()`` returns one :class:`~alpha_audit.render.common.Renderer` per
format (dispatch ending in ``assert_never``), so a new format is one module and
one line.  The result types and their enums:

=================  ==========================================  =====================
result             formats                                     enum
=================  ==========================================  =====================
``CheckReport``    table, json, junit, sarif, markdown, github  :class:`CheckFormat`
``SuggestResult``  table, json, markdown                        ``SuggestFormat``
``PairReport``     table, json                                  ``PairFormat``
``Reproduction``   table, json, markdown                        ``ReproduceFormat``
=================  ==========================================  =====================

(:mod:`alpha_audit.suggest.report`, :mod:`alpha_audit.render.pair`,
:mod:`alpha_audit.reproduce.report`.)  Shared helpers (escaping, JSON, text)
live once in :mod:`alpha_audit.render.common`.  A renderer never probes its
destination (no ``isatty``, no clock) and its output order is stable.
"""

from __future__ import annotations

from enum import StrEnum
from typing import TYPE_CHECKING, assert_never

from alpha_audit.render.common import SUFFIXES, Renderer, RenderOptions, display_path

if TYPE_CHECKING:
    from alpha_audit.gate import CheckReport
    from alpha_audit.reproduce.run import Reproduction
    from alpha_audit.suggest.engine import SuggestResult

__all__ = [
    "SUFFIXES",
    "CheckFormat",
    "RenderOptions",
    "Renderer",
    "ReproduceFormat",
    "SuggestFormat",
    "display_path",
    "render_check",
    "render_suggest",
]


class CheckFormat(StrEnum):
    """Output formats of ``alpha-audit check``."""

    TABLE = "table"
    JSON = "json"
    JUNIT = "junit"
    SARIF = "sarif"
    MARKDOWN = "markdown"
    GITHUB = "github"
    GITLAB = "gitlab"

    def renderer(self) -> Renderer[CheckReport]:
        """The render function for this format (imported on first use)."""
        if self is CheckFormat.TABLE:
            from alpha_audit.render.table import render_report as table

            return table
        if self is CheckFormat.JSON:
            from alpha_audit.render.json import render_report as as_json

            return as_json
        if self is CheckFormat.JUNIT:
            from alpha_audit.render.junit import render_report as junit

            return junit
        if self is CheckFormat.SARIF:
            from alpha_audit.render.sarif import render_report as sarif

            return sarif
        if self is CheckFormat.MARKDOWN:
            from alpha_audit.render.markdown import render_report as markdown

            return markdown
        if self is CheckFormat.GITHUB:
            from alpha_audit.render.github import render_report as github

            return github
        if self is CheckFormat.GITLAB:
            from alpha_audit.render.gitlab import render_report as gitlab

            return gitlab
        assert_never(self)


class SuggestFormat(StrEnum):
    """Output formats of ``alpha-audit suggest``."""

    TABLE = "table"
    JSON = "json"
    MARKDOWN = "markdown"

    def renderer(self) -> Renderer[SuggestResult]:
        """The render function for this format (:mod:`alpha_audit.suggest.report`)."""
        from alpha_audit.suggest import report

        if self is SuggestFormat.TABLE:
            return report.render_table
        if self is SuggestFormat.JSON:
            return report.render_json
        if self is SuggestFormat.MARKDOWN:
            return report.render_markdown
        assert_never(self)


class ReproduceFormat(StrEnum):
    """Output formats of ``alpha-audit reproduce`` (``--out`` writes JSON and Markdown)."""

    TABLE = "table"
    JSON = "json"
    MARKDOWN = "markdown"

    def renderer(self) -> Renderer[Reproduction]:
        """The render function for this format (:mod:`alpha_audit.reproduce.report`)."""
        from alpha_audit.reproduce import report

        if self is ReproduceFormat.TABLE:
            return report.render_table
        if self is ReproduceFormat.JSON:
            return report.render_json
        if self is ReproduceFormat.MARKDOWN:
            return report.render_markdown
        assert_never(self)


def render_check(report: CheckReport, fmt: CheckFormat | str, options: RenderOptions) -> str:
    """Render a gated report in ``fmt``.

    An :class:`~alpha_audit.audit.AuditResult` alone has no verdict: gate it
    with :func:`alpha_audit.gate.evaluate` and the policy you mean, and wrap
    it in a :class:`~alpha_audit.gate.CheckReport` (or use
    :func:`alpha_audit.pipeline.check_project`).
    """
    return CheckFormat(fmt).renderer()(report, options)


def render_suggest(
    result: SuggestResult, fmt: SuggestFormat | str, options: RenderOptions | None = None
) -> str:
    """``result`` as text in ``fmt``."""
    return SuggestFormat(fmt).renderer()(result, options or RenderOptions())
