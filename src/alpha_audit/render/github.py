"""GitHub Actions workflow commands: annotations on the offending files, within GitHub's limits.

``::error file=...,title=...::message`` lines, which the Actions runner turns
into annotations on the pull request's diff.  Values are escaped as the
runner expects (``%``, CR and LF everywhere; also ``:`` and ``,`` in
properties), so a hostile icon name cannot start a command of its own.
"""

from __future__ import annotations

from pathlib import Path

from alpha_audit.findings import Finding
from alpha_audit.render.common import RenderOptions, display_path
from alpha_audit.results import CheckReport
from alpha_audit.rules import RULES, Rule
from alpha_audit.safe_text import safe_text

__all__ = ["MAX_ANNOTATIONS", "escape_data", "escape_property", "render_report"]


def escape_data(text: str) -> str:
    """Escape a workflow-command message.

    >>> escape_data("50%\\nnext")
    '50%25%0Anext'
    """
    text = safe_text(text, newlines=True)  # ESC, C1, bidi: escaped before the runner sees them
    return text.replace("%", "%25").replace("\r", "%0D").replace("\n", "%0A")


def escape_property(text: str) -> str:
    """Escape a workflow-command property value (``file=``, ``title=``)."""
    return escape_data(text).replace(":", "%3A").replace(",", "%2C")


def _command(level: str, message: str, *, file: str | None, line: int | None, title: str) -> str:
    props = []
    if file:
        props.append(f"file={escape_property(file)}")
        if line:
            props.append(f"line={line}")
    props.append(f"title={escape_property(title)}")
    return f"::{level} {','.join(props)}::{escape_data(message)}"


def _annotation(f: Finding, base: Path | None) -> str:
    manifest = display_path(f.manifest, base)
    where = f"{', '.join(f.icons)} on {f.canvas}" if f.canvas else ", ".join(f.icons)
    message = f"{where} ({f.theme}): {f.message}"
    if manifest and f.lines:
        message += f" [colour/alpha set in {manifest} line {', '.join(map(str, f.lines))}]"
    if f.sources:
        shown = ", ".join(f"{display_path(p, base)} line {n}" for p, n in f.sources)
        message += f" [colour set by tokens in {shown}]"
    file = display_path(f.files[0], base) if f.files else manifest
    line = None if f.files else (f.lines[0] if f.lines else None)
    if f.sources:  # the annotation goes where the colour is set
        file, line = display_path(f.sources[0][0], base), f.sources[0][1]
    return _command("error", message, file=file, line=line, title=f"alpha-audit {f.rule.value}")


# GitHub shows at most 10 error and 10 warning annotations per step and drops
# the rest without a word (actions/toolkit#734; GitHub Docs, "Workflow commands
# for GitHub Actions", annotation limits).  One of each is kept for the roll-up.
MAX_ANNOTATIONS = 10


def _capped(level: str, annotations: list[str], rollup: str) -> list[str]:
    """At most MAX_ANNOTATIONS lines of ``level``: the first, then ``rollup`` naming the rest."""
    if len(annotations) <= MAX_ANNOTATIONS:
        return annotations
    kept = MAX_ANNOTATIONS - 1
    left_out = len(annotations) - kept
    message = rollup.format(n=left_out)
    return [
        *annotations[:kept],
        _command(level, message, file=None, line=None, title="alpha-audit"),
    ]


def render_report(report: CheckReport, options: RenderOptions) -> str:
    """Annotations GitHub displays: failures and warnings each capped at 10, with a roll-up.

    Up to 9 failing findings (10 when they fit) are annotated on their files;
    the last error line is the verdict, naming how many findings were left out
    (the job summary, written from ``--format markdown``, lists them all).
    Warnings for unrenderable icons are capped the same way.
    """
    gate = report.gate
    errors = [_annotation(f, options.base) for f in gate.failures]
    warnings = [
        _command(
            "warning" if w.rule is Rule.UNRENDERABLE else "notice",
            f"{', '.join(w.icons)}: {w.message}",
            file=display_path(w.files[0], options.base) if w.files else None,
            line=None,
            title=f"alpha-audit {w.rule.value}: {RULES[w.rule].help}",
        )
        for w in gate.warnings
    ]
    lines: list[str] = []
    if gate.passed:
        summary = f"gate passed ({len(report.audits)} audit(s))"
        lines.append(_command("notice", summary, file=None, line=None, title="alpha-audit"))
    else:
        counts = ", ".join(f"{n} {rule}" for rule, n in gate.counts().items())
        # The verdict is an error line too: the findings get the other nine.
        shown = errors if len(errors) < MAX_ANNOTATIONS else errors[: MAX_ANNOTATIONS - 1]
        verdict = f"gate failed: {counts}"
        if len(shown) < len(errors):
            verdict += (
                f"; {len(errors) - len(shown)} more finding(s) not annotated "
                "(GitHub shows 10 per step): see the job summary, and the JSON or SARIF "
                "report for every finding"
            )
        lines += shown
        lines.append(_command("error", verdict, file=None, line=None, title="alpha-audit"))
    lines = (
        _capped(
            "warning",
            warnings,
            "{n} more note(s): icons that could not be rendered or hard-coded paints "
            "(GitHub shows 10 per step): see the job summary",
        )
        + lines
    )
    return "\n".join(lines) + "\n"
