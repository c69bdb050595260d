"""The page views of a report whose rows a browser drew (``alpha-audit render``).

A ``render`` report is ``check``'s own :class:`~alpha_audit.results.CheckReport`:
its audits hold rows a browser drew (each with its measured paint,
:attr:`~alpha_audit.rows.AuditResult.observed`) and ``pages`` says what the run
saw besides.  The CI formats (SARIF, GitLab, GitHub) need nothing else; the
formats a reader reads take their page view from here, so every format of both
commands is one renderer:

* the table: a tree in one name column (story or page, then state, then icon:
  a narrow terminal wraps names least), an engine column when several ran,
  then the counts and the verdict;
* JSON: ``check``'s document with each row's measurement and a ``pages`` block;
* the pull-request comment: the story x state matrix, then the failing icons
  with the pair that limits, where to change it and the fix.

Pure functions of the report; every name a page supplies is printed through
:func:`~alpha_audit.safe_text.safe_text` (or the format's own escaping).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any

from rich.console import Group
from rich.padding import Padding
from rich.text import Text

from alpha_audit.figures import ContrastFigures
from alpha_audit.findings import Finding
from alpha_audit.observed import BlockedRequest, MeasuredPaint, PageRun
from alpha_audit.render.common import (
    COMMENT_LIMIT,
    RenderOptions,
    baselined_text,
    display_path,
    escape_markdown,
    finding_fix,
    fitted_table,
    location_text,
    location_to_dict,
    name_column,
    names_and,
    number_column,
    to_text,
)
from alpha_audit.results import CheckReport
from alpha_audit.rules import Rule
from alpha_audit.safe_text import safe_text

__all__ = [
    "MARKER",
    "PageRow",
    "blocked_line",
    "headline",
    "page_json",
    "page_markdown",
    "page_rows",
    "page_table",
    "problems_line",
    "state_matrix_cells",
    "summary_notes",
]

MARKER = "<!-- alpha-audit render -->"  # the sticky comment of the page audit
_LISTED = 50  # failing icons listed in the comment; the JSON and SARIF have them all


@dataclass(frozen=True)
class PageRow:
    """One row a browser drew (or a paint it drew too thin to measure), for the page views.

    ``paint`` is the measured paint the row carries; ``contrast`` the row's judged
    contrast (None: not measured); ``passes`` the row's verdict on it.
    """

    paint: MeasuredPaint | None
    source: str
    state: str
    engine: str
    name: str
    contrast: float | None
    passes: bool | None
    note: str = ""


def page_rows(report: CheckReport) -> list[PageRow]:
    """Every row of the report's audits a browser drew, in page order (source, state, then
    engine and the icon's place on the page), each paint too thin to measure among them."""
    out: list[tuple[tuple[Any, ...], PageRow]] = []
    for result in report.audits:
        for p, o in enumerate(result.observed):
            c = float(result.contrast[p, 0])
            row = PageRow(o, o.source, o.state, o.engine, o.name, c, bool(result.passes[p, 0]))
            out.append(((o.source, o.state, o.engine, o.box[1], o.box[0], o.name), row))
        for u in result.unaudited:
            row = PageRow(
                None, result.iconset.name, result.theme.name, "", u.icon, None, None, "not measured"
            )
            out.append(((row.source, row.state, "", 0.0, 0.0, u.icon), row))
    return [row for _, row in sorted(out, key=lambda kv: kv[0])]


# ------------------------------------------------------------------ table


def _figure(value: float | None) -> str:
    return "-" if value is None else f"{value:.2f}"


def _verdict(report: CheckReport) -> str:
    gate = report.gate
    head = "gate passed" if gate.passed else "gate failed: " + gate.counts_text()
    return f"{head} ({len(gate.warnings)} reported; {len(gate.baselined)} baselined)"


