"""SARIF 2.1.0 for code-scanning dashboards (GitHub, GitLab, Azure DevOps).

Each finding is a result pointing first at the line of each design token
that sets a colour of the finding (icon colour, then canvas), then at the
manifest line that sets the icon's colour or alpha (where the fix goes), then
at the icon's SVG file (line 1: a drawing has no better line).  URIs are
relative to ``%SRCROOT%`` and percent-encoded (RFC 3986); no absolute path
of the machine appears.  Rule ids are opaque (``AA001`` ...), names
readable, and each rule has ``help.markdown``.
Exempted and baselined findings stay in the log with a ``suppressions`` entry
(so dashboards show them as dismissed, with the reason), and every result has a
``partialFingerprints`` entry built from what a baseline matches on (theme,
icon set, rule, canvas, icons), never from line numbers.
"""

from __future__ import annotations

import hashlib
import os
from pathlib import Path
from typing import Any
from urllib.parse import quote

from alpha_audit.gate import CheckReport, Finding
from alpha_audit.policy import Rule
from alpha_audit.render.common import RenderOptions, dumps
from alpha_audit.render.rules import RULE_FIX, RULE_HELP, RULE_IDS

__all__ = [
    "SARIF_SCHEMA",
    "SRCROOT",
    "relative_uri",
    "render_report",
]

SARIF_SCHEMA = "https://json.schemastore.org/sarif-2.1.0.json"  # OASIS SARIF 2.1.0
# SARIF 2.1.0 3.14.14: a symbolic base for relative URIs, resolved by the
# consumer (the checkout); deliberately given no "uri", so the log carries no
# absolute path of the machine that wrote it.
SRCROOT = "%SRCROOT%"

# RFC 3986 section 3.3: pchar = unreserved / pct-encoded / sub-delims / ":" / "@".
# ":" is encoded too: in a relative reference's first segment it would read as a
# scheme (section 4.2).  Everything else (space, "#", "%", "?", controls,
# non-ASCII as UTF-8) is percent-encoded.
_URI_SAFE = "/!$&'()*+,;=@"


def relative_uri(path: Path | str, base: Path | None) -> str:
    """``path`` as an RFC 3986 relative reference (POSIX, percent-encoded), never absolute.

    Inside ``base``: relative to it.  Outside it (or with no base): relative
    with ``..`` when there is a base, else the file name alone.

    >>> relative_uri("/repo/icons/a #1%.svg", Path("/repo"))
    'icons/a%20%231%25.svg'
    """
    p = Path(path)
    if p.is_absolute():
        text = Path(os.path.relpath(p, base)).as_posix() if base is not None else p.name
    else:
        text = p.as_posix()
    return quote(text, safe=_URI_SAFE)


def _location(path: Path | None, base: Path | None, line: int | None = None) -> dict[str, Any]:
    """A physical location with a region: the given line, else line 1 of the file."""
    artifact: dict[str, Any] = {"uri": relative_uri(path or "", base), "uriBaseId": SRCROOT}
    region = {"startLine": line or 1}
    return {"physicalLocation": {"artifactLocation": artifact, "region": region}}


def _fingerprint(f: Finding) -> str:
    theme, iconset, rule, canvas, icons = f.key
    text = "\x1f".join([theme, iconset, rule, canvas or "", *icons])
    return hashlib.sha256(text.encode("utf-8")).hexdigest()[:32]


def _result(
    f: Finding, index: int, base: Path | None, level: str = "error", fix: str | None = None
) -> dict[str, Any]:
    where = f"{', '.join(f.icons)} on {f.canvas}" if f.canvas else ", ".join(f.icons)
    locations = [_location(p, base) for p in f.files]
    if f.manifest is not None:
        # The manifest lines that set the colour or alpha come first: that is
        # where a fix goes (the SVG file is line 1 of the drawing).
        locations = [_location(f.manifest, base, line) for line in f.lines] + locations
    # A colour set by a design token is fixed at the token's line, before all else.
    locations = [_location(path, base, line) for path, line in f.sources] + locations
    result: dict[str, Any] = {
        "ruleId": RULE_IDS[f.rule],
        "ruleIndex": index,
        "level": level,
        "message": {
            "text": f"{where} ({f.theme} / {f.iconset}): {f.message}"
            + (f". Fix: {fix}" if fix else "")
        },
        "locations": locations or ([_location(f.manifest, base)] if f.manifest else []),
        "partialFingerprints": {"alphaAuditFinding/v1": _fingerprint(f)},
        "properties": {
            "theme": f.theme,
            "iconset": f.iconset,
            "canvas": f.canvas,
            "icons": list(f.icons),
            **dict(f.numbers),
        },
    }
    if f.exemption is not None:
        result["suppressions"] = [{"kind": "external", "justification": f.exemption.reason}]
    elif f.baselined:
        result["suppressions"] = [{"kind": "external", "justification": "in the baseline"}]
    return result


def _rule(rule: Rule, enabled: bool) -> dict[str, Any]:
    """A reportingDescriptor: opaque id, readable name, what it means and how to fix it."""
    help_text = f"{RULE_HELP[rule]} {RULE_FIX[rule]}"
    return {
        "id": RULE_IDS[rule],
        "name": rule.name.title().replace("_", ""),
        "shortDescription": {"text": RULE_HELP[rule]},
        "help": {
            "text": help_text.replace("`", ""),
            "markdown": f"**{rule.value}**: {RULE_HELP[rule]}\n\n**Fix:** {RULE_FIX[rule]}",
        },
        "defaultConfiguration": {"level": "error" if enabled else "none"},
        "properties": {"alphaAuditRule": rule.value},
    }


def render_report(report: CheckReport, options: RenderOptions) -> str:
    """The report as one SARIF 2.1.0 run."""
    from alpha_audit import __version__

    rules = list(Rule)
    index = {r: i for i, r in enumerate(rules)}
    enabled = report.gate.policy.rules
    # Each failure's message ends with its fix, in the PR comment's words.
    from alpha_audit.render.markdown import report_fixes_hook

    failing = {id(f) for f in report.gate.failures}  # findings hold dicts: by identity
    hook = report_fixes_hook(report) if failing else None
    results = [
        _result(f, index[f.rule], options.base, fix=hook(f) if hook and id(f) in failing else None)
        for f in report.gate.findings
    ]
    if Rule.UNRENDERABLE not in enabled:
        for audit in report.audits:
            for p in audit.problems:
                f = Finding(
                    Rule.UNRENDERABLE,
                    audit.theme.name,
                    audit.iconset.name,
                    None,
                    (p.icon,),
                    p.message,
                    files=(Path(p.file),),
                )
                results.append(_result(f, index[Rule.UNRENDERABLE], options.base, "warning"))
    run: dict[str, Any] = {
        "tool": {
            "driver": {
                "name": "alpha-audit",
                "version": __version__,
                "informationUri": "https://github.com/alpha-audit/alpha-audit",
                "rules": [_rule(r, r in enabled) for r in rules],
            }
        },
        "results": results,
    }
    run["originalUriBaseIds"] = {
        SRCROOT: {"description": {"text": "The folder alpha-audit ran in (the repository root)."}}
    }
    return dumps({"$schema": SARIF_SCHEMA, "version": "2.1.0", "runs": [run]})
