"""GitHub Actions workflow commands: annotations on the offending files, within GitHub's limits.

``::error file=...,title=...::message`` lines, which the Actions runner turns
into annotations on the pull request's diff.  Values are escaped as the
runner expects (``%``, CR and LF everywhere; also ``:`` and ``,`` in
properties), so a hostile icon name cannot start a command of its own.
"""

from __future__ import annotations

from pathlib import Path

from alpha_audit.findings import Finding
from alpha_audit.gate import GateResult
from alpha_audit.render.common import RenderOptions, display_path, location_text, where_text
from alpha_audit.results import CheckReport
from alpha_audit.rules import RULES, Rule
from alpha_audit.safe_text import safe_text

__all__ = [
    "MAX_ANNOTATIONS",
    "escape_data",
    "escape_property",
    "gate_annotations",
    "render_report",
]


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
    """One failing root cause, annotated on the line that sets its failing value.

    That line (an ``alpha:`` or colour in the manifest, a design token, the
    config's ``alpha:``) is what a pull request changes, so GitHub shows the
    annotation inline in the diff; an SVG alone (its drawing is the cause)
    gets its file.
    """
    message = f"{where_text(f)} ({f.theme} / {f.iconset}): {f.message}"
    related = [f"{loc.what} at {location_text(loc, base)}" for loc in f.locations[1:]] + [
        f"SVG {display_path(p, base)}" for p in f.files[:3]
    ]
    if related:
        message += f" [{'; '.join(related)}]"
    file: str | None
    line: int | None
    if f.locations:
        file, line = display_path(f.locations[0].file, base), f.locations[0].line
    else:
        file = display_path(f.files[0], base) if f.files else display_path(f.manifest, base)
        line = None
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

    Up to 9 failing root causes, worst first (10 when they fit), are annotated
    on the lines that set them; the last error line is the verdict, naming how
    many were left out (the job summary, written from ``--format markdown``,
    lists them).
    Warnings for unrenderable icons are capped the same way.
    """
    counted = (
        f"{report.pages.audited} page state(s)"
        if report.pages is not None
        else f"{len(report.audits)} audit(s)"
    )
    return gate_annotations(report.gate, options, f"gate passed ({counted})")


def gate_annotations(gate: GateResult, options: RenderOptions, passed: str) -> str:
    """The annotations of ``gate`` (:func:`render_report`); ``passed`` is the passing verdict."""
    errors = [_annotation(f, options.base) for f in gate.failures]
    warnings = [
        _command(
            "warning" if w.rule is Rule.UNRENDERABLE else "notice",
            f"{where_text(w)}: {w.message}",
            file=display_path(w.locations[0].file if w.locations else w.files[0], options.base)
            if w.locations or w.files
            else None,
            line=w.locations[0].line if w.locations else None,
            title=f"alpha-audit {w.rule.value}: {RULES[w.rule].help}",
        )
        for w in gate.warnings
        # A loss reported but not gated (an invisible paint, a sub-tolerance loss) is
        # in the JSON and SARIF reports; an annotation slot is for what needs a look.
        if w.numbers.get("gated") != "false"
    ]
    lines: list[str] = []
    if gate.passed:
        lines.append(_command("notice", passed, file=None, line=None, title="alpha-audit"))
    else:
        counts = ", ".join(f"{n} {rule}" for rule, n in gate.counts().items())
        # The verdict is an error line too: the findings get the other nine.
        shown = errors if len(errors) < MAX_ANNOTATIONS else errors[: MAX_ANNOTATIONS - 1]
        verdict = f"gate failed: {len(errors)} root cause(s): {counts}"
        if len(shown) < len(errors):
            verdict += (
                f"; {len(errors) - len(shown)} more root cause(s) not annotated "
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
