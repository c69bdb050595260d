"""Renderers of a page audit (``alpha-audit render``): pure functions of a :class:`PageReport`.

The CI formats are ``check``'s own, read through
:meth:`~alpha_audit.pages.report.PageReport.as_check` (a measured paint's
findings are :class:`~alpha_audit.findings.Finding` objects like any other):
SARIF results sit at the manifest line of the mapped icon with the story file
(or page) related and the story, state, engine and DOM path in their
properties; GitLab Code Quality and GitHub annotations likewise.  What is
page-specific is here: the table and JSON (``alpha-audit.render/1``: the
measured paints, then the gate), JUnit (a suite per story or page, a case per
icon and state) and the pull-request comment, a story x state matrix followed
by the failing icons with their worst contrast, backdrop and fix.  The HTML
report (:mod:`alpha_audit.render.pages_html`) shares the matrix and verdict.
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from dataclasses import asdict
from pathlib import Path
from typing import Any

from rich import box
from rich.text import Text

from alpha_audit.findings import Finding
from alpha_audit.pages.measured import MeasuredPaint
from alpha_audit.pages.report import PageReport
from alpha_audit.render.common import (
    RenderOptions,
    baselined_text,
    display_path,
    dumps,
    escape_markdown,
    finding_fix,
    fitted_table,
    fix_to_dict,
    location_text,
    name_column,
    number_column,
    to_text,
)
from alpha_audit.safe_text import safe_text

__all__ = [
    "MARKER",
    "RENDER_SCHEMA",
    "headline",
    "paint_record",
    "render_github",
    "render_gitlab",
    "render_json",
    "render_junit",
    "render_markdown",
    "render_sarif",
    "render_table",
    "state_matrix_cells",
    "summary_notes",
]

RENDER_SCHEMA = "alpha-audit.render/1"
MARKER = "<!-- alpha-audit render -->"  # the sticky comment of the page audit
COMMENT_LIMIT = 65_536  # GitHub's comment limit (render.markdown.COMMENT_LIMIT)
_LISTED = 50  # failing icons listed in the comment; the JSON and SARIF have them all


# ------------------------------------------------------------------ JSON


def _clean(value: Any) -> Any:
    """NaN (no coverage) as null: JSON has no NaN."""
    if isinstance(value, float) and math.isnan(value):
        return None
    if isinstance(value, dict):
        return {k: _clean(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [_clean(v) for v in value]
    return value


def paint_record(paint: MeasuredPaint, base: Path | None = None) -> dict[str, Any]:
    """One measured paint as JSON data (every field of :class:`MeasuredPaint`, and ``passes``)."""
    record = asdict(paint)
    record["match"] = str(paint.match)
    record["passes"] = paint.passes
    record["file"] = display_path(paint.file, base)
    return dict(_clean(record))


def render_json(report: PageReport, options: RenderOptions) -> str:
    """``alpha-audit.render/1``: engines, counts, measured paints, problems, blocked, the gate."""
    from alpha_audit.render.json import gate_to_dict

    result, gate = report.result, report.gate
    document = {
        "schema": RENDER_SCHEMA,
        "engines": [{"name": n, "version": v} for n, v in result.engines],
        "summary": {
            "audited": result.audited,
            "icons": result.icons,
            "paints": len(result.paints),
            "failing": len(result.failing),
            "problems": len(result.problems),
            "blocked": len(result.blocked),
        },
        "paints": [paint_record(p, options.base) for p in result.paints],
        "problems": [asdict(p) for p in result.problems],
        "blocked": [asdict(b) for b in result.blocked],
        "gate": gate_to_dict(gate, options.base),
        "fixes": [fix_to_dict(f, options.base) for f in report.fixes],
    }
    return dumps(document)


# ------------------------------------------------------------------ table


def _figure(value: float | None) -> str:
    return "-" if value is None else f"{value:.2f}"


def _verdict(report: PageReport) -> str:
    gate = report.gate
    if gate.passed:
        head = "gate passed"
    else:
        head = "gate failed: " + ", ".join(f"{n} {rule}" for rule, n in gate.counts().items())
    extra = [
        f"{len(gate.warnings)} reported",
        f"{len(gate.baselined)} baselined",
    ]
    return f"{head} ({'; '.join(extra)})"


def render_table(report: PageReport, options: RenderOptions) -> str:
    """Every measured paint, one row each, as a tree in one name column (story or page,
    then state, then icon: a narrow terminal wraps names least), then the counts and the
    gate's verdict."""
    result = report.result
    rows: list[tuple[str | Text, ...]] = []
    source = state = None
    for p in result.paints:
        if p.source != source:
            rows.append((Text(p.source, style="bold"), *[""] * 7))
            source, state = p.source, None
        if p.state != state:
            rows.append(("  " + p.state, *[""] * 7))
            state = p.state
        linear, css = p.prediction("linear"), p.prediction("css")
        rows.append(
            (
                "    " + (p.icon or p.dom_path.rsplit(" > ", 1)[-1]),
                p.drawn or "-",
                p.behind or "-",
                _figure(p.contrast_worst),
                _figure(p.contrast_median),
                _figure(linear.contrast if linear else None),
                _figure(css.contrast if css else None),
                _figure(p.render_drift),
            )
        )
    columns = [name_column("source / state / icon", 12)]
    columns += [number_column(h, "left") for h in ("drawn", "behind")]
    columns += [number_column(h) for h in ("worst", "median", "linear", "css", "drift")]
    table = fitted_table(columns, rows, box=box.SIMPLE_HEAD, pad_edge=False)
    threshold = result.paints[0].threshold if result.paints else 3.0
    lines = [
        f"{result.audited} page states, {result.icons} icons, {len(result.paints)} paints; "
        f"{len(result.failing)} below {threshold:g}:1 at their worst pixel; "
        f"{len(result.blocked)} requests blocked",
    ]
    for f in report.gate.failures:
        lines.append(safe_text(f"  {f.rule.value}: {_where(f)}: {f.message}"))
    lines.append(_verdict(report))
    return to_text(table, options) + "\n".join(lines) + "\n"


