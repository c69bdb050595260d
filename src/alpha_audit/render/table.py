"""Terminal report for ``check``: a per-canvas summary and the findings that matter.

Built with rich and rendered to a string of a given width, so it is a pure
function of the result; the CLI decides width and colour.
"""

from __future__ import annotations

from io import StringIO

from rich import box
from rich.console import Console, Group, RenderableType
from rich.table import Table
from rich.text import Text

from alpha_audit.audit import AuditResult
from alpha_audit.gate import CheckReport, GateResult
from alpha_audit.render import RenderOptions, as_report

__all__ = ["MAX_FINDINGS", "check_renderable", "gate_renderable", "render_check", "render_report"]

MAX_FINDINGS = 12  # per section; the JSON has everything


def _fmt_alpha(result: AuditResult) -> str:
    alphas = sorted({float(a) for a in result.alpha})
    if len(alphas) == 1:
        return f"{alphas[0]:g}"
    return f"{alphas[0]:g}..{alphas[-1]:g}"


def _summary_table(result: AuditResult) -> Table:
    t = result.threshold
    table = Table(box=box.SIMPLE_HEAD, pad_edge=False, collapse_padding=True, header_style="bold")
    table.add_column("canvas", no_wrap=True, max_width=20, overflow="ellipsis")
    for name in ("bg", "gain", f"≥{t:g}:1", "new", "loss", "coll", "min ΔE"):
        table.add_column(name, justify="left" if name == "bg" else "right", no_wrap=True)
    for cs in result.canvas_summaries():
        passing = f"{cs.passing_ref}→{cs.passing}/{cs.icons}"
        loss = Text(f"{cs.losses} (-{cs.max_loss:.2f})", style="red") if cs.losses else Text("0")
        coll = Text(str(cs.collisions), style="red") if cs.collisions else Text("0")
        sep = cs.separation
        de = "-" if sep is None else f"{sep.delta_e_ref:.1f}→{sep.delta_e:.1f}"
        table.add_row(
            cs.canvas,
            Text(cs.background, style=f"on {cs.background}"),
            Text(f"{cs.mean_gain:+.2f}", style="green" if cs.mean_gain > 0 else "red"),
            passing,
            Text(str(cs.newly_pass), style="green") if cs.newly_pass else "0",
            loss,
            coll,
            de,
        )
    return table


def _findings(result: AuditResult) -> list[RenderableType]:
    out: list[RenderableType] = []
    rows = list(result.rows())

    def section(title: str, items: list[str], style: str) -> None:
        if not items:
            return
        out.append(Text(f"{title} ({len(items)})", style=f"bold {style}"))
        for line in items[:MAX_FINDINGS]:
            out.append(Text(f"  {line}"))
        if len(items) > MAX_FINDINGS:
            out.append(Text(f"  … and {len(items) - MAX_FINDINGS} more (see --format json)"))

    losses = sorted((r for r in rows if r.loss), key=lambda r: r.gain)
    section(
        "Contrast losses",
        [
            f"{r.icon} on {r.canvas}: {r.contrast_ref:.3f} → {r.contrast:.3f} "
            f"({r.gain:+.4f}) at α={r.alpha:g}"
            for r in losses
        ],
        "red",
    )
    section(
        f"Newly below {result.threshold:g}:1",
        [
            f"{r.icon} on {r.canvas}: {r.contrast_ref:.3f} → {r.contrast:.3f}"
            for r in rows
            if r.newly_fails
        ],
        "red",
    )
    section(
        "Collisions (distinct colours, same 8-bit output)",
        [
            f"{c.canvas}: {', '.join(c.sources)} → {c.output} "
            f"({', '.join(c.icons)}){'' if c.new else ' [already at α=1]'}"
            for c in result.collisions
        ],
        "red",
    )
    section(
        f"Newly reach {result.threshold:g}:1",
        [
            f"{r.icon} on {r.canvas}: {r.contrast_ref:.3f} → {r.contrast:.3f}"
            for r in rows
            if r.newly_passes
        ],
        "green",
    )
    still = [r for r in rows if not r.passes]
    section(
        f"Still below {result.threshold:g}:1 at α",
        [
            f"{r.icon} on {r.canvas}: {r.contrast:.3f}"
            for r in sorted(still, key=lambda r: r.contrast)
        ],
        "yellow",
    )
    section(
        "Icons that could not be rendered",
        [f"{p.icon} ({p.file}): {p.message}" for p in result.problems],
        "yellow",
    )
    return out


