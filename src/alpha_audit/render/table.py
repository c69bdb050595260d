"""Terminal report for ``check``: a per-canvas summary and the findings that matter.

Built with rich and rendered to a string of a given width, so it is a pure
function of the result; the CLI decides width and colour.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping, Sequence
from pathlib import Path
from typing import TypeVar

from rich.console import Group, RenderableType
from rich.padding import Padding
from rich.text import Text

from alpha_audit.findings import Finding
from alpha_audit.gate import GateResult, rule_summary
from alpha_audit.render.common import (
    RenderOptions,
    baselined_text,
    display_path,
    finding_fix,
    fitted_table,
    gamut_line,
    location_text,
    name_column,
    number_column,
    stale_text,
    to_text,
    where_text,
)
from alpha_audit.render.common import shorten_names as icons_label
from alpha_audit.results import CheckReport
from alpha_audit.rows import AuditResult, Row
from alpha_audit.rules import Rule
from alpha_audit.safe_text import safe_text

__all__ = ["MAX_FINDINGS", "check_renderable", "gate_renderable", "render_report"]

MAX_FINDINGS = 12  # per section; the JSON has everything
_Item = TypeVar("_Item")


def _more(items: Sequence[object], where: str = "--format json") -> list[RenderableType]:
    """The line counting what a section leaves out beyond :data:`MAX_FINDINGS`, if any."""
    n = len(items) - MAX_FINDINGS
    return [Text(f"  … and {n} more (see {where})")] if n > 0 else []


def _listed(
    title: Text, items: Sequence[_Item], line: Callable[[_Item], str], where: str = "--format json"
) -> list[RenderableType]:
    """``title``, a line per item up to :data:`MAX_FINDINGS`, then how many more."""
    return [title, *(Text(line(i)) for i in items[:MAX_FINDINGS]), *_more(items, where)]


def _fmt_alpha(result: AuditResult) -> str:
    alphas = sorted({float(a) for a in result.alpha})
    if not alphas:  # every icon failed to render: nothing was composited
        return "-"
    if len(alphas) == 1:
        return f"{alphas[0]:g}"
    return f"{alphas[0]:g}..{alphas[-1]:g}"


def _summary_table(result: AuditResult) -> RenderableType:
    t = result.threshold
    rows = []
    for cs in result.canvas_summaries():
        passing = f"{cs.passing_ref}→{cs.passing}/{cs.rows}"
        loss = Text(f"{cs.losses} (-{cs.max_loss:.2f})", style="red") if cs.losses else Text("0")
        coll = Text(str(cs.collisions), style="red") if cs.collisions else Text("0")
        sep = cs.separation
        # The set's minimum at alpha 1 (its own closest pair) -> at alpha.
        de = "-" if sep is None else f"{sep.set_delta_e_ref:.1f}→{sep.delta_e:.1f}"
        rows.append(
            (
                Text(cs.canvas),
                Text(cs.background, style=f"on {cs.background}"),
                Text(f"{cs.mean_gain:+.2f}", style="green" if cs.mean_gain > 0 else "red"),
                passing,
                Text(str(cs.newly_pass), style="green") if cs.newly_pass else "0",
                loss,
                coll,
                de,
            )
        )
    columns = [
        name_column("canvas", min_width=8),
        number_column("bg", justify="left"),
        *(number_column(name) for name in ("gain", f"≥{t:g}:1", "new", "loss", "coll", "min ΔE")),
    ]
    # The box's space divider is the gap: the row fits 60 columns.
    return fitted_table(columns, rows, padding=(0, 0), header_style="bold")


def _grouped(result: AuditResult, rows: Iterable[Row]) -> list[tuple[Row, list[str]]]:
    """Rows that differ only by icon (same canvas, paint, opacity and alpha) merged, in order.

    Icons sharing a paint and coefficient get identical numbers on a canvas, so a
    set of 300 icons in 7 colours reports 7 lines per canvas, not 300.
    """
    groups: dict[tuple[str, str, float, float], tuple[Row, list[str]]] = {}
    for row in rows:
        key = (row.canvas, row.source, row.opacity, row.alpha)
        if key in groups:
            if row.icon not in groups[key][1]:
                groups[key][1].append(row.icon)
        else:
            groups[key] = (row, [row.icon])
    return list(groups.values())


# Columns of figures are never cut (render.common.fitted_table); these fold,
# no narrower than their longest figure: "■ #rrggbb" and a hex code.
_NAME_WIDTHS = {"colour": 9, "sources": 7, "output": 7}
_FIGURES = {"α", "contrast", "contrast at α", "output"}


def _section(
    title: str, style: str, header: tuple[str, ...], items: list[tuple[str | Text, ...]]
) -> list[RenderableType]:
    """A titled table, one finding per row; names wrap, figures stay whole."""
    if not items:
        return []
    columns = [
        number_column(name, "right" if name.startswith("contrast") else "left")
        if name in _FIGURES
        else name_column(name, _NAME_WIDTHS.get(name, 6), shrink_first=name == "icons")
        for name in header
    ]
    table = fitted_table(
        columns, items[:MAX_FINDINGS], box=None, padding=(0, 1), header_style="dim"
    )
    title_text = Text(f"{title} ({len(items)})", style=f"bold {style}")
    return [title_text, Padding(table, (0, 0, 0, 2)), *_more(items)]


def _colour(row: Row, palette_names: Mapping[str, str | None]) -> Text:
    """A row's colour: a swatch, its palette name and hex, its opacity when not 1."""
    name = None if row.fixed else palette_names.get(row.icon)
    swatch = Text("■ ", style=row.source)
    label = f"{name} {row.source}" if name else row.source
    if row.opacity != 1.0:
        label += f" @{row.opacity:g}"
    return swatch + Text(label)


