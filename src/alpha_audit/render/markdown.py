"""Markdown: a summary fit for a pull-request comment or a CI step summary.

Every name that reaches a table cell comes from files a pull request can
change, so it is escaped: Markdown and HTML punctuation, pipes, line breaks
and ``@`` (which would mention someone).
"""

from __future__ import annotations

from alpha_audit.gate import CheckReport, Finding
from alpha_audit.render.common import RenderOptions, escape_markdown

__all__ = ["MAX_ROWS", "render_report"]

MAX_ROWS = 100  # failures listed in full; the JSON and SARIF reports have every one


def _numbers(f: Finding) -> str:
    n = f.numbers
    if "contrast" in n:
        return (
            f"{n['contrast_ref']:.3f} → {n['contrast']:.3f} ({n['gain']:+.4f}) at α={n['alpha']:g}"
        )
    if "delta_e" in n:
        return f"ΔE00 {n['delta_e']:.2f} (α=1: {n['delta_e_ref']:.2f}) < {n['min_delta_e']:g}"
    if "output" in n:
        return f"{n['sources']} → {n['output']}"
    return f.message


def _row(f: Finding, extra: str = "") -> str:
    cells = [f.rule.value, ", ".join(f.icons), f.canvas or "", f.theme, _numbers(f)]
    if extra:
        cells.append(extra)
    return "| " + " | ".join(escape_markdown(c) for c in cells) + " |"


def render_report(report: CheckReport, options: RenderOptions) -> str:
    """Verdict, per-audit summary table, failures, exemptions and baseline news."""
    gate = report.gate
    rules = ", ".join(f"`{r}`" for r in sorted(r.value for r in gate.policy.rules))
    lines: list[str] = []
    if gate.passed:
        lines.append("## alpha-audit: ✅ gate passed")
    else:
        counts = ", ".join(f"{n} {escape_markdown(rule)}" for rule, n in gate.counts().items())
        lines.append(f"## alpha-audit: ❌ gate failed ({counts})")
    lines += ["", f"Rules: {rules}; max loss {gate.policy.max_loss:g}.", ""]
    lines += [
        "| theme | icon set | icons | α | mean gain | losses | newly failing | collisions "
        "| unrendered |",
        "|---|---|--:|--:|--:|--:|--:|--:|--:|",
    ]
    for r in report.audits:
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
            f"{s.mean_gain:+.3f}",
            str(s.losses),
            str(s.newly_fail),
            f"{s.collisions} ({s.new_collisions} new)",
            str(len(r.problems)),
        ]
        lines.append("| " + " | ".join(cells) + " |")
    failures = gate.failures
    if failures:
        lines += [
            "",
            "### Failures",
            "",
            "| rule | icon | canvas | theme | numbers |",
            "|---|---|---|---|---|",
        ]
        lines += [_row(f) for f in failures[:MAX_ROWS]]
        if len(failures) > MAX_ROWS:
            lines.append(f"\n… and {len(failures) - MAX_ROWS} more; see the JSON or SARIF report.")
    exempt = gate.exempted
    if exempt:
        lines += ["", "<details><summary>Exempted findings</summary>", ""]
        lines += [
            "| rule | icon | canvas | theme | numbers | reason |",
            "|---|---|---|---|---|---|",
        ]
        lines += [_row(f, f.exemption.reason) for f in exempt[:MAX_ROWS] if f.exemption]
        lines += ["", "</details>"]
    baselined = len(gate.baselined)
    if baselined or gate.stale:
        lines += [
            "",
            f"{baselined} finding(s) already in the baseline; "
            f"{len(gate.stale)} baseline "
            f"{'entry no longer occurs' if len(gate.stale) == 1 else 'entries no longer occur'}.",
        ]
    if gate.warnings:
        lines += ["", "### Icons that could not be rendered", ""]
        for w in gate.warnings:
            lines.append(f"- {escape_markdown(', '.join(w.icons))}: {escape_markdown(w.message)}")
    return "\n".join(lines) + "\n"
