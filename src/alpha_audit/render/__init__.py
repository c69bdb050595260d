"""Renderers: pure functions from a check report to text, chosen by name.

Each format lives in its own module with a ``render_report(report, options)``
function; :meth:`CheckFormat.renderer` is the registry the CLI reads.  A
renderer never probes its destination (no ``isatty``, no clock): everything it
may know is in :class:`RenderOptions`, and its output order is stable.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from enum import StrEnum
from pathlib import Path
from typing import assert_never

from alpha_audit.audit import AuditResult
from alpha_audit.gate import CheckReport, evaluate
from alpha_audit.policy import Policy

__all__ = ["CheckFormat", "RenderOptions", "as_report", "display_path", "render_check"]


@dataclass(frozen=True)
class RenderOptions:
    """What a renderer may know about its destination (never probed inside).

    ``base`` is the folder file paths are shown relative to (the working
    directory, usually the repository root in CI).
    """

    width: int = 100
    color: bool = False
    base: Path | None = None


class CheckFormat(StrEnum):
    """Output formats of ``alpha-audit check``."""

    TABLE = "table"
    JSON = "json"
    JUNIT = "junit"
    SARIF = "sarif"
    MARKDOWN = "markdown"
    GITHUB = "github"
    GITLAB = "gitlab"

    def renderer(self) -> Callable[[CheckReport, RenderOptions], str]:
        """The render function for this format."""
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


def as_report(result: AuditResult | CheckReport, policy: Policy | None = None) -> CheckReport:
    """A single audit wrapped as a report, gated by ``policy`` (default policy)."""
    if isinstance(result, CheckReport):
        return result
    return CheckReport(audits=(result,), gate=evaluate([result], policy or Policy()))


def render_check(
    result: AuditResult | CheckReport, fmt: CheckFormat | str, options: RenderOptions
) -> str:
    """Render a report (or one audit, gated by the default policy) in ``fmt``."""
    return CheckFormat(fmt).renderer()(as_report(result), options)


def display_path(path: Path | str | None, base: Path | None) -> str | None:
    """``path`` relative to ``base`` when inside it, in POSIX form; else as given."""
    if path is None:
        return None
    p = Path(path)
    if base is not None and p.is_absolute():
        try:
            return p.relative_to(base).as_posix()
        except ValueError:
            pass
    return p.as_posix()