def _change(row: Row) -> str:
    return f"{row.contrast_ref:.3f} → {row.contrast:.3f}"


def _findings(result: AuditResult, base: Path | None = None) -> list[RenderableType]:
    rows = list(result.rows())
    palette_names = {i.name: i.color_name for i in result.iconset.icons}
    one_alpha = len({float(a) for a in result.alpha}) <= 1  # then α is in the heading

    def grouped(
        selected: Iterable[Row], numbers: Callable[[Row], str]
    ) -> list[tuple[str | Text, ...]]:
        return [
            (
                _colour(r, palette_names),
                *(() if one_alpha else (f"{r.alpha:g}",)),
                r.canvas,
                numbers(r),
                icons_label(icons),
            )
            for r, icons in _grouped(result, selected)
        ]

    alpha_col: tuple[str, ...] = () if one_alpha else ("α",)
    head = ("colour", *alpha_col, "canvas", "contrast", "icons")
    losses = sorted((r for r in rows if r.loss), key=lambda r: r.gain)
    still = sorted((r for r in rows if not r.passes), key=lambda r: r.contrast)
    collisions: list[tuple[str | Text, ...]] = [
        (
            c.canvas,
            ", ".join(c.sources),
            c.output + ("" if c.new else " (already at α=1)"),
            icons_label(c.icons),
        )
        for c in result.collisions
    ]
    t = f"{result.threshold:g}:1"
    lost = grouped(losses, lambda r: f"{_change(r)} ({r.gain:+.4f})")
    newly_below = grouped((r for r in rows if r.newly_fails), _change)
    newly_reach = grouped((r for r in rows if r.newly_passes), _change)
    return [
        *_section("Contrast losses", "red", head, lost),
        *_section(f"Newly below {t}", "red", head, newly_below),
        *_section(
            "Collisions (distinct colours, same 8-bit output)",
            "red",
            ("canvas", "sources", "output", "icons"),
            collisions,
        ),
        *_section(f"Newly reach {t}", "green", head, newly_reach),
        *_section(
            f"Still below {t} at α",
            "yellow",
            ("colour", *alpha_col, "canvas", "contrast at α", "icons"),
            grouped(still, lambda r: f"{r.contrast:.3f}"),
        ),
        *_problems(result, base),
    ]


def _problems(result: AuditResult, base: Path | None) -> list[RenderableType]:
    """The icons that could not be rendered, with the reason."""
    if not result.problems:
        return []
    return _listed(
        Text(f"Icons that could not be rendered ({len(result.problems)})", style="bold yellow"),
        result.problems,
        lambda p: safe_text(f"  {p.icon} ({display_path(p.file, base)}): {p.message}"),
    )


def check_renderable(result: AuditResult, base: Path | None = None) -> RenderableType:
    """The whole report as one rich renderable."""
    s = result.summary
    theme, iconset = result.theme, result.iconset
    head = Text.assemble(
        ("alpha-audit check", "bold"),
        f"  {iconset.name} ({len(iconset.icons)} icons) on {theme.name} "
        f"({len(theme.canvases)} canvas{'' if len(theme.canvases) == 1 else 'es'}), "
        f"α={_fmt_alpha(result)}",
    )
    foot = Text(
        f"{s.combinations} paint×canvas: contrast up {s.increase_pct:.1f}%, "
        f"down {s.decrease_pct:.1f}%, mean {s.mean_gain:+.3f}; "
        f"{s.newly_pass} newly reach {result.threshold:g}:1, {s.newly_fail} newly fail; "
        f"{s.losses} losses (max {s.max_loss:.4f}); {s.collisions} collisions "
        f"({s.new_collisions} new)" + _drift_note(result),
        style="bold",
    )
    return Group(head, _summary_table(result), *_findings(result, base), Text(""), foot)