def _where(f: Finding) -> str:
    return f"{f.icons[0]} in {f.iconset} [{f.theme}]"


# ------------------------------------------------------------------ CI formats


def render_sarif(report: PageReport, options: RenderOptions) -> str:
    """SARIF 2.1.0: ``check``'s log of the findings (story, state and DOM path as properties)."""
    from alpha_audit.render.sarif import render_report

    return render_report(report.as_check(), options)


def render_gitlab(report: PageReport, options: RenderOptions) -> str:
    """GitLab Code Quality: ``check``'s issues of the findings."""
    from alpha_audit.render.gitlab import render_report

    return render_report(report.as_check(), options)


def render_github(report: PageReport, options: RenderOptions) -> str:
    """GitHub workflow annotations: ``check``'s, the verdict counting page states."""
    from alpha_audit.render.github import gate_annotations

    passed = f"gate passed ({report.result.audited} page state(s))"
    return gate_annotations(report.gate, options, passed)


def render_junit(report: PageReport, options: RenderOptions) -> str:
    """JUnit XML: a suite per story or page, a case per icon and state, failing or not."""
    from alpha_audit.render.junit import xml_safe

    failing: dict[tuple[str, str, str], list[Finding]] = {}
    for f in report.gate.findings:
        failing.setdefault((f.iconset, f.theme, f.icons[0]), []).append(f)
    cases: dict[str, dict[tuple[str, str], MeasuredPaint]] = {}
    for p in report.result.paints:
        name = p.icon if p.icon is not None else p.dom_path
        cases.setdefault(p.source, {}).setdefault((p.state, name), p)
    root = ET.Element("testsuites", {"name": "alpha-audit render"})
    totals = {"tests": 0, "failures": 0, "errors": 0, "skipped": 0}
    problems = {(q.source, q.state): q for q in report.result.problems}
    sources = list(dict.fromkeys([*cases, *(q.source for q in report.result.problems)]))
    for source in sources:
        suite = ET.SubElement(root, "testsuite", {"name": xml_safe(source)})
        counts = dict.fromkeys(totals, 0)
        for (state, name), p in cases.get(source, {}).items():
            case = ET.SubElement(
                suite,
                "testcase",
                {
                    "name": xml_safe(f"{name} [{state}]"),
                    "classname": xml_safe(f"{source}.{state}"),
                    "file": xml_safe(display_path(p.file, options.base) or ""),
                    "time": "0",
                },
            )
            counts["tests"] += 1
            found = failing.get((source, state, name), [])
            fails = [f for f in found if f.fails]
            if fails:
                counts["failures"] += 1
                said = "; ".join(f"{f.rule.value}: {f.message}" for f in fails)
                kinds = ",".join(sorted({f.rule.value for f in fails}))
                failure = ET.SubElement(case, "failure", {"message": xml_safe(said), "type": kinds})
                failure.text = xml_safe("\n".join(f.message for f in fails))
            elif found:
                counts["skipped"] += 1
                why = f"{found[0].rule.value} in the baseline"
                ET.SubElement(case, "skipped", {"message": why})
        for (src, state), q in problems.items():
            if src != source:
                continue
            case = ET.SubElement(
                suite, "testcase", {"name": xml_safe(f"[{state}]"), "classname": xml_safe(source)}
            )
            counts["tests"] += 1
            counts["errors"] += 1
            error = ET.SubElement(case, "error", {"message": xml_safe(q.message), "type": "page"})
            error.text = xml_safe(q.message)
        for k, v in counts.items():
            suite.set(k, str(v))
            totals[k] += v
    for k, v in totals.items():
        root.set(k, str(v))
    ET.indent(root)
    return '<?xml version="1.0" encoding="UTF-8"?>\n' + ET.tostring(root, "unicode") + "\n"


