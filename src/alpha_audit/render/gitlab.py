"""GitLab Code Quality (``-f gitlab``): a JSON array for ``artifacts:reports:codequality``.

GitLab reads a subset of the Code Climate issue spec
(https://docs.gitlab.com/ci/testing/code_quality/, "Code Quality report
format"): ``description``, ``check_name``, ``fingerprint``, ``severity`` (one
of info, minor, major, critical, blocker), ``location.path`` (relative to the
repository root) and ``location.lines.begin``.  GitLab shows issues with the
same fingerprint as one, and compares fingerprints between the merge request
and its target branch to say what is new, so a fingerprint is built from what
a baseline matches on (theme, icon set, rule, icons: one root cause, whatever
its canvases) -- never a line number -- and made unique within the report.
``location`` is the line that sets the failing value (the ``alpha:`` or
colour a change edits), so the issue lands on the diff.

Only what fails the gate is an issue: exempted and baselined findings are
decisions already taken, and Code Quality has no "dismissed" state.  The
gate's warnings (reported rules: icons that could not be rendered, hard-coded
paints) are ``info`` issues.  The description ends with the finding's fix.
"""

from __future__ import annotations

from pathlib import Path, PurePosixPath
from typing import Any

from alpha_audit.findings import Finding
from alpha_audit.render.common import (
    RenderOptions,
    digest,
    display_path,
    dumps,
    finding_fix,
    where_text,
)
from alpha_audit.results import CheckReport
from alpha_audit.rules import RULES

__all__ = ["render_report"]

_CHECK_PREFIX = "alpha-audit/"  # namespaced: several tools share one Code Quality widget


def _relative(path: Path | None, base: Path | None) -> str:
    """A repository-relative POSIX path; never an absolute one (outside ``base``: the name)."""
    shown = display_path(path, base)
    if not shown:
        return "."
    posix = PurePosixPath(shown)
    if posix.is_absolute() or Path(shown).is_absolute():
        return posix.name
    return shown


def _where(f: Finding, base: Path | None) -> tuple[str, int]:
    """The line that sets the failing value (:attr:`Finding.locations`), else the SVG's first."""
    if f.locations:
        return _relative(f.locations[0].file, base), f.locations[0].line
    if f.manifest is not None and f.lines:
        return _relative(f.manifest, base), f.lines[0]
    if f.files:
        return _relative(f.files[0], base), 1
    return _relative(f.manifest, base), 1


def render_report(report: CheckReport, options: RenderOptions) -> str:
    """Every failing finding as one GitLab Code Quality issue, in the gate's order."""
    entries: list[tuple[Finding, str]] = [(f, RULES[f.rule].severity) for f in report.gate.failures]
    entries += [(note, "info") for note in report.gate.warnings]
    issues: list[dict[str, Any]] = []
    seen: set[str] = set()
    for f, severity in entries:
        theme, iconset, rule, icons = f.key
        identity = "\x1f".join([theme, iconset, rule, *icons])
        fingerprint = digest(identity)
        n = 1
        while fingerprint in seen:  # an icon unrenderable in two themes, say
            n += 1
            fingerprint = digest(f"{identity}\x1e{n}")
        seen.add(fingerprint)
        path, line = _where(f, options.base)
        issues.append(
            {
                "type": "issue",
                "description": f"{where_text(f)} ({f.theme} / {f.iconset}): {f.message}. "
                f"Fix: {finding_fix(f, report)}.",
                "check_name": _CHECK_PREFIX + f.rule.value,
                "fingerprint": fingerprint,
                "severity": severity,
                "location": {"path": path, "lines": {"begin": max(1, line)}},
            }
        )
    return dumps(issues)
