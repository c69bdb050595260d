"""SARIF 2.1.0 for code-scanning dashboards (GitHub, GitLab, Azure DevOps).

Root causes (each folded over canvases) that share the line setting their
failing value and a rule are one result (:func:`~alpha_audit.render.lines.by_line`;
GitHub code scanning makes every result with its own fingerprint an alert of its
own, shown as its own annotation in a pull request's diff, so a set-wide ``alpha:``
failing 69 icons would be 69 alerts on one line), with every icon, canvas and the
count of root causes in its ``properties`` and the worst one's figures.  Its
location is the line that sets the failing value
(:attr:`~alpha_audit.findings.Finding.locations`: the ``alpha:`` that
applies, the palette entry, colour or design token of its colour, the
palette entries of both roles of a confusion), with the value's exact region
where the loader knows it.  The other places (the other values, the manifest
lines, the tokens of the canvas, the icon's SVG file at line 1: a drawing has no
better line) are ``relatedLocations``.  URIs are relative to ``%SRCROOT%`` and
percent-encoded (RFC 3986); no absolute path of the machine appears.  Rule
ids are opaque (``AA001`` ...), names readable, and each rule has
``help.markdown``.
Exempted and baselined findings stay in the log with a ``suppressions`` entry
(so dashboards show them as dismissed, with the reason), and every result has a
``partialFingerprints`` entry built from what a baseline matches on (theme,
icon set, rule, icons; a folded result: its rule, the file and kind of value
of its line, its audits and icons), never from canvases or line numbers.
Reported rules (hard-coded paints, icons that could not be rendered, losses
that are reported but not gated) are results of level ``note`` and
``warning``.  A failing finding whose fix is an exact edit of a written value
(:attr:`~alpha_audit.findings.Finding.edits`: the icon's alpha, or the palette
entry or token value of its colour) carries SARIF ``fixes`` (3.55): one fix
per answer, each replacing that value's region with the new value, quoted as
it was.
Columns count Unicode code points (``run.columnKind``, 3.14.27).
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any
from urllib.parse import quote

from alpha_audit.model import Edit, Location, Span
from alpha_audit.render.common import RenderOptions, baselined_text, dumps
from alpha_audit.render.lines import LineGroup, by_line, group_fix, group_message
from alpha_audit.results import CheckReport
from alpha_audit.rules import RULES, Level, Rule

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
# SVG files a folded result names beside its line: a set-wide alpha failing thousands of
# icons stays one result of bounded size (every icon is in its properties).
MAX_FILES = 12

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
    >>> relative_uri("bad\\udcff.svg", None)
    'bad%FF.svg'
    """
    p = Path(path)
    if base is not None and not p.is_absolute():
        p = Path(os.path.abspath(p))  # relative to where it was opened from, this process's folder
    if p.is_absolute():
        text = Path(os.path.relpath(p, base)).as_posix() if base is not None else p.name
    else:
        text = p.as_posix()
    try:  # a file name that is not UTF-8 holds its bytes as surrogates (PEP 383)
        raw = text.encode("utf-8", "surrogateescape")
    except UnicodeEncodeError:  # a lone surrogate that is no byte: encoded, not a crash
        raw = text.encode("utf-8", "surrogatepass")
    return quote(raw, safe=_URI_SAFE)


def _artifact(path: Path | None, base: Path | None) -> dict[str, Any]:
    return {"uri": relative_uri(path or "", base), "uriBaseId": SRCROOT}


def _location(
    path: Path | None, base: Path | None, line: int | None = None, span: Span | None = None
) -> dict[str, Any]:
    """A physical location with a region: the span's, else the given line, else line 1."""
    region = _region(span) if span is not None else {"startLine": line or 1}
    return {"physicalLocation": {"artifactLocation": _artifact(path, base), "region": region}}


def _region(span: Span) -> dict[str, int]:
    """A text region (3.30) with both ends: 1-based lines, code-point columns, end exclusive."""
    return {
        "startLine": span.start_line,
        "startColumn": span.start_column,
        "endLine": span.end_line,
        "endColumn": span.end_column,
    }


def _fix(edit: Edit, base: Path | None) -> dict[str, Any]:
    """A SARIF fix (3.55): one artifactChange replacing the value's region (3.56, 3.57)."""
    return {
        "description": {"text": edit.description},
        "artifactChanges": [
            {
                "artifactLocation": _artifact(edit.span.file, base),
                "replacements": [
                    {
                        # The snippet is the text replaced, so a consumer can
                        # check the file has not changed since (3.30.13).
                        "deletedRegion": {
                            **_region(edit.span),
                            "snippet": {"text": edit.span.text},
                        },
                        "insertedContent": {"text": edit.inserted},
                    }
                ],
            }
        ],
    }


def _unique(locations: list[dict[str, Any]]) -> list[dict[str, Any]]:
    """One location per (file, line), first kept; a later one with columns lends them."""
    out: dict[tuple[str, int], dict[str, Any]] = {}
    for loc in locations:
        physical = loc["physicalLocation"]
        key = (physical["artifactLocation"]["uri"], physical["region"]["startLine"])
        if key not in out:
            out[key] = loc
        elif (
            "startColumn" in physical["region"] and len(out[key]["physicalLocation"]["region"]) == 1
        ):
            out[key] = {
                "physicalLocation": {**out[key]["physicalLocation"], "region": physical["region"]}
            }
    return list(out.values())


