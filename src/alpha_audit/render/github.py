"""GitHub Actions workflow commands: annotations on the offending files, within GitHub's limits.

``::error file=...,title=...::message`` lines, which the Actions runner turns
into annotations on the pull request's diff.  Values are escaped as the
runner expects (``%``, CR and LF everywhere; also ``:`` and ``,`` in
properties), so a hostile icon name cannot start a command of its own.
"""

from __future__ import annotations

from pathlib import Path

from alpha_audit.gate import GateResult
from alpha_audit.render.common import RenderOptions, display_path, location_text
from alpha_audit.render.lines import LineGroup, by_line, group_message, group_where
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


def _command(
    level: str, message: str, *, file: str | None = None, line: int | None = None, title: str
) -> str:
    props = []
    if file:
        props.append(f"file={escape_property(file)}")
        if line:
            props.append(f"line={line}")
    props.append(f"title={escape_property(title)}")
    return f"::{level} {','.join(props)}::{escape_data(message)}"


def _annotation(g: LineGroup, base: Path | None) -> str:
    """One line's failing root causes of one rule, annotated on that line.

    That line (an ``alpha:`` or colour in the manifest, a design token, the
    config's ``alpha:``) is what a pull request changes, so GitHub shows the
    annotation inline in the diff, once however many icons it fails; an SVG
    alone (its drawing is the cause) gets its file.
    """
    f = g.worst
    message = group_message(g)
    related = []
    if not g.folded:  # the other places of one root cause (a group's differ by icon)
        related += [f"{loc.what} at {location_text(loc, base)}" for loc in f.locations[1:]]
        related += [f"SVG {display_path(p, base)}" for p in f.files[:3]]
    if related:
        message += f" [{'; '.join(related)}]"
    file = _file(g, base) or display_path(f.manifest, base)
    return _command("error", message, file=file, line=_line(g), title=f"alpha-audit {g.rule.value}")


def _file(g: LineGroup, base: Path | None) -> str | None:
    """The file a group is annotated on: its line's, else its SVG's."""
    if g.location is not None:
        return display_path(g.location.file, base)
    return display_path(g.worst.files[0], base) if g.worst.files else None


def _line(g: LineGroup) -> int | None:
    return g.location.line if g.location is not None else None


# GitHub shows at most 10 error and 10 warning annotations per step and drops
# the rest without a word (actions/toolkit#734; GitHub Docs, "Workflow commands
# for GitHub Actions", annotation limits).  One of each is kept for the roll-up.
MAX_ANNOTATIONS = 10


def _capped(level: str, annotations: list[str], rollup: str) -> list[str]:
    """At most MAX_ANNOTATIONS lines of ``level``: the first, then ``rollup`` naming the rest."""
    if len(annotations) <= MAX_ANNOTATIONS:
        return annotations
    kept = MAX_ANNOTATIONS - 1
    rolled = rollup.format(n=len(annotations) - kept)
    return [*annotations[:kept], _command(level, rolled, title="alpha-audit")]


def render_report(report: CheckReport, options: RenderOptions) -> str:
    """Annotations GitHub displays: failures and warnings each capped at 10, with a roll-up.

    Failing root causes are folded by the line that sets them (one annotation per
    line and rule, with the icon and canvas counts and the worst case); up to 9
    lines, worst first (10 when they fit), are annotated; the last error line is
    the verdict, naming how many were left out (the job summary, written from
    ``--format markdown``, lists them).
    Warnings for unrenderable icons are capped the same way.
    """
    counted = (
        f"{report.pages.audited} page state(s)"
        if report.pages is not None
        else f"{len(report.audits)} audit(s)"
    )
    return gate_annotations(report.gate, options, f"gate passed ({counted})")


def gate_annotations(gate: GateResult, options: RenderOptions, passed: str) -> str:
    """The annotations of ``gate`` (:func:`render_report`); ``passed`` is the passing verdict.

    Root causes are folded by the line that sets their failing value
    (:func:`~alpha_audit.render.lines.by_line`): one annotation per line and rule.
    """
    failing = by_line(gate.failures)
    errors = [_annotation(g, options.base) for g in failing]
    warnings = [
        _command(
            "warning" if g.rule is Rule.UNRENDERABLE else "notice",
            f"{group_where(g)}: {g.worst.message}",
            file=_file(g, options.base),
            line=_line(g),
            title=f"alpha-audit {g.rule.value}: {RULES[g.rule].help}",
        )
        # A loss reported but not gated (an invisible paint, a sub-tolerance loss) is
        # in the JSON and SARIF reports; an annotation slot is for what needs a look.
        for g in by_line(w for w in gate.warnings if not w.quiet)
    ]
    lines: list[str] = []
    if gate.passed:
        lines.append(_command("notice", passed, title="alpha-audit"))
    else:
        counts = gate.counts_text()
        # The verdict is an error line too: the findings get the other nine.
        shown = errors if len(errors) < MAX_ANNOTATIONS else errors[: MAX_ANNOTATIONS - 1]
        verdict = (
            f"gate failed: {len(gate.failures)} root cause(s) on {len(errors)} line(s): {counts}"
        )
        if len(shown) < len(errors):
            verdict += (
                f"; {len(errors) - len(shown)} more line(s) not annotated "
                "(GitHub shows 10 per step): see the job summary, and the JSON or SARIF "
                "report for every finding"
            )
        lines += shown
        lines.append(_command("error", verdict, title="alpha-audit"))
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
