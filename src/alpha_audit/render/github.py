"""GitHub Actions workflow commands: an annotation on each offending icon file.

``::error file=...,title=...::message`` lines, which the Actions runner turns
into annotations on the pull request's diff.  Values are escaped as the
runner expects (``%``, CR and LF everywhere; also ``:`` and ``,`` in
properties), so a hostile icon name cannot start a command of its own.
"""

from __future__ import annotations

from pathlib import Path

from alpha_audit.gate import CheckReport, Finding
from alpha_audit.render.common import RenderOptions, display_path
from alpha_audit.safe_text import safe_text

__all__ = ["escape_data", "escape_property", "render_report"]


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
    file = display_path(f.files[0], base) if f.files else manifest
    line = None if f.files else (f.lines[0] if f.lines else None)
    return _command("error", message, file=file, line=line, title=f"alpha-audit {f.rule.value}")


def render_report(report: CheckReport, options: RenderOptions) -> str:
    """One annotation per failing finding, warnings for unrenderable icons, a summary notice."""
    gate = report.gate
    lines = [_annotation(f, options.base) for f in gate.failures]
    for w in gate.warnings:
        lines.append(
            _command(
                "warning",
                f"{', '.join(w.icons)}: {w.message}",
                file=display_path(w.files[0], options.base) if w.files else None,
                line=None,
                title="alpha-audit could not render this icon",
            )
        )
    if gate.passed:
        summary = f"gate passed ({len(report.audits)} audit(s))"
        lines.append(_command("notice", summary, file=None, line=None, title="alpha-audit"))
    else:
        counts = ", ".join(f"{n} {rule}" for rule, n in gate.counts().items())
        lines.append(
            _command("error", f"gate failed: {counts}", file=None, line=None, title="alpha-audit")
        )
    return "\n".join(lines) + "\n"