def _place(loc: Location, base: Path | None) -> dict[str, Any]:
    """A location with the value's exact region when known, else its line."""
    return _location(loc.span.file if loc.span else loc.file, base, loc.line, loc.span)


def _result(
    g: LineGroup,
    index: int,
    base: Path | None,
    level: str = "error",
    fix: str | None = None,
    edits: tuple[Edit, ...] = (),
    baselined: str = "in the baseline",
) -> dict[str, Any]:
    f = g.worst
    places = [_place(loc, base) for loc in f.locations]
    places += [_location(path, base, line) for path, line in f.sources]
    if f.manifest is not None:
        places += [_location(f.manifest, base, line) for line in f.lines]
    files = list(dict.fromkeys(p for one in g.findings for p in one.files))
    places += [_location(p, base) for p in (files[:MAX_FILES] if g.folded else files)]
    places = _unique(places)
    if not places and f.manifest is not None:
        places = [_location(f.manifest, base)]
    result: dict[str, Any] = {
        "ruleId": RULES[g.rule].sarif_id,
        "ruleIndex": index,
        "level": level,
        "message": {"text": group_message(g) + (f". Fix: {fix}" if fix else "")},
        "locations": places[:1],
        "partialFingerprints": {"alphaAuditFinding/v2": g.fingerprint(base)},
        "properties": {
            "theme": f.theme,
            "iconset": f.iconset,
            "canvas": f.canvas,
            "canvases": list(g.canvases),
            "icons": list(g.icons),
            "rootCauses": len(g.findings),
            **({"audits": [list(a) for a in g.audits]} if len(g.audits) > 1 else {}),
            **f.figures.to_dict(),
        },
    }
    if len(places) > 1:
        # 3.27.22: ids unique within the result; a reviewer's other places to look.
        result["relatedLocations"] = [{"id": k, **loc} for k, loc in enumerate(places[1:], 1)]
    if edits:
        result["fixes"] = [_fix(e, base) for e in edits]
    if f.exemption is not None:
        result["suppressions"] = [{"kind": "external", "justification": f.exemption.reason}]
    elif f.baselined:
        result["suppressions"] = [{"kind": "external", "justification": baselined}]
    return result


def _shared_edits(g: LineGroup) -> tuple[Edit, ...]:
    """The exact edits every root cause of the group carries: those known to clear it all."""
    first, *rest = (f.edits for f in g.findings)
    return tuple(e for e in first if all(e in other for other in rest))


def _rule(rule: Rule, level: str) -> dict[str, Any]:
    """A reportingDescriptor: opaque id, readable name, what it means and how to fix it."""
    spec = RULES[rule]
    help_text = f"{spec.help} {spec.fix}"
    return {
        "id": spec.sarif_id,
        "name": rule.name.title().replace("_", ""),
        "shortDescription": {"text": spec.help},
        "help": {
            "text": help_text.replace("`", ""),
            "markdown": f"**{rule.value}**: {spec.help}\n\n**Fix:** {spec.fix}",
        },
        "defaultConfiguration": {"level": level},
        "properties": {"alphaAuditRule": rule.value},
    }


# SARIF 2.1.0 3.27.10: a rule's default level ("none" for one the policy turns off).
_LEVELS = {Level.FAIL: "error", Level.WARN: "note", Level.OFF: "none"}


def render_report(report: CheckReport, options: RenderOptions) -> str:
    """The report as one SARIF 2.1.0 run."""
    from alpha_audit import __version__

    rules = list(Rule)
    index = {r: i for i, r in enumerate(rules)}
    policy = report.gate.policy
    why = baselined_text(report.gate)
    results = [
        _result(
            g,
            index[g.rule],
            options.base,
            # Each failure's message ends with its fix, in the PR comment's words.
            fix=group_fix(g, report) if g.worst.fails else None,
            edits=_shared_edits(g) if g.worst.fails else (),
            baselined=why,
        )
        for g in by_line(report.gate.findings)
    ]
    for g in by_line(report.gate.warnings):
        level = "warning" if g.rule is Rule.UNRENDERABLE else "note"
        results.append(_result(g, index[g.rule], options.base, level))
    run: dict[str, Any] = {
        "tool": {
            "driver": {
                "name": "alpha-audit",
                "version": __version__,
                "informationUri": "https://github.com/alpha-audit/alpha-audit",
                "rules": [_rule(r, _LEVELS[policy.level(r)]) for r in rules],
            }
        },
        "results": results,
        # 3.14.27: required with results; Python counts code points, as our spans do.
        "columnKind": "unicodeCodePoints",
    }
    run["originalUriBaseIds"] = {
        SRCROOT: {"description": {"text": "The folder alpha-audit ran in (the repository root)."}}
    }
    return dumps({"$schema": SARIF_SCHEMA, "version": "2.1.0", "runs": [run]})
