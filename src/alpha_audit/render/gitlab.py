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
colour a change edits), so the issue lands on the diff; root causes that share
that line and rule are one issue (:func:`~alpha_audit.render.lines.by_line`:
a set-wide ``alpha:`` failing every icon is one entry, with the icon and canvas
counts and the worst case), fingerprinted by the line's file and kind of value,
its audits and its icons.

Only what fails the gate is an issue: exempted and baselined findings are
decisions already taken, and Code Quality has no "dismissed" state.  The
gate's warnings (reported rules: icons that could not be rendered, hard-coded
paints) are ``info`` issues.  The description ends with the finding's fix.
"""

from __future__ import annotations

from pathlib import Path, PurePosixPath
from typing import Any

from alpha_audit.render.common import RenderOptions, digest, display_path, dumps
from alpha_audit.render.lines import LineGroup, by_line, group_fix, group_message
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


def _where(g: LineGroup, base: Path | None) -> tuple[str, int]:
    """The line that sets the failing value (:attr:`Finding.locations`), else the SVG's first."""
    f = g.worst
    if g.location is not None:
        return _relative(g.location.file, base), g.location.line
    if f.manifest is not None and f.lines:
        return _relative(f.manifest, base), f.lines[0]
    if f.files:
        return _relative(f.files[0], base), 1
    return _relative(f.manifest, base), 1


def render_report(report: CheckReport, options: RenderOptions) -> str:
    """Every failing line (root causes folded by the line and rule) as one GitLab issue.

    In the gate's order, then the gate's warnings as ``info`` issues, folded alike.
    """
    entries: list[tuple[LineGroup, str]] = [
        (g, RULES[g.rule].severity) for g in by_line(report.gate.failures)
    ]
    entries += [(g, "info") for g in by_line(report.gate.warnings)]
    issues: list[dict[str, Any]] = []
    seen: set[str] = set()
    for g, severity in entries:
        identity = g.fingerprint(options.base)
        fingerprint, n = identity, 1
        while fingerprint in seen:  # an icon unrenderable in two themes, say
            n += 1
            fingerprint = digest(f"{identity}\x1e{n}")
        seen.add(fingerprint)
        path, line = _where(g, options.base)
        fix = group_fix(g, report)
        issues.append(
            {
                "type": "issue",
                "description": f"{group_message(g)}. Fix: {fix}.",
                "check_name": _CHECK_PREFIX + g.rule.value,
                "fingerprint": fingerprint,
                "severity": severity,
                "location": {"path": path, "lines": {"begin": max(1, line)}},
            }
        )
    return dumps(issues)