def page_table(report: CheckReport, run: PageRun, options: RenderOptions) -> str:
    """Every measured paint, one row each, as a tree in one name column (story or page,
    then state, then icon), an engine column when several engines ran, then the counts
    and the gate's verdict."""
    several = len(run.engines) > 1
    width = 6 + several
    cells: list[tuple[str | Text, ...]] = []
    source = state = None
    rows = page_rows(report)
    files = dict(run.files)
    for r in rows:
        if r.source != source:
            cells.append((Text(safe_text(r.source), style="bold"), *[""] * width))
            file = display_path(files.get(r.source), options.base)
            if file is not None:  # the story's source (importPath) or the page
                cells.append((Text(f"  ({safe_text(file)})", style="dim"), *[""] * width))
            source, state = r.source, None
        if r.state != state:
            cells.append(("  " + safe_text(r.state), *[""] * width))
            state = r.state
        o = r.paint
        linear = o.prediction("linear") if o else None
        css = o.prediction("css") if o else None
        figures = (
            (o.drawn or "-") if o else "-",
            (o.behind or "-") if o else "-",
            _figure(r.contrast) if o else r.note,
            _figure(linear.contrast if linear else None),
            _figure(css.contrast if css else None),
            _figure(o.render_drift if o else None),
        )
        engine = (r.engine,) if several else ()
        cells.append(("    " + safe_text(r.name), *engine, *figures))
    columns = [name_column("source / state / icon", 12)]
    if several:
        columns.append(number_column("engine", "left"))
    columns += [number_column(h, "left") for h in ("drawn", "behind")]
    columns += [number_column(h) for h in ("contrast", "linear", "css", "drift")]
    table = fitted_table(columns, cells)
    threshold = report.audits[0].threshold if report.audits else 3.0
    failing = sum(1 for r in rows if r.passes is False)
    unmeasured = sum(1 for r in rows if r.paint is None)
    summary = (
        f"{run.audited} page states, {run.icons} icons, {run.paints} paints; "
        f"{failing} below {threshold:g}:1 at full coverage"
        + (f"; {unmeasured} too thin to measure" if unmeasured else "")
        + f"; {len(run.blocked)} requests blocked"
    )
    # Each failure indented as a block: wrapped at the terminal's width, it stays under
    # its start (a CI log at 80 columns).
    failures = (
        Padding(Text(safe_text(f"{f.rule.value}: {where(f)}: {f.message}")), (0, 0, 0, 2))
        for f in report.gate.failures
    )
    return to_text(Group(table, Text(summary), *failures, Text(_verdict(report))), options)


def where(f: Finding) -> str:
    """``icon in story [state]`` (with the engine when the finding names one)."""
    tail = "" if f.observed is None else f", {f.observed.engine}"
    return f"{f.icons[0]} in {f.iconset} [{f.theme}{tail}]"


# ------------------------------------------------------------------ JSON


def paint_record(paint: MeasuredPaint, base: Path | None = None) -> dict[str, Any]:
    """One measured paint as JSON data (every field of :class:`MeasuredPaint`)."""
    record: dict[str, Any] = _finite(asdict(paint))
    record["match"] = str(paint.match)
    record["file"] = display_path(paint.file, base)
    record["locations"] = [location_to_dict(loc, base) for loc in paint.locations]
    return record


