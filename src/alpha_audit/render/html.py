"""A report as one self-contained HTML file; a page run's with crops of its icons.

``alpha-audit render -f html -o render.html``: the verdict, the story x state
matrix (:func:`~alpha_audit.render.pages.state_matrix_cells`, the comment's
own), then each failing finding and, in a second section, each reported one:
story or page, state, icon, the pair that limits (drawn colour and backdrop as
swatches) and its contrast against the threshold, the model's prediction, the
fix the other formats give (:func:`~alpha_audit.render.common.finding_fix`),
where to change it, and the icon twice, side by side, as drawn and with the
icons hidden (:class:`~alpha_audit.observed.IconCrop`), enlarged without
smoothing so each device pixel shows.  ``check -f html`` writes the same page
without the matrix and the crops.

The file runs nothing and loads nothing: no script, images as ``data:`` URIs,
and a Content-Security-Policy that forbids anything else, so a story's name
holding markup stays text (every input string goes through
:func:`~alpha_audit.render.common.escape_html`) and the report can be opened
from a CI artifact safely.
"""

from __future__ import annotations

import base64
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path

from alpha_audit.figures import ContrastFigures, RenderDriftFigures
from alpha_audit.findings import Finding
from alpha_audit.observed import IconCrop, MeasuredPaint, PageRun
from alpha_audit.render.common import (
    RenderOptions,
    baselined_text,
    escape_html,
    finding_fix,
    location_text,
)
from alpha_audit.render.pages import headline, state_matrix_cells, summary_notes
from alpha_audit.results import CheckReport

__all__ = ["CSP", "render_report"]

# Nothing but inline style and data: images (CSP Level 3, 'default-src' the fallback of
# every fetch directive): the report must not load or run anything, whatever it quotes.
CSP = "default-src 'none'; img-src data:; style-src 'unsafe-inline'"
_SHOWN = 192  # CSS px a crop is enlarged towards (in whole multiples, at most 8x)
_HEX = re.compile(r"#[0-9a-fA-F]{6}")

_STYLE = """
body { font: 14px/1.45 system-ui, sans-serif; margin: 2em auto; max-width: 1100px;
  padding: 0 1em; color: #1f2328; background: #fff; }
h1 { font-size: 1.4em; } h2 { font-size: 1.15em; margin-top: 2em; }
h1.fail { color: #b3261e; } h1.pass { color: #1a7f37; }
code { font: 0.92em ui-monospace, monospace; overflow-wrap: anywhere; }
table.matrix { border-collapse: collapse; }
table.matrix th, table.matrix td { border: 1px solid #d0d7de; padding: 0.25em 0.6em;
  text-align: left; }
td.fail { background: #ffebe9; font-weight: 600; } td.pass { color: #1a7f37; }
td.none { color: #656d76; }
article { border: 1px solid #d0d7de; border-radius: 6px; padding: 0.8em 1em;
  margin: 1em 0; display: flex; gap: 1.5em; flex-wrap: wrap; }
article.fail { border-left: 6px solid #cf222e; }
article.reported { border-left: 6px solid #bf8700; }
article h3 { flex-basis: 100%; margin: 0; font-size: 1.05em; }
article p.message { flex-basis: 100%; margin: 0; }
figure { margin: 0; display: flex; gap: 0.8em; align-items: flex-start; }
figure div { text-align: center; font-size: 0.85em; color: #656d76; }
figure img { display: block; image-rendering: pixelated; image-rendering: crisp-edges;
  border: 1px solid #d0d7de; }
p.size { font-size: 0.8em; color: #656d76; margin: 0.3em 0 0; }
dl { display: grid; grid-template-columns: max-content 1fr; gap: 0.2em 1em; margin: 0;
  flex: 1; min-width: 320px; }
dt { color: #656d76; } dd { margin: 0; }
.swatch { display: inline-block; width: 1.1em; height: 1.1em; vertical-align: -0.2em;
  border: 1px solid #8c959f; margin-right: 0.3em; }
.nocrop { color: #656d76; font-style: italic; max-width: 14em; }
footer { margin-top: 2em; color: #656d76; font-size: 0.9em; }
"""


def _e(text: object) -> str:
    return escape_html(text)


def _swatch(color: object) -> str:
    """A colour as a swatch and its hex; only a measured ``#rrggbb`` reaches the style."""
    if not isinstance(color, str):
        return "—"
    if _HEX.fullmatch(color) is None:
        return f"<code>{_e(color)}</code>"
    return f'<span class="swatch" style="background:{color}"></span><code>{color}</code>'


def _ratio(value: object) -> str:
    return f"{value:.2f}:1" if isinstance(value, float) else "—"


