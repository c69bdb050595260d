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

__all__ = [
    "RULE_FIX",
    "RULE_HELP",
    "RULE_IDS",
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

# Rule ids are opaque and stable (SARIF 3.49.3: "ruleId" should not be the
# readable name, which lives in "name").  Never renumber: dashboards key on these.
RULE_IDS: dict[Rule, str] = {
    Rule.LOSS: "AA001",
    Rule.BELOW_THRESHOLD: "AA002",
    Rule.NEWLY_FAILING: "AA003",
    Rule.COLLISION: "AA004",
    Rule.NEW_COLLISION: "AA005",
    Rule.SEPARATION: "AA006",
    Rule.UNRENDERABLE: "AA007",
    Rule.FIXED_COLOUR: "AA008",
    Rule.NOT_AUDITED: "AA009",
    Rule.DRIFT: "AA010",
    Rule.LOCK: "AA011",
    Rule.CONFUSION: "AA012",
    Rule.THIN_STROKES: "AA013",
    Rule.CVD_COLLISION: "AA014",
    Rule.CVD_CONFUSION: "AA015",
}

RULE_HELP: dict[Rule, str] = {
    Rule.LOSS: "The icon's WCAG contrast on this canvas is lower at its alpha than at alpha 1.",
    Rule.BELOW_THRESHOLD: "The icon is below the contrast threshold on this canvas at its alpha.",
    Rule.NEWLY_FAILING: "The icon meets the threshold at alpha 1 but not at its alpha.",
    Rule.COLLISION: "Distinct source colours give the same 8-bit output on this canvas.",
    Rule.NEW_COLLISION: "Distinct colours collide at their alpha but not at alpha 1.",
    Rule.SEPARATION: "Two of the set's colours are closer than the minimum CIEDE2000.",
    Rule.UNRENDERABLE: "The icon's SVG could not be rendered.",
    Rule.FIXED_COLOUR: "The SVG hard-codes a paint colour that will not follow the theme.",
    Rule.NOT_AUDITED: "The SVG draws something the audit cannot judge (gradient, text, image).",
    Rule.DRIFT: "The paint's colour moves further than max-drift (CIEDE2000) at its alpha.",
    Rule.LOCK: "A locked brand colour changes by more than one just-noticeable difference.",
    Rule.CONFUSION: "Two palette roles told apart at alpha 1 are no longer told apart.",
    Rule.THIN_STROKES: "At a raster size the antialiased paint falls below min-size-contrast.",
    Rule.CVD_COLLISION: "Distinct colours newly look identical under simulated colour blindness.",
    Rule.CVD_CONFUSION: "Two roles are no longer told apart under simulated colour blindness.",
}

# What to do about each rule (help.markdown, shown by code-scanning dashboards).
RULE_FIX: dict[Rule, str] = {
    Rule.LOSS: (
        "Lower the icon's `alpha` (run `alpha-audit suggest` for the largest safe value "
        "per colour), or exempt the canvas with a reason."
    ),
    Rule.BELOW_THRESHOLD: (
        "Raise the icon's `alpha` above 1 where that helps, or pick a source colour "
        "with more contrast on this canvas."
    ),
    Rule.NEWLY_FAILING: (
        "Lower the icon's `alpha` back towards 1 (`alpha-audit suggest` gives the "
        "largest value that still passes)."
    ),
    Rule.COLLISION: "Move one of the colliding colours apart, or lower the set's `alpha`.",
    Rule.NEW_COLLISION: (
        "Lower the set's `alpha` below the value `alpha-audit suggest` reports, or move "
        "one of the colours apart."
    ),
    Rule.SEPARATION: (
        "Move the two closest colours apart, or lower the `alpha` that pulls them together."
    ),
    Rule.UNRENDERABLE: "Fix the SVG file (the message names the problem) or remove the icon.",
    Rule.FIXED_COLOUR: (
        "Paint with `currentColor` (or a theme token) instead of the fixed colour, or "
        "exempt the icon with a reason if the colour is meant to stay."
    ),
    Rule.NOT_AUDITED: (
        "Audit the element by hand, or draw it with plain fills and strokes the audit can read."
    ),
    Rule.DRIFT: (
        "Lower the icon's `alpha` towards 1 (drift is zero at 1), or raise `max-drift` "
        "if the shift is acceptable."
    ),
    Rule.LOCK: "Keep locked brand colours at `alpha: 1`, or remove the lock.",
    Rule.CONFUSION: (
        "Lower the `alpha` that pulls the two roles together, or move one role's colour "
        "further from the other."
    ),
    Rule.THIN_STROKES: (
        "Use a heavier stroke or a larger size, or a source colour with more contrast."
    ),
    Rule.CVD_COLLISION: "Move the two colours apart in lightness, not only in hue.",
    Rule.CVD_CONFUSION: (
        "Separate the two roles in lightness (CVD keeps lightness), or lower the `alpha`."
    ),
}

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


def _result(f: Finding, index: int, base: Path | None, level: str = "error") -> dict[str, Any]:
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
        "message": {"text": f"{where} ({f.theme} / {f.iconset}): {f.message}"},
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
    results = [_result(f, index[f.rule], options.base) for f in report.gate.findings]
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