def check_renderable(result: AuditResult) -> RenderableType:
    """The whole report as one rich renderable."""
    s = result.summary
    theme, iconset = result.theme, result.iconset
    head = Text.assemble(
        ("alpha-audit check", "bold"),
        f"  {iconset.name} ({len(iconset.icons)} icons) on {theme.name} "
        f"({len(theme.canvases)} canvases), α={_fmt_alpha(result)}",
    )
    foot = Text(
        f"{s.combinations} icon×canvas: contrast up {s.increase_pct:.1f}%, "
        f"down {s.decrease_pct:.1f}%, mean {s.mean_gain:+.3f}; "
        f"{s.newly_pass} newly reach {result.threshold:g}:1, {s.newly_fail} newly fail; "
        f"{s.losses} losses (max {s.max_loss:.4f}); {s.collisions} collisions "
        f"({s.new_collisions} new)",
        style="bold",
    )
    return Group(head, _summary_table(result), *_findings(result), Text(""), foot)


def gate_renderable(gate: GateResult) -> RenderableType:
    """The gate verdict: failures with rule, icon, canvas and numbers; exemptions; baseline."""
    out: list[RenderableType] = []
    rules = ", ".join(sorted(r.value for r in gate.policy.rules))
    failures = gate.failures
    if failures:
        out.append(Text(f"Gate failed: {len(failures)} finding(s) [{rules}]", style="bold red"))
        for f in failures[:MAX_FINDINGS]:
            where = f"{', '.join(f.icons)} on {f.canvas}" if f.canvas else ", ".join(f.icons)
            out.append(Text(f"  {f.rule.value}: {where} ({f.theme}): {f.message}"))
        if len(failures) > MAX_FINDINGS:
            more = len(failures) - MAX_FINDINGS
            out.append(Text(f"  … and {more} more (see --format json or markdown)"))
    else:
        out.append(Text(f"Gate passed [{rules}]", style="bold green"))
    exempt = [f for f in gate.findings if f.exemption is not None]
    baselined = [f for f in gate.findings if f.baselined and f.exemption is None]
    if exempt:
        out.append(Text(f"  {len(exempt)} exempted finding(s), e.g. {exempt[0].exemption.reason}"))
    if baselined:
        out.append(Text(f"  {len(baselined)} finding(s) already in the baseline"))
    if gate.stale:
        out.append(
            Text(
                f"  {len(gate.stale)} baseline entr{'y' if len(gate.stale) == 1 else 'ies'} "
                "no longer occur; rewrite the baseline with --write-baseline",
                style="yellow",
            )
        )
    return Group(*out)


def render_report(report: CheckReport, options: RenderOptions) -> str:
    """Every audit of the report, then the gate, at ``options.width`` columns."""
    parts: list[RenderableType] = []
    for result in report.audits:
        parts += [check_renderable(result), Text("")]
    parts.append(gate_renderable(report.gate))
    return to_text(Group(*parts), options)


def render_check(result: AuditResult | CheckReport, options: RenderOptions) -> str:
    """Render one audit (gated by the default policy) or a whole report."""
    return render_report(as_report(result), options)


def to_text(renderable: RenderableType, options: RenderOptions) -> str:
    """Render at ``options.width`` columns, with or without ANSI colour."""
    buffer = StringIO()
    console = Console(
        file=buffer,
        width=options.width,
        color_system="truecolor" if options.color else None,
        force_terminal=options.color,
        no_color=not options.color,
        highlight=False,
        emoji=False,
    )
    console.print(renderable)
    return buffer.getvalue()
