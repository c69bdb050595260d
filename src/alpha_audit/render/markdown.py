"""Markdown: a pull-request comment (and CI job summary) a reviewer can act on.

Layout: a hidden marker (:data:`MARKER`, so a bot updates one sticky comment),
a headline verdict counting root causes, one line per rule (how many root
causes fail, how many icons, what is only reported, and the worst one), one
summary row per audit, then per audit (theme x icon set) a ``<details>``
section with the failing rows worst first (collisions of many colours,
confusions, newly failing paints, then losses by size), each the root causes of
one rule whose failing value one line sets (a set-wide ``alpha:`` failing every
icon is one row; :func:`~alpha_audit.render.lines.by_line`): their colours, the
line, the worst canvas and how many, the worst figures, the icons shortened to a
count and the first names, and the fix (computed in the pipeline,
:mod:`alpha_audit.fixes`, worded by
:func:`~alpha_audit.render.common.finding_fix`); then what improved (newly
passing), exemptions, the baseline, and the notes (hard-coded paints, icons that
could not be rendered).  The whole text stays within GitHub's comment limit
(:data:`COMMENT_LIMIT`); what is left out is counted and the reader is pointed
at the full report.

Every name comes from files a pull request can change, so it is escaped
(:func:`~alpha_audit.render.common.escape_markdown`).
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from dataclasses import dataclass

from alpha_audit.figures import (
    CollisionFigures,
    ConfusionFigures,
    ContrastFigures,
    DriftFigures,
    RenderDriftFigures,
    SeparationFigures,
)
from alpha_audit.findings import Finding
from alpha_audit.gate import rule_summary
from alpha_audit.render.common import (
    COMMENT_LIMIT,
    RenderOptions,
    baselined_text,
    escape_markdown,
    gamut_line,
    location_text,
    shorten_names,
    stale_text,
    where_text,
)
from alpha_audit.render.lines import LineGroup, by_line, group_fix
from alpha_audit.results import CheckReport
from alpha_audit.rows import AuditResult
from alpha_audit.rules import Rule

__all__ = ["COMMENT_LIMIT", "MARKER", "render_markdown", "render_report"]

MARKER = "<!-- alpha-audit -->"  # finds the sticky comment to update (action.yml)
_NAMES = 3  # icon names shown per group; the JSON report has them all
_NAME = 100  # characters of a theme or icon-set name in a <details> summary
_RESERVE = 1_000  # room kept for the closing lines and the "left out" note
_FRAME = 600  # room kept per audit for its <details> lines and summary (names are capped)


# ------------------------------------------------------------------ grouping


@dataclass
class _Group:
    """Root causes of one rule whose failing value one line sets (a comment row)."""

    line: LineGroup
    colour: str
    canvas: str
    canvases: int
    figures: str


def _figures(f: Finding) -> str:
    match f.figures:
        case ContrastFigures() as n:
            return f"{n.contrast_ref:.3f} → {n.contrast:.3f} ({n.gain:+.4f}) at α={n.alpha:g}"
        case SeparationFigures() | ConfusionFigures() as n:
            under = f" ({n.deficiency})" if isinstance(n, ConfusionFigures) and n.deficiency else ""
            return f"ΔE00 {n.delta_e:.2f} (α=1: {n.delta_e_ref:.2f}) < {n.min_delta_e:g}{under}"
        case CollisionFigures() as n:  # the colours are in the colour column already
            give = "both give" if n.colours == 2 else f"{n.colours} colours all give"
            return f"{give} {n.output}" + ("" if n.new else " (also at α=1)")
        case _:
            return f.message


def _colour(f: Finding, roles: dict[str, str]) -> str:
    """The colour (role) a finding is about, or the colours of a collision, or two roles."""
    match f.figures:
        case (
            ContrastFigures(source=source)
            | DriftFigures(source=source)
            | RenderDriftFigures(source=source)
        ):
            return f"{roles.get(f.icons[0], '')} {source}".strip()
        case CollisionFigures(sources=sources) | SeparationFigures(sources=sources):
            return shorten_names(list(sources), 8)
        case ConfusionFigures(roles=pair):
            return " / ".join(pair)
        case _:
            return ""


def _groups(findings: Sequence[Finding], roles: dict[str, str]) -> list[_Group]:
    """One row per line and rule (:func:`~alpha_audit.render.lines.by_line`), worst first."""
    out = []
    for g in by_line(findings):
        colours = list(dict.fromkeys(_colour(f, roles) for f in g.findings))
        out.append(
            _Group(
                g,
                shorten_names(colours, 4),
                g.worst.canvas or "",
                len(g.canvases),
                _figures(g.worst),
            )
        )
    return out


def _where(f: Finding, options: RenderOptions) -> str:
    """The line to edit: ``set.yaml:12`` (the finding's first location), or nothing."""
    return location_text(f.locations[0], options.base) if f.locations else ""


def _canvases(g: _Group) -> str:
    return g.canvas if g.canvases <= 1 else f"{g.canvas} (worst) +{g.canvases - 1}"


def _icons(names: Sequence[str]) -> str:
    count = f"{len(names)} icon{'s' if len(names) != 1 else ''}"
    return f"{count}: {shorten_names(list(names), _NAMES)}"


_BACKSLASH = re.compile(r"\\(.)")


def _html(text: str) -> str:
    """A name inert inside an HTML block (``<summary>``), where Markdown is not parsed."""
    return _BACKSLASH.sub(r"\1", escape_markdown(text))


# ------------------------------------------------------------------ rendering


class _Budget:
    """Lines kept while they fit GitHub's comment limit; counts what did not."""

    def __init__(self, limit: int) -> None:
        self.lines: list[str] = []
        self.size = 0
        self.limit = limit
        self.left_out = 0

    def force(self, *lines: str) -> None:
        """Add ``lines`` whatever the size (short frame lines budgeted by the caller)."""
        self.lines.extend(lines)
        self.size += sum(len(line) + 1 for line in lines)

    def add(self, *lines: str) -> bool:
        cost = sum(len(line) + 1 for line in lines)
        if self.size + cost > self.limit:
            return False
        self.lines.extend(lines)
        self.size += cost
        return True


def _table(
    budget: _Budget, title: str, header: str, rows: Sequence[str], left_out: list[int]
) -> None:
    if not rows:
        return
    cells = header.count("|") - 1
    if not budget.add("", title, "", header, "|" + "---|" * cells):
        left_out[0] += len(rows)
        return
    for k, row in enumerate(rows):
        if not budget.add(row):
            left_out[0] += len(rows) - k
            return


def render_markdown(
    report: CheckReport, options: RenderOptions, *, limit: int = COMMENT_LIMIT
) -> str:
    """The comment, at most ``limit`` characters, each failing group with its fix."""
    gate = report.gate
    audits = report.audits
    budget = _Budget(limit - _RESERVE)
    left_out = [0]
    all_roles = {
        (r.theme.name, r.iconset.name): {i.name: i.color_name or "" for i in r.iconset.icons}
        for r in audits
    }
    per_audit = {
        key: _groups([f for f in gate.failures if (f.theme, f.iconset) == key], roles)
        for key, roles in all_roles.items()
    }
    _head(report, budget)
    _rule_table(report, options, budget)
    _audit_table(report, per_audit, budget)
    for k, r in enumerate(audits):
        key = (r.theme.name, r.iconset.name)
        groups = per_audit[key]
        verdict = f"❌ {len(groups)} failing group(s)" if groups else "✅ passed"
        newly = _groups_of_rows(r, all_roles[key])
        summary = f"{_html(r.theme.name[:_NAME])} / {_html(r.iconset.name[:_NAME])}: {verdict}"
        if newly:
            summary += f"; {len(newly)} newly passing"
        opened = " open" if groups else ""
        # Every audit gets its <details> and an equal share of what is left, so
        # a long first theme cannot crowd the others out of the comment.
        budget.force("", f"<details{opened}><summary><b>{summary}</b></summary>")
        remaining = len(audits) - k
        section = _Budget((budget.limit - budget.size - _FRAME * remaining) // remaining)
        _audit_section(report, r, groups, all_roles[key], newly, options, section, left_out)
        budget.force(*section.lines, "", "</details>")
    _notes(report, options, budget, left_out)
    lines = budget.lines
    if left_out[0]:
        lines += [
            "",
            f"**{left_out[0]} row(s) left out** to stay within GitHub's "
            f"{COMMENT_LIMIT:,}-character comment limit; every finding is in the JSON "
            "(`--format json`) and SARIF reports.",
        ]
    return "\n".join(lines) + "\n"


def _head(report: CheckReport, budget: _Budget) -> None:
    """The verdict line and the rules gated."""
    gate, audits = report.gate, report.audits
    rules = ", ".join(f"`{r}`" for r in sorted(r.value for r in gate.policy.rules))
    if gate.passed:
        improved = sum(s.summary.newly_pass for s in audits)
        head = f"## ✅ alpha-audit: gate passed ({len(audits)} audit(s)"
        head += f"; {improved} paint×canvas newly reach the threshold)" if improved else ")"
    else:
        failing_audits = {(f.theme, f.iconset) for f in gate.failures}
        counts = gate.counts_text(escape_markdown)
        head = (
            f"## ❌ alpha-audit: gate failed: {len(gate.failures)} root cause(s) ({counts}) "
            f"in {len(failing_audits)} of {len(audits)} audit(s)"
        )
    budget.add(MARKER, head, "", f"Rules: {rules}; max loss {gate.policy.max_loss:g}.", "")


def _rule_table(report: CheckReport, options: RenderOptions, budget: _Budget) -> None:
    """One row per rule: its failing, reported, exempted and baselined root causes, the worst."""
    by_rule = rule_summary(report.gate)
    if not by_rule:
        return
    budget.add(
        "| rule | failing root causes | icons | reported, not gated | exempted | "
        f"{'on the base' if report.gate.on_base else 'baselined'} | worst |",
        "|---|--:|--:|--:|--:|--:|---|",
    )
    for rs in by_rule:
        worst = ""
        if rs.worst is not None:
            at = _where(rs.worst, options)
            worst = f"{where_text(rs.worst)}: {_figures(rs.worst)}" + (f" ({at})" if at else "")
        cells = [
            f"`{rs.rule.value}`",
            str(rs.failing),
            str(rs.icons),
            str(rs.reported),
            str(rs.exempted),
            str(rs.baselined),
            escape_markdown(worst),
        ]
        budget.add("| " + " | ".join(cells) + " |")
    budget.add("")


def _audit_table(
    report: CheckReport, per_audit: dict[tuple[str, str], list[_Group]], budget: _Budget
) -> None:
    """One row per audit: theme, icon set, alpha, verdict and counts."""
    failing_audits = {(f.theme, f.iconset) for f in report.gate.failures}
    budget.add(
        "| theme | icon set | icons | α | verdict | failing groups | newly passing paint×canvas "
        "| collisions | unrendered |",
        "|---|---|--:|--:|---|--:|--:|--:|--:|",
    )
    for r in report.audits:
        key = (r.theme.name, r.iconset.name)
        s = r.summary
        alphas = sorted({float(a) for a in r.alpha})
        alpha = (
            "" if not alphas else f"{alphas[0]:g}" + (f"–{alphas[-1]:g}" if len(alphas) > 1 else "")
        )
        cells = [
            escape_markdown(r.theme.name),
            escape_markdown(r.iconset.name),
            str(len(r.iconset.icons)),
            alpha,
            "❌ failed" if key in failing_audits else "✅ passed",
            str(len(per_audit[key])),
            str(s.newly_pass),
            f"{s.collisions} ({s.new_collisions} new)",
            str(len(r.problems)),
        ]
        budget.add("| " + " | ".join(cells) + " |")


def _row(cells: Sequence[str]) -> str:
    return "| " + " | ".join(escape_markdown(c) for c in cells) + " |"


def _audit_section(
    report: CheckReport,
    r: AuditResult,
    groups: list[_Group],
    roles: dict[str, str],
    newly: Sequence[tuple[str, str, str, list[str]]],
    options: RenderOptions,
    section: _Budget,
    left_out: list[int],
) -> None:
    """One audit's failing groups with their fixes, what newly passes, what is exempted."""
    rows = [
        _row(
            (
                g.colour,
                _where(g.line.worst, options),
                _canvases(g),
                g.line.rule.value,
                g.figures,
                _icons(g.line.icons),
                group_fix(g.line, report) or "",
            )
        )
        for g in groups
    ]
    _table(
        section,
        "**Failing**, worst first (colour, the line that sets it, canvases)",
        "| colour | set at | canvases | rule | numbers | icons | fix |",
        rows,
        left_out,
    )
    _table(
        section,
        f"**Improved**: newly reach {r.threshold:g}:1",
        "| colour | canvas | contrast | icons |",
        [_row((colour, canvas, shown, _icons(icons))) for colour, canvas, shown, icons in newly],
        left_out,
    )
    key = (r.theme.name, r.iconset.name)
    exempt = [f for f in report.gate.exempted if (f.theme, f.iconset) == key]
    _table(
        section,
        "**Exempted**",
        "| colour | canvases | rule | icons | reason |",
        [
            _row((g.colour, _canvases(g), g.line.rule.value, _icons(g.line.icons), _reason(g)))
            for g in _groups(exempt, roles)
        ],
        left_out,
    )
    baselined = sum(1 for f in report.gate.baselined if (f.theme, f.iconset) == key)
    if baselined:
        section.add("", f"{baselined} root cause(s) {baselined_text(report.gate)}.")


def _reason(g: _Group) -> str:
    return g.line.worst.exemption.reason if g.line.worst.exemption else ""


def _notes(
    report: CheckReport, options: RenderOptions, budget: _Budget, left_out: list[int]
) -> None:
    """Colours outside sRGB, stale baseline entries, broken icons and hard-coded paints."""
    gate = report.gate
    if report.gamut:
        budget.add("", f"### Colours outside sRGB ({len(report.gamut)})", "")
        for k, note in enumerate(report.gamut):
            if not budget.add(f"- {escape_markdown(gamut_line(note, options.base))}"):
                left_out[0] += len(report.gamut) - k
                break
    if gate.stale:
        budget.add("", f"{stale_text(gate)}.")
    for rule, title in (
        (Rule.UNRENDERABLE, "Icons that could not be rendered"),
        (Rule.FIXED_COLOUR, "Hard-coded paints (they will not follow the theme)"),
    ):
        notes = [w for w in gate.warnings if w.rule is rule]
        if not notes:
            continue
        budget.add("", f"### {title} ({len(notes)})", "")
        for k, w in enumerate(notes):
            line = f"- {escape_markdown(', '.join(w.icons))}: {escape_markdown(w.message)}"
            if not budget.add(line):
                left_out[0] += len(notes) - k
                break


def _groups_of_rows(
    result: AuditResult, roles: dict[str, str]
) -> list[tuple[str, str, str, list[str]]]:
    """Newly passing (colour, canvas) pairs: colour, canvas, contrast change, icons."""
    groups: dict[tuple[str, str, float], tuple[str, str, str, list[str]]] = {}
    for row in result.rows():
        if not row.newly_passes:
            continue
        key = (row.source, row.canvas, row.alpha)
        if key not in groups:
            colour = f"{roles.get(row.icon, '')} {row.source}".strip()
            change = f"{row.contrast_ref:.3f} → {row.contrast:.3f} at α={row.alpha:g}"
            groups[key] = (colour, row.canvas, change, [])
        groups[key][3].append(row.icon)
    order = {c: k for k, c in enumerate(dict.fromkeys(g[0] for g in groups.values()))}
    return sorted(groups.values(), key=lambda g: order[g[0]])


def render_report(report: CheckReport, options: RenderOptions) -> str:
    """The pull-request comment (:func:`render_markdown`; a page run's:
    :func:`~alpha_audit.render.pages.page_markdown`)."""
    if report.pages is not None:
        from alpha_audit.render.pages import page_markdown

        return page_markdown(report, report.pages, options)
    return render_markdown(report, options)