# ------------------------------------------------------------------ Markdown


def state_matrix_cells(
    report: PageReport,
) -> tuple[list[str], list[tuple[str, list[int | str]]]]:
    """Stories or pages x states: the states, then per source a cell per state.

    A cell is the number of failing icons there (0: passed), ``"not audited"``
    (the page state is a problem) or ``"—"`` (the state was not asked of it).
    """
    result = report.result
    pages = list(result.pages) or list(dict.fromkeys((p.source, p.state) for p in result.paints))
    sources = list(dict.fromkeys(s for s, _ in pages))
    states = list(dict.fromkeys(t for _, t in pages))
    failing: dict[tuple[str, str], set[str]] = {}
    for f in report.gate.failures:
        failing.setdefault((f.iconset, f.theme), set()).update(f.icons)
    broken = {(q.source, q.state) for q in result.problems}
    rows: list[tuple[str, list[int | str]]] = []
    for source in sources:
        cells: list[int | str] = []
        for state in states:
            if (source, state) in broken:
                cells.append("not audited")
            elif (source, state) not in pages:
                cells.append("—")
            else:
                cells.append(len(failing.get((source, state), ())))
        rows.append((source, cells))
    return states, rows


def _matrix(report: PageReport) -> list[str]:
    """The story x state matrix as a Markdown table: pass, **n failing**, not audited."""
    states, rows = state_matrix_cells(report)
    lines = [
        "| story or page | " + " | ".join(escape_markdown(t) for t in states) + " |",
        "|---|" + "---|" * len(states),
    ]
    for source, cells in rows:
        shown = [c if isinstance(c, str) else (f"**{c} failing**" if c else "pass") for c in cells]
        lines.append(f"| {escape_markdown(source)} | " + " | ".join(shown) + " |")
    return lines


def headline(report: PageReport) -> str:
    """The verdict in one line: ``gate passed (10 page states)`` or ``gate failed: ...``."""
    gate, result = report.gate, report.result
    if gate.passed:
        return f"gate passed ({result.audited} page states)"
    icons = len({(f.iconset, f.theme, f.icons) for f in gate.failures})
    return f"gate failed: {icons} failing icon(s) in {result.audited} page states"


def summary_notes(report: PageReport) -> list[str]:
    """What else the reader should know: reported, baselined, page states not audited."""
    gate, result = report.gate, report.result
    notes = []
    if gate.warnings:
        rules = sorted({f.rule.value for f in gate.warnings})
        notes.append(f"{len(gate.warnings)} reported ({', '.join(rules)})")
    if gate.baselined:
        notes.append(f"{len(gate.baselined)} {baselined_text(gate)}")
    if result.problems:
        notes.append(f"{len(result.problems)} page state(s) could not be audited")
    return notes


def render_markdown(report: PageReport, options: RenderOptions) -> str:
    """The pull-request comment: verdict, story x state matrix, failing icons with their fixes."""
    gate = report.gate
    check = report.as_check()
    failures = gate.failures
    head = f"### {'✅' if gate.passed else '❌'} alpha-audit render: {headline(report)}"
    lines = [MARKER, head, ""]
    notes = summary_notes(report)
    if notes:
        lines += ["; ".join(notes).capitalize() + ".", ""]
    lines += _matrix(report)
    if failures:
        lines += [
            "",
            "| icon | story or page | state | worst | backdrop | where | fix |",
            "|---|---|---|---|---|---|---|",
        ]
        for f in failures[:_LISTED]:
            n = f.numbers
            worst = n.get("contrast")
            shown = f"{worst:.2f}:1" if isinstance(worst, float) else "—"
            if f.rule.value != "below-threshold":
                shown = f"{f.rule.value}"
            where = (
                escape_markdown(location_text(f.locations[0], options.base))
                if f.locations
                else escape_markdown(n.get("dom_path", ""))
            )
            lines.append(
                f"| {escape_markdown(f.icons[0])} | {escape_markdown(f.iconset)} | "
                f"{escape_markdown(f.theme)} | {shown} | {escape_markdown(f.canvas or '—')} | "
                f"{where} | {escape_markdown(finding_fix(f, check))} |"
            )
        if len(failures) > _LISTED:
            lines += ["", f"{len(failures) - _LISTED} more failing icon(s): see the JSON report."]
    text = "\n".join(lines) + "\n"
    if len(text) > COMMENT_LIMIT:
        cut = text[: COMMENT_LIMIT - 200].rsplit("\n", 1)[0]
        text = cut + "\n\nThe comment was cut at GitHub's limit: see the JSON report.\n"
    return text