def _matrix(report: CheckReport, run: PageRun) -> list[str]:
    states, rows = state_matrix_cells(report, run)
    out = ['<table class="matrix">', "<tr><th>story or page</th>"]
    out[-1] += "".join(f"<th>{_e(s)}</th>" for s in states) + "</tr>"
    for source, cells in rows:
        shown = []
        for cell in cells:
            if isinstance(cell, str):
                shown.append(f'<td class="none">{_e(cell)}</td>')
            elif cell:
                shown.append(f'<td class="fail">{cell} failing</td>')
            else:
                shown.append('<td class="pass">pass</td>')
        out.append(f"<tr><th>{_e(source)}</th>{''.join(shown)}</tr>")
    out.append("</table>")
    return out


def _image(png: bytes, width: int, height: int, zoom: int, alt: str) -> str:
    data = base64.b64encode(png).decode("ascii")
    return (
        f'<img src="data:image/png;base64,{data}" width="{width * zoom}" '
        f'height="{height * zoom}" alt="{_e(alt)}">'
    )


def _figure(crop: IconCrop | None, icon: str, left_out: int) -> str:
    if crop is None:
        why = "no crop kept"
        if left_out:
            why += f": the run reached its limit of crops ({left_out} left out)"
        return f'<p class="nocrop">{why}</p>'
    zoom = max(1, min(8, _SHOWN // max(crop.width, crop.height)))
    size = f"{crop.width * crop.step} × {crop.height * crop.step} device px (scale {crop.scale})"
    if crop.step > 1:
        size += f", 1 in {crop.step} pixels per row and column"
    size += f", shown {zoom}×"
    drawn = _image(crop.drawn, crop.width, crop.height, zoom, f"{icon} as drawn")
    hidden = _image(crop.hidden, crop.width, crop.height, zoom, f"{icon}: the backdrop")
    return (
        "<div><figure>"
        f"<div>{drawn}as drawn</div>"
        f"<div>{hidden}backdrop (icons hidden)</div>"
        f'</figure><p class="size">{size}</p></div>'
    )


def _model(o: MeasuredPaint) -> str:
    near = o.nearer
    if near is None:
        return "—"
    source = "?" if o.model_source is None else o.model_source
    alpha = 1.0 if o.model_alpha is None else o.model_alpha
    given = f"<code>{_e(source)}</code> at alpha {alpha:g}"
    if o.model_opacity is not None and o.model_opacity != 1.0:
        given += f", opacity {o.model_opacity:g}"
    drift = o.render_drift
    drift_text = "" if drift is None else f"; CIEDE2000 {drift:.1f} from the drawn colour"
    return (
        f"{given} → {_swatch(near.output)} ({_e(near.pipeline)}): "
        f"contrast {_ratio(near.contrast)}{drift_text}"
    )


@dataclass(frozen=True)
class _Lookups:
    """What every finding's entry reads, built once per report."""

    report: CheckReport
    crops: Mapping[tuple[str, str, str, str], IconCrop]
    crops_left_out: int
    base: Path | None

    @classmethod
    def of(cls, report: CheckReport, options: RenderOptions) -> _Lookups:
        run = report.pages
        crops = {c.key: c for c in run.crops} if run is not None else {}
        return cls(report, crops, run.crops_left_out if run else 0, options.base)


def _page_rows(f: Finding, o: MeasuredPaint) -> list[tuple[str, str]]:
    """Where a page's finding was drawn: story or page, state and engine, icon, DOM path."""
    icon = f.icons[0] if f.icons else ""
    return [
        ("story" if o.source_kind == "storybook" else "page", f"<code>{_e(f.iconset)}</code>"),
        ("state", f"<code>{_e(f.theme)}</code> ({_e(o.engine)})"),
        ("icon", f"<code>{_e(icon)}</code> ({_e(o.element)}, {_e(str(o.match))})"),
        ("DOM path", f"<code>{_e(o.dom_path)}</code>"),
    ]


def _figure_rows(f: Finding, o: MeasuredPaint | None) -> list[tuple[str, str]]:
    """The contrast judged, and for a page's finding what was drawn on what, and the model."""
    fig = f.figures
    rows: list[tuple[str, str]] = []
    if isinstance(fig, ContrastFigures):
        contrast = f"{_ratio(fig.contrast)}; threshold {fig.threshold:g}:1"
        if o is not None:
            contrast += (
                f" (the paint's own colour; its pixels with antialiased edges: worst "
                f"{_ratio(o.contrast_worst)}, median {_ratio(o.contrast_median)})"
            )
        rows.append(("contrast", contrast))
    if o is not None and isinstance(fig, ContrastFigures | RenderDriftFigures):
        backdrop = _swatch(fig.background) + " behind"
        if o.around is not None and o.around != fig.background:
            backdrop += f", {_swatch(o.around)} around"
        rows += [("drawn", _swatch(o.drawn)), ("backdrop", backdrop), ("model", _model(o))]
    elif f.canvas:
        rows.append(("canvas", f"<code>{_e(f.canvas)}</code>"))
    return rows


def _finding(f: Finding, kind: str, look: _Lookups) -> list[str]:
    """One finding: heading, message, the two crops (a page's) and its figures."""
    o = f.observed
    icon = f.icons[0] if f.icons else ""
    where = "<br>".join(
        f"<code>{_e(location_text(loc, look.base))}</code> ({_e(loc.what)})" for loc in f.locations
    )
    if o is not None:
        rows = _page_rows(f, o)
    else:
        rows = [
            ("theme", f"<code>{_e(f.theme)}</code>"),
            ("icon set", f"<code>{_e(f.iconset)}</code>"),
            ("icons", ", ".join(f"<code>{_e(i)}</code>" for i in f.icons[:12])),
        ]
    rows += _figure_rows(f, o)
    rows += [("fix", _e(finding_fix(f, look.report))), ("where", where or "—")]
    out = [
        f'<article class="{kind}">',
        f"<h3><code>{_e(icon)}</code> in <code>{_e(f.iconset)}</code> "
        f"[<code>{_e(f.theme)}</code>]: {_e(f.rule.value)}</h3>",
        f'<p class="message">{_e(f.message)}</p>',
    ]
    if o is not None:
        key = (f.iconset, f.theme, o.engine, o.dom_path)
        out.append(_figure(look.crops.get(key), icon, look.crops_left_out))
    out += ["<dl>" + "".join(f"<dt>{_e(k)}</dt><dd>{v}</dd>" for k, v in rows) + "</dl>"]
    return [*out, "</article>"]


def _section(title: str, kind: str, findings: Sequence[Finding], look: _Lookups) -> list[str]:
    if not findings:
        return []
    out = [f"<h2>{title} ({len(findings)})</h2>"]
    for f in findings:
        out += _finding(f, kind, look)
    return out


def _check_headline(report: CheckReport) -> str:
    gate = report.gate
    if gate.passed:
        return f"gate passed ({len(report.audits)} audit(s))"
    return f"gate failed: {len(gate.failures)} root cause(s)"


def render_report(report: CheckReport, options: RenderOptions) -> str:
    """The report as one HTML page that runs no script and loads nothing (crops inline)."""
    gate, run = report.gate, report.pages
    if run is not None:
        title = f"alpha-audit render: {headline(report, run)}"
        notes = summary_notes(report, run)
    else:
        title = f"alpha-audit check: {_check_headline(report)}"
        notes = [f"{len(gate.baselined)} {baselined_text(gate)}"] if gate.baselined else []
    lines = [
        "<!DOCTYPE html>",
        '<html lang="en">',
        "<head>",
        '<meta charset="utf-8">',
        f'<meta http-equiv="Content-Security-Policy" content="{CSP}">',
        '<meta name="referrer" content="no-referrer">',
        '<meta name="viewport" content="width=device-width, initial-scale=1">',
        f"<title>{_e(title)}</title>",
        f"<style>{_STYLE}</style>",
        "</head>",
        "<body>",
        f'<h1 class="{"pass" if gate.passed else "fail"}">{_e(title)}</h1>',
    ]
    if notes:
        said = "; ".join(notes)
        lines.append(f"<p>{_e(said[:1].upper() + said[1:])}.</p>")
    if run is not None:
        lines += ["<h2>Stories and pages by state</h2>", *_matrix(report, run)]
    look = _Lookups.of(report, options)
    lines += _section("Failing", "fail", gate.failures, look)
    lines += _section("Reported", "reported", gate.warnings, look)
    if run is None:
        return "\n".join([*lines, "</body>", "</html>"]) + "\n"
    if run.problems:
        lines.append(f"<h2>Not audited ({len(run.problems)})</h2><ul>")
        lines += [
            f"<li><code>{_e(q.source)}</code> [<code>{_e(q.state)}</code>, {_e(q.engine)}]: "
            f"{_e(q.message)}</li>"
            for q in run.problems
        ]
        lines.append("</ul>")
    footer = [
        f"{run.audited} page states, {run.icons} icons, {run.paints} paints",
        f"{len(run.blocked)} requests blocked",
        "engines: " + (", ".join(f"{n} {v}" for n, v in run.engines) or "none"),
        f"{len(run.crops)} crops",
    ]
    if run.crops_left_out:
        footer[-1] += f" ({run.crops_left_out} more not kept: a run keeps a bounded number)"
    lines += [f"<footer>{_e('; '.join(footer))}.</footer>", "</body>", "</html>"]
    return "\n".join(lines) + "\n"
