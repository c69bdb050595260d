"""Renderers: pure functions from a result to text, chosen by a format enum.

Every result type has the same frame: a :class:`Format` enum of its formats
whose :meth:`Format.renderer` returns one typed
:class:`~alpha_audit.render.common.Renderer` (its module imported on first
use), so a new format is one module, one member and one case.  The result
types and their enums:

- ``CheckReport``: table, json, junit, sarif, markdown, github, gitlab, html
  (:class:`CheckFormat`);
- ``SuggestResult``: table, json, markdown (:class:`SuggestFormat`);
- ``PairReport``: table, json (:class:`PairFormat`);
- ``Reproduction``: table, json, markdown
  (:class:`~alpha_audit.reproduce.formats.ReproduceFormat`, beside the paper's
  renderers: the core never imports the paper);
- bundled themes: table, json (:class:`ThemesFormat`).

``check`` and ``render`` both produce a ``CheckReport`` (``render``'s rows are
drawn by a browser, :mod:`alpha_audit.render.pages` gives their page views),
so one enum serves both commands.

Shared helpers (escaping, JSON, text, fix wording) live once in
:mod:`alpha_audit.render.common`.  A renderer never probes its destination (no
``isatty``, no clock) and its output order is stable.
"""

from __future__ import annotations

from enum import StrEnum
from typing import TYPE_CHECKING, Any, assert_never

from alpha_audit.render.common import SUFFIXES, Renderer, RenderOptions, display_path

if TYPE_CHECKING:
    from alpha_audit.pair import PairReport
    from alpha_audit.render.themes import Themes
    from alpha_audit.results import CheckReport, SuggestResult

__all__ = [
    "SUFFIXES",
    "CheckFormat",
    "Format",
    "PairFormat",
    "RenderOptions",
    "Renderer",
    "SuggestFormat",
    "ThemesFormat",
    "display_path",
    "render_check",
    "render_suggest",
]

# Each format's renderer() imports its module on first use (inside the method), so
# `alpha-audit --help` loads no renderer, and a new format is one member and one case.


class Format(StrEnum):
    """The formats of one result type; each enum's :meth:`renderer` returns its render function."""

    def renderer(self) -> Renderer[Any]:
        """The render function for this format (its module imported on first use)."""
        raise NotImplementedError(type(self).__name__)


class CheckFormat(Format):
    """Output formats of ``alpha-audit check`` and ``alpha-audit render``."""

    TABLE = "table"
    JSON = "json"
    JUNIT = "junit"
    SARIF = "sarif"
    MARKDOWN = "markdown"
    GITHUB = "github"
    GITLAB = "gitlab"
    HTML = "html"

    def renderer(self) -> Renderer[CheckReport]:
        """The render function for this format (its module imported on first use)."""
        match self:
            case CheckFormat.TABLE:
                from alpha_audit.render.table import render_report
            case CheckFormat.JSON:
                from alpha_audit.render.json import render_report
            case CheckFormat.JUNIT:
                from alpha_audit.render.junit import render_report
            case CheckFormat.SARIF:
                from alpha_audit.render.sarif import render_report
            case CheckFormat.MARKDOWN:
                from alpha_audit.render.markdown import render_report
            case CheckFormat.GITHUB:
                from alpha_audit.render.github import render_report
            case CheckFormat.GITLAB:
                from alpha_audit.render.gitlab import render_report
            case CheckFormat.HTML:
                from alpha_audit.render.html import render_report
            case _:
                assert_never(self)
        return render_report


class SuggestFormat(Format):
    """Output formats of ``alpha-audit suggest``."""

    TABLE = "table"
    JSON = "json"
    MARKDOWN = "markdown"

    def renderer(self) -> Renderer[SuggestResult]:
        """The render function for this format (its module imported on first use)."""
        from alpha_audit.render import suggest

        return {
            SuggestFormat.TABLE: suggest.render_table,
            SuggestFormat.JSON: suggest.render_json,
            SuggestFormat.MARKDOWN: suggest.render_markdown,
        }[self]


class PairFormat(Format):
    """Output formats of ``alpha-audit pair``."""

    TABLE = "table"
    JSON = "json"

    def renderer(self) -> Renderer[PairReport]:
        """The render function for this format (its module imported on first use)."""
        from alpha_audit.render import pair

        return {PairFormat.TABLE: pair.render_table, PairFormat.JSON: pair.render_json}[self]


class ThemesFormat(Format):
    """Output formats of ``alpha-audit themes``."""

    TABLE = "table"
    JSON = "json"

    def renderer(self) -> Renderer[Themes]:
        """The render function for this format (its module imported on first use)."""
        from alpha_audit.render import themes

        return {ThemesFormat.TABLE: themes.render_table, ThemesFormat.JSON: themes.render_json}[
            self
        ]


def render_check(report: CheckReport, fmt: CheckFormat | str, options: RenderOptions) -> str:
    """Render a gated report (:func:`alpha_audit.pipeline.check_project`) in ``fmt``."""
    return CheckFormat(fmt).renderer()(report, options)


def render_suggest(
    result: SuggestResult, fmt: SuggestFormat | str, options: RenderOptions | None = None
) -> str:
    """``result`` as text in ``fmt``."""
    return SuggestFormat(fmt).renderer()(result, options or RenderOptions())