def _finite(value: Any) -> Any:
    """NaN (no coverage) as null, recursively: strict JSON has no NaN."""
    if isinstance(value, float) and math.isnan(value):
        return None
    if isinstance(value, dict):
        return {k: _finite(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [_finite(v) for v in value]
    return value


def page_json(run: PageRun, base: Path | None = None) -> dict[str, Any]:
    """The ``pages`` block: engines, counts, pages and their files, problems, blocked."""
    return {
        "engines": [{"name": n, "version": v} for n, v in run.engines],
        "summary": {
            "audited": run.audited,
            "icons": run.icons,
            "paints": run.paints,
            "problems": len(run.problems),
            "blocked": len(run.blocked),
        },
        "pages": [
            {"source": s, "state": t, "file": display_path(dict(run.files).get(s), base)}
            for s, t in run.pages
        ],
        "problems": [asdict(p) for p in run.problems],
        "blocked": [asdict(b) for b in run.blocked],
        "crops_left_out": run.crops_left_out,
    }


# ------------------------------------------------------------------ Markdown


def state_matrix_cells(
    report: CheckReport, run: PageRun
) -> tuple[list[str], list[tuple[str, list[int | str]]]]:
    """Stories or pages x states: the states, then per source a cell per state.

    A cell is the number of failing icons there (0: passed), ``"not audited"``
    (the page state is a problem) or ``"—"`` (the state was not asked of it).
    """
    pages = list(run.pages)
    sources = list(dict.fromkeys(s for s, _ in pages))
    states = list(dict.fromkeys(t for _, t in pages))
    failing: dict[tuple[str, str], set[str]] = {}
    for f in report.gate.failures:
        failing.setdefault((f.iconset, f.theme), set()).update(f.icons)
    broken = {(q.source, q.state) for q in run.problems}
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


def _matrix(report: CheckReport, run: PageRun) -> list[str]:
    """The story x state matrix as a Markdown table: pass, **n failing**, not audited."""
    states, rows = state_matrix_cells(report, run)
    lines = [
        "| story or page | " + " | ".join(escape_markdown(t) for t in states) + " |",
        "|---|" + "---|" * len(states),
    ]
    for source, cells in rows:
        shown = [c if isinstance(c, str) else (f"**{c} failing**" if c else "pass") for c in cells]
        lines.append(f"| {escape_markdown(source)} | " + " | ".join(shown) + " |")
    return lines


def headline(report: CheckReport, run: PageRun) -> str:
    """The verdict in one line: ``gate passed (10 page states)`` or ``gate failed: ...``."""
    gate = report.gate
    if gate.passed:
        return f"gate passed ({run.audited} page states)"
    icons = len({(f.iconset, f.theme, f.icons) for f in gate.failures})
    return f"gate failed: {icons} failing icon(s) in {run.audited} page states"


def summary_notes(report: CheckReport, run: PageRun) -> list[str]:
    """What else the reader should know: reported, baselined, page states not audited."""
    gate = report.gate
    notes = []
    if gate.warnings:
        rules = sorted({f.rule.value for f in gate.warnings})
        notes.append(f"{len(gate.warnings)} reported ({', '.join(rules)})")
    if gate.baselined:
        notes.append(f"{len(gate.baselined)} {baselined_text(gate)}")
    if run.problems:
        notes.append(f"{len(run.problems)} page state(s) could not be audited")
    return notes


def page_markdown(report: CheckReport, run: PageRun, options: RenderOptions) -> str:
    """The pull-request comment: verdict, story x state matrix, failing icons with their fixes."""
    gate = report.gate
    failures = gate.failures
    head = f"### {'✅' if gate.passed else '❌'} alpha-audit render: {headline(report, run)}"
    lines = [MARKER, head, ""]
    notes = summary_notes(report, run)
    if notes:
        lines += ["; ".join(notes).capitalize() + ".", ""]
    lines += _matrix(report, run)
    if failures:
        several = len(run.engines) > 1
        engine_head = " engine |" if several else ""
        lines += [
            "",
            f"| icon | story or page | state |{engine_head} drawn on backdrop | contrast | "
            "where | fix |",
            "|---|---|---|" + ("---|" if several else "") + "---|---|---|---|",
        ]
        for f in failures[:_LISTED]:
            o, fig = f.observed, f.figures
            shown = f.rule.value
            if f.rule is Rule.BELOW_THRESHOLD and isinstance(fig, ContrastFigures):
                shown = f"{fig.contrast:.2f}:1"
            drawn = o.drawn if o is not None else None
            pair = f"{'—' if drawn is None else drawn} on {f.canvas or '—'}"
            at = (
                escape_markdown(location_text(f.locations[0], options.base))
                if f.locations
                else escape_markdown(o.dom_path if o is not None else "")
            )
            engine = f" {escape_markdown(o.engine if o is not None else '')} |" if several else ""
            lines.append(
                f"| {escape_markdown(f.icons[0])} | {escape_markdown(f.iconset)} | "
                f"{escape_markdown(f.theme)} |{engine} {escape_markdown(pair)} | {shown} | "
                f"{at} | {escape_markdown(finding_fix(f, report))} |"
            )
        if len(failures) > _LISTED:
            lines += ["", f"{len(failures) - _LISTED} more failing icon(s): see the JSON report."]
    text = "\n".join(lines) + "\n"
    if len(text) > COMMENT_LIMIT:
        cut = text[: COMMENT_LIMIT - 200].rsplit("\n", 1)[0]
        text = cut + "\n\nThe comment was cut at GitHub's limit: see the JSON report.\n"
    return text


# ------------------------------------------------------------------ problems and blocked requests


def problems_line(run: PageRun) -> str:
    """One line for the page states a run could not audit: how many, and the first.

    >>> from alpha_audit.observed import PageProblem
    >>> problem = PageProblem("a--b", "theme:dark", "chromium", "timed out")
    >>> run = PageRun((problem,), (), 4, 0, 0, ())
    >>> problems_line(run)
    'error: 1 of 4 page states could not be audited; first: a--b [theme:dark, chromium]: timed out'
    """
    first = run.problems[0]
    return (
        f"error: {len(run.problems)} of {run.audited} page states could not be audited; "
        f"first: {first.source} [{first.state}, {first.engine}]: {first.message}"
    )


def blocked_line(blocked: Sequence[BlockedRequest], shown: int = 3) -> str:
    """One line for the requests a run refused: how many, and to which hosts.

    >>> from alpha_audit.observed import BlockedRequest as B
    >>> line = blocked_line([B("s", "dark", "chromium", "https://fonts.example/a.css"),
    ...                      B("s", "light", "chromium", "https://fonts.example/b.css"),
    ...                      B("s", "dark", "firefox", "cdn.example:443")])
    >>> line.startswith("3 requests to anything but the pages' server blocked, ")
    True
    >>> line.endswith("to cdn.example and fonts.example (every one in the JSON report)")
    True
    """
    hosts = sorted({b.host for b in blocked})
    # Per engine, the hosts it alone asked, each by itself (no page did: no other engine).
    askers: dict[str, set[str | None]] = {}
    for b in blocked:
        askers.setdefault(b.host, set()).add(b.own)
    own: dict[str, list[str]] = {}
    for host in hosts:
        (label, *others) = askers[host]
        if not others and label is not None:
            own.setdefault(label, []).append(host)
    tail = "".join(
        f"; {label} asks {_and(names)} by itself, whatever the page"
        for label, names in sorted(own.items())
    )
    return safe_text(
        f"{len(blocked)} requests to anything but the pages' server blocked, to "
        f"{_and(hosts, shown)} (every one in the JSON report{tail})"
    )


def _and(names: Sequence[str], shown: int = 3) -> str:
    """``a``, ``a and b``, ``a, b and c``, or the first ``shown`` and a count of the rest."""
    if len(names) > shown:
        return ", ".join(names[:shown]) + f" and {len(names) - shown} more hosts"
    return names_and(names) if names else ""
