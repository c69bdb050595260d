"""Renderers: pure functions from a result to text, chosen by a format enum.

Every result type has the same frame: a :class:`Format` enum of its formats
whose :meth:`Format.renderer` loads one
:class:`~alpha_audit.render.common.Renderer` from :data:`RENDERERS`, so a new
format is one module and one line.  The result types and their enums:

=================  ===================================================  ========================
result             formats                                              enum
=================  ===================================================  ========================
``CheckReport``    table, json, junit, sarif, markdown, github, gitlab,  :class:`CheckFormat`
                   html
``SuggestResult``  table, json, markdown                                :class:`SuggestFormat`
``PairReport``     table, json                                          :class:`PairFormat`
``Reproduction``   table, json, markdown                                :class:`ReproduceFormat`
bundled themes     table, json                                          :class:`ThemesFormat`
=================  ===================================================  ========================

``check`` and ``render`` both produce a ``CheckReport`` (``render``'s rows are
drawn by a browser, :mod:`alpha_audit.render.pages` gives their page views),
so one enum serves both commands.

Shared helpers (escaping, JSON, text, fix wording) live once in
:mod:`alpha_audit.render.common`.  A renderer never probes its destination (no
``isatty``, no clock) and its output order is stable.
"""

from __future__ import annotations

import importlib
from enum import StrEnum
from typing import TYPE_CHECKING, Any

from alpha_audit.render.common import SUFFIXES, Renderer, RenderOptions, display_path

if TYPE_CHECKING:
    from alpha_audit.results import CheckReport, SuggestResult

__all__ = [
    "RENDERERS",
    "SUFFIXES",
    "CheckFormat",
    "Format",
    "PairFormat",
    "RenderOptions",
    "Renderer",
    "ReproduceFormat",
    "SuggestFormat",
    "ThemesFormat",
    "display_path",
    "render_check",
    "render_suggest",
]


class Format(StrEnum):
    """The formats of one result type; each member names its renderer in :data:`RENDERERS`."""

    def renderer(self) -> Renderer[Any]:
        """The render function for this format (its module imported on first use)."""
        module, name = RENDERERS[type(self)][self.value].split(":")
        renderer: Renderer[Any] = getattr(importlib.import_module(module), name)
        return renderer


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


class SuggestFormat(Format):
    """Output formats of ``alpha-audit suggest``."""

    TABLE = "table"
    JSON = "json"
    MARKDOWN = "markdown"


class PairFormat(Format):
    """Output formats of ``alpha-audit pair``."""

    TABLE = "table"
    JSON = "json"


class ReproduceFormat(Format):
    """Output formats of ``alpha-audit reproduce`` (``--out`` writes JSON and Markdown)."""

    TABLE = "table"
    JSON = "json"
    MARKDOWN = "markdown"


class ThemesFormat(Format):
    """Output formats of ``alpha-audit themes``."""

    TABLE = "table"
    JSON = "json"


# Every format of every result type: "module:function" (a test loads each one).  Keyed by
# class first: the members are strings, so CheckFormat.TABLE == ThemesFormat.TABLE.
RENDERERS: dict[type[Format], dict[str, str]] = {
    CheckFormat: {
        "table": "alpha_audit.render.table:render_report",
        "json": "alpha_audit.render.json:render_report",
        "junit": "alpha_audit.render.junit:render_report",
        "sarif": "alpha_audit.render.sarif:render_report",
        "markdown": "alpha_audit.render.markdown:render_report",
        "github": "alpha_audit.render.github:render_report",
        "gitlab": "alpha_audit.render.gitlab:render_report",
        "html": "alpha_audit.render.html:render_report",
    },
    SuggestFormat: {
        "table": "alpha_audit.render.suggest:render_table",
        "json": "alpha_audit.render.suggest:render_json",
        "markdown": "alpha_audit.render.suggest:render_markdown",
    },
    PairFormat: {
        "table": "alpha_audit.render.pair:render_table",
        "json": "alpha_audit.render.pair:render_json",
    },
    ReproduceFormat: {
        "table": "alpha_audit.reproduce.report:render_table",
        "json": "alpha_audit.reproduce.report:render_json",
        "markdown": "alpha_audit.reproduce.report:render_markdown",
    },
    ThemesFormat: {
        "table": "alpha_audit.render.themes:render_table",
        "json": "alpha_audit.render.themes:render_json",
    },
}


def render_check(report: CheckReport, fmt: CheckFormat | str, options: RenderOptions) -> str:
    """Render a gated report (:func:`alpha_audit.pipeline.check_project`) in ``fmt``."""
    return CheckFormat(fmt).renderer()(report, options)


def render_suggest(
    result: SuggestResult, fmt: SuggestFormat | str, options: RenderOptions | None = None
) -> str:
    """``result`` as text in ``fmt``."""
    return SuggestFormat(fmt).renderer()(result, options or RenderOptions())
