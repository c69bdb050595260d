"""SARIF 2.1.0 for code-scanning dashboards (GitHub, GitLab, Azure DevOps).

Each finding is a result pointing at the icon's SVG file and, where the
manifest sets the icon's colour or alpha on a known line, at that line too.
Exempted and baselined findings stay in the log with a ``suppressions`` entry
(so dashboards show them as dismissed, with the reason), and every result has a
``partialFingerprints`` entry built from what a baseline matches on (theme,
icon set, rule, canvas, icons), never from line numbers.
"""

from __future__ import annotations

import hashlib
from pathlib import Path
from typing import Any

from alpha_audit.gate import CheckReport, Finding
from alpha_audit.policy import Rule
from alpha_audit.render.common import RenderOptions, display_path, dumps

__all__ = ["RULE_HELP", "SARIF_SCHEMA", "render_report"]

SARIF_SCHEMA = "https://json.schemastore.org/sarif-2.1.0.json"  # OASIS SARIF 2.1.0
_SRCROOT = "SRCROOT"

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


def _location(path: Path | None, base: Path | None, line: int | None = None) -> dict[str, Any]:
    uri = display_path(path, base) or ""
    artifact: dict[str, Any] = {"uri": uri}
    if not Path(uri).is_absolute():
        artifact["uriBaseId"] = _SRCROOT
    physical: dict[str, Any] = {"artifactLocation": artifact}
    if line:
        physical["region"] = {"startLine": line}
    return {"physicalLocation": physical}


def _fingerprint(f: Finding) -> str:
    theme, iconset, rule, canvas, icons = f.key
    text = "\x1f".join([theme, iconset, rule, canvas or "", *icons])
    return hashlib.sha256(text.encode("utf-8")).hexdigest()[:32]


def _result(f: Finding, index: int, base: Path | None, level: str = "error") -> dict[str, Any]:
    where = f"{', '.join(f.icons)} on {f.canvas}" if f.canvas else ", ".join(f.icons)
    locations = [_location(p, base) for p in f.files]
    if f.manifest is not None:
        locations += [_location(f.manifest, base, line) for line in f.lines]
    result: dict[str, Any] = {
        "ruleId": f.rule.value,
        "ruleIndex": index,
        "level": level,
        "message": {"text": f"{where} ({f.theme} / {f.iconset}): {f.message}"},
        "locations": locations or [_location(f.manifest, base)],
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
                "rules": [
                    {
                        "id": r.value,
                        "name": r.name.title().replace("_", ""),
                        "shortDescription": {"text": RULE_HELP[r]},
                        "defaultConfiguration": {"level": "error" if r in enabled else "none"},
                    }
                    for r in rules
                ],
            }
        },
        "results": results,
    }
    if options.base is not None:
        run["originalUriBaseIds"] = {_SRCROOT: {"uri": options.base.as_uri() + "/"}}
    return dumps({"$schema": SARIF_SCHEMA, "version": "2.1.0", "runs": [run]})