def _drift_note(result: AuditResult) -> str:
    """The worst colour drift over the rows (docs/model.md)."""
    if not result.drift.size:
        return ""
    p, j = divmod(int(result.drift.argmax()), result.drift.shape[1])
    e = result.entries[p]
    where = e.icon.name if not e.fixed else f"{e.icon.name} {e.paint}"
    canvas = result.theme.canvases[j].name
    return f"; colour drift up to {result.drift[p, j]:.1f} CIEDE2000 ({where} on {canvas})"


def gate_renderable(gate: GateResult, base: Path | None = None) -> RenderableType:
    """The verdict: one line per rule, then the failing root causes worst first.

    Each root cause names its icons, its worst canvas (and how many more), the
    line that sets its failing value and its numbers; then exemptions, the
    baseline (or the base revision) and the notes the policy reports.
    """
    out: list[RenderableType] = []
    rules = ", ".join(sorted(r.value for r in gate.policy.rules))
    failures = gate.failures
    if gate.vacuous:
        out.append(Text(f"Gate failed: no icon could be audited [{rules}]", style="bold red"))
    elif failures:
        out.append(Text(f"Gate failed: {len(failures)} root cause(s) [{rules}]", style="bold red"))
    else:
        out.append(Text(f"Gate passed [{rules}]", style="bold green"))
    for s in rule_summary(gate):
        parts = [f"{s.failing} failing ({s.icons} icon{'s' * (s.icons != 1)})"]
        parts += [
            f"{n} {what}"
            for n, what in (
                (s.reported, "reported, not gated"),
                (s.exempted, "exempted"),
                (s.baselined, "baselined"),
            )
            if n
        ]
        out.append(Text(f"  {s.rule.value}: {', '.join(parts)}", style="bold" if s.failing else ""))
    if failures:
        out += _listed(
            Text("Worst first:"), failures, _failure_line(base), "--format json or markdown"
        )
    exempt, baselined = gate.exempted, gate.baselined
    if exempt and exempt[0].exemption is not None:
        reason = exempt[0].exemption.reason
        out.append(Text(f"  {len(exempt)} exempted root cause(s), e.g. {reason}"))
    if baselined:
        out.append(Text(f"  {len(baselined)} root cause(s) {baselined_text(gate)}"))
    # Unrenderable icons are listed with their audit; the other warnings here.
    notes = [f for f in gate.warnings if f.rule is not Rule.UNRENDERABLE]
    if notes:
        out += _listed(
            Text(f"Notes ({len(notes)}), reported without failing the gate:"),
            notes,
            lambda f: safe_text(f"  {f.rule.value}: {where_text(f)}: {f.message}"),
        )
    if gate.stale:
        rewrite = "" if gate.on_base else "; rewrite the baseline with --write-baseline"
        out.append(Text(f"  {stale_text(gate)}{rewrite}", style="yellow"))
    return Group(*out)


def _failure_line(base: Path | None) -> Callable[[Finding], str]:
    def line(f: Finding) -> str:
        at = f" [{location_text(f.locations[0], base)}]" if f.locations else ""
        return safe_text(f"  {f.rule.value}: {where_text(f)} ({f.theme}){at}: {f.message}")

    return line


def fixes_renderable(report: CheckReport) -> RenderableType | None:
    """How to fix the failures: each distinct fix once, in the failures' order.

    The same texts as the pull-request comment (:func:`~alpha_audit.render.common.finding_fix`).
    """
    failures = report.gate.failures
    if not failures:
        return None
    seen: dict[str, None] = {}
    for f in failures:
        text = finding_fix(f, report)
        if text:
            seen.setdefault(text)
        if len(seen) >= MAX_FINDINGS:
            break
    if not seen:
        return None
    # Indented as a block, so a fix wrapped at the terminal's width stays under its start.
    return Group(Text("How to fix:"), *(Padding(Text(t), (0, 0, 0, 2)) for t in seen))


def render_report(report: CheckReport, options: RenderOptions) -> str:
    """The gate, every audit of the report, then how to fix it, at ``options.width``.

    A report whose rows a browser drew is shown as its pages
    (:func:`~alpha_audit.render.pages.page_table`).
    """
    if report.pages is not None:
        from alpha_audit.render.pages import page_table

        return page_table(report, report.pages, options)
    # The verdict and the worst root causes lead; each audit's figures follow.
    parts: list[RenderableType] = [gate_renderable(report.gate, options.base), Text("")]
    for result in report.audits:
        parts += [check_renderable(result, options.base), Text("")]
    if report.gamut:
        parts += [gamut_renderable(report, options), Text("")]
    fixes = fixes_renderable(report)
    if fixes is not None:
        parts.append(fixes)
    return to_text(Group(*parts), options)


def gamut_renderable(report: CheckReport, options: RenderOptions) -> RenderableType:
    """Colours outside sRGB that the gamut policy moved: one line per colour."""
    notes = report.gamut
    return Group(
        *_listed(
            Text(f"Colours outside sRGB ({len(notes)}), fitted by the gamut policy", style="bold"),
            notes,
            lambda n: f"  {safe_text(gamut_line(n, options.base))}",
        )
    )
