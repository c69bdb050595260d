"""Renderers of a :class:`~alpha_audit.reproduce.run.Reproduction`: table, JSON and Markdown.

Pure functions of the result: no printing, no clock, stable order.  The rich
tables fit 80 columns and never cut a number.  The JSON
schema ``alpha-audit.reproduce/1`` is documented in ``docs/reproduce.md``;
numbers are unrounded.  The Markdown report puts the paper's printed values
beside ours and says, per value, whether it is comparable in digits and
whether ours matches to every printed digit.
"""

from __future__ import annotations

from importlib.metadata import PackageNotFoundError, version
from typing import Any

from rich import box
from rich.console import Group
from rich.table import Table
from rich.text import Text

from alpha_audit.render.common import RenderOptions, dumps, escape_markdown, to_text
from alpha_audit.reproduce.experiments import ContrastChange
from alpha_audit.reproduce.paper import (
    PAPER,
    WORST_BACKGROUND,
    WORST_SOURCE,
    PaperValue,
    matches_printed,
)
from alpha_audit.reproduce.report_browser import (
    browser_json,
    browser_markdown,
    browser_tables,
    runtime_json,
    runtime_markdown,
)
from alpha_audit.reproduce.run import Reproduction

__all__ = [
    "SCHEMA",
    "alpha_key",
    "render_json",
    "render_markdown",
    "render_table",
    "tables",
    "to_json_dict",
]

SCHEMA = "alpha-audit.reproduce/1"


def alpha_key(alpha: float) -> str:
    """JSON key of a coefficient: ``str(float)``, e.g. ``"1.1"``, ``"1.0"``.

    >>> alpha_key(1.1), alpha_key(1)
    ('1.1', '1.0')
    """
    return str(float(alpha))


def _tool_version() -> str:
    try:
        return version("alpha-audit")
    except PackageNotFoundError:  # running from a source tree without metadata
        return "unknown"


def _change(change: ContrastChange | None) -> dict[str, Any] | None:
    return None if change is None else change.as_dict()


def to_json_dict(run: Reproduction) -> dict[str, Any]:
    """The ``alpha-audit.reproduce/1`` document as plain Python data."""
    theme = run.theme
    doc: dict[str, Any] = {
        "schema": SCHEMA,
        "tool": {"name": "alpha-audit", "version": _tool_version()},
        "quick": run.quick,
        "alphas": list(run.alphas),
        "theme": {
            "name": theme.name,
            "path": None if theme.path is None else str(theme.path),
            "threshold": theme.threshold,
            "canvases": [
                {"name": c.name, "color": c.color, "mode": c.mode} for c in theme.canvases
            ],
        },
    }
    if run.broad_grid is not None:
        first = run.broad_grid[0]
        section: dict[str, Any] = {
            "source_levels": first.source_levels,
            "background_levels": first.background_levels,
            "combinations": first.combinations,
        }
        for r in run.broad_grid:
            section[alpha_key(r.alpha)] = {
                "increase": r.increase,
                "decrease": r.decrease,
                "unchanged": r.unchanged,
                "loss_le_0_25": r.loss_le_0_25,
                "increase_pct": r.increase_pct,
                "decrease_pct": r.decrease_pct,
                "max_loss": r.max_loss,
                "loss_le_0_25_pct": r.loss_le_0_25_pct,
                "worst": {
                    "source": list(r.worst_source),
                    "background": list(r.worst_background),
                    "contrast": {alpha_key(a): cr for a, cr in r.worst_contrast.items()},
                },
            }
        doc["broad_grid"] = section
    if run.full_gamut is not None:
        first_fg = run.full_gamut[0]
        fg: dict[str, Any] = {"levels": first_fg.levels, "threshold": first_fg.threshold}
        for g in run.full_gamut:
            fg[alpha_key(g.alpha)] = {
                "all": _change(g.total),
                "light": _change(g.group("light")),
                "dark": _change(g.group("dark")),
                "canvases": [
                    {"name": c.name, "color": c.color, "mode": c.mode} | c.change.as_dict()
                    for c in g.canvases
                ],
            }
        doc["full_gamut"] = fg
    if run.sweep is not None:
        s = run.sweep
        doc["sweep"] = {
            "levels": s.levels,
            "pairs": s.pairs,
            "seed": s.seed,
            "alphas": list(s.alphas),
            "mean_change": {k: list(v) for k, v in s.mean_change.items()},
            "decrease_share": {k: list(v) for k, v in s.decrease_share.items()},
            "collision_rate": {k: list(v) for k, v in s.collision_rate.items()},
        }
    if run.palette is not None:
        p = run.palette
        pal: dict[str, Any] = {"palette": list(p.palette), "combinations": p.combinations}
        for a in p.alphas:
            pal[alpha_key(a)] = {
                "smaller": p.smaller[a],
                "collisions": p.collisions[a],
                "smaller_per_canvas": list(p.smaller_per_canvas[a]),
                "collisions_per_canvas": list(p.collisions_per_canvas[a]),
            }
        pal["random"] = {
            "pairs": p.random_pairs,
            "seed": p.seed,
            "combinations": p.random_combinations,
            "collisions": {alpha_key(a): n for a, n in p.random_collisions.items()},
        }
        doc["palette"] = pal
    if run.browser is not None:
        doc["browser"] = browser_json(run.browser)
    if run.runtime is not None:
        doc["runtime"] = runtime_json(run.runtime)
    doc["paper"] = {
        experiment: {
            group: {
                name: {
                    "value": v.value,
                    "decimals": v.decimals,
                    "comparable": v.comparable,
                    "where": v.where,
                }
                for name, v in values.items()
            }
            for group, values in groups.items()
        }
        for experiment, groups in PAPER.items()
    }
    return doc


def render_json(run: Reproduction, options: RenderOptions | None = None) -> str:
    """``to_json_dict`` as JSON text (``options`` change nothing)."""
    return dumps(to_json_dict(run))


# --------------------------------------------------------------------------- Markdown


def _fmt(value: float, decimals: int) -> str:
    return f"{value:z,.{decimals}f}"


def _row(label: str, ours: float | None, printed: PaperValue | None, decimals: int = 4) -> str:
    if printed is None:
        shown = "—" if ours is None else _fmt(ours, decimals)
        return f"| {label} | — | {shown} | no printed value | — |"
    d = printed.decimals
    if ours is None:
        return f"| {label} | {_fmt(printed.value, d)} | — | — | — |"
    if printed.comparable:
        verdict = "**yes**" if matches_printed(ours, printed) else "**NO**"
        comparable = f"yes ({printed.where})"
    else:
        verdict = "n/a"
        comparable = f"method only ({printed.where})"
    shown = _fmt(ours, max(d, 4) if d else 0)  # counts stay integers
    return f"| {label} | {_fmt(printed.value, d)} | {shown} | {comparable} | {verdict} |"


_HEADER = [
    "| Quantity | Paper | Ours | Comparable in digits? | Matches every printed digit? |",
    "|---|---:|---:|---|---|",
]


def _broad_section(run: Reproduction) -> list[str]:
    assert run.broad_grid is not None
    first = run.broad_grid[0]
    lines = [
        "## Broad grid (Table 1, Section 4.2)",
        "",
        f"{first.source_levels}^3 sources x {first.background_levels}^3 backgrounds, uniform in "
        f"encoded sRGB with endpoints; {first.combinations:,} combinations per alpha.  Depends on "
        "nothing the paper leaves out: comparable to every printed digit at the paper's grid "
        "sizes.",
        "",
        *_HEADER,
    ]
    paper_grid = first.source_levels == 17 and first.background_levels == 33
    for r in run.broad_grid:
        key = alpha_key(r.alpha)
        printed = PAPER["broad_grid"].get(key, {}) if paper_grid else {}
        lines += [
            _row(f"alpha {key}: increase %", r.increase_pct, printed.get("increase_pct")),
            _row(f"alpha {key}: decrease %", r.decrease_pct, printed.get("decrease_pct")),
            _row(f"alpha {key}: maximum loss", r.max_loss, printed.get("max_loss")),
            _row(
                f"alpha {key}: decreases with loss <= 0.25, %",
                r.loss_le_0_25_pct,
                printed.get("loss_le_0_25_pct"),
            ),
            _row(
                f"alpha {key}: worst case, contrast at 1",
                r.worst_contrast[1.0],
                printed.get("worst_contrast_1.0"),
            ),
            _row(
                f"alpha {key}: worst case, contrast at {key}",
                r.worst_contrast[r.alpha],
                printed.get(f"worst_contrast_{key}"),
            ),
        ]
    lines.append("")
    for r in run.broad_grid:
        same = r.worst_source == WORST_SOURCE and r.worst_background == WORST_BACKGROUND
        verdict = (
            ("the same as" if same else "NOT the same as") if paper_grid else "on a grid unlike"
        )
        contrasts = " -> ".join(
            f"{cr:z.4f} (alpha {alpha_key(a)})" for a, cr in r.worst_contrast.items()
        )
        lines.append(
            f"- alpha {alpha_key(r.alpha)}: largest loss for source sRGB {r.worst_source} on "
            f"{r.worst_background}, {verdict} the paper's (0, 0, 0.8125) on (1, 1, 0); "
            f"contrast {contrasts}."
        )
    return [*lines, ""]


def _full_gamut_section(run: Reproduction) -> list[str]:
    assert run.full_gamut is not None
    first = run.full_gamut[0]
    lines = [
        "## Full gamut (Section 4.2, Table 1)",
        "",
        f"All {first.levels}^3 sources on the {len(first.canvases)} canvases of theme "
        f"{escape_markdown(first.theme)}.  The paper does not publish its sixteen canvases, so "
        "these figures are comparable in method only.",
        "",
        *_HEADER,
    ]
    for r in run.full_gamut:
        key = alpha_key(r.alpha)
        printed = PAPER["full_gamut"].get(key, {})
        t = r.total
        for label, name in (
            ("increase %", "increase_pct"),
            ("decrease %", "decrease_pct"),
            ("unchanged %", "unchanged_pct"),
            ("mean change", "mean_change"),
            (f"newly reach {r.threshold:g}:1, % of all", "newly_reach_pct"),
            ("Difference mean change", "mean_difference_change"),
            ("Exclusion mean change", "mean_exclusion_change"),
        ):
            lines.append(_row(f"alpha {key}: {label}", getattr(t, name), printed.get(name)))
    lines += ["", "Per canvas:", ""]
    lines += [
        "| alpha | canvas | mode | increase % | decrease % | unchanged % | mean change "
        "| newly reach % |",
        "|---|---|---|---:|---:|---:|---:|---:|",
    ]
    for r in run.full_gamut:
        rows: list[tuple[str, str, ContrastChange | None]] = [
            (escape_markdown(c.name), c.mode, c.change) for c in r.canvases
        ]
        rows += [(f"*{m} group*", m, r.group(m)) for m in ("light", "dark") if r.group(m)]
        for name, mode, c in rows:
            assert c is not None
            lines.append(
                f"| {alpha_key(r.alpha)} | {name} | {mode} | {c.increase_pct:z.4f} | "
                f"{c.decrease_pct:z.4f} | {c.unchanged_pct:z.4f} | {c.mean_change:z.4f} | "
                f"{c.newly_reach_pct:z.4f} |"
            )
    return [*lines, ""]


def _sweep_section(run: Reproduction) -> list[str]:
    assert run.sweep is not None
    s = run.sweep
    lines = [
        "## Coefficient sweep (Figures 3 and 6)",
        "",
        f"alpha in [{s.alphas[0]:g}, {s.alphas[-1]:g}] ({len(s.alphas)} values) on a {s.levels}^3 "
        f"source grid; collision rate over {s.pairs:,} distinct random 8-bit source pairs (seed "
        f"{s.seed}).  Light and dark groups each weight their canvases equally.  The paper prints "
        "no sweep values and does not publish its canvases or pair construction: figures only, "
        "comparable in shape, not in digits.  See `sweep-1-2.png` and `sweep-0-2.png`.",
        "",
        "| alpha | mean change light | mean change dark | decreases light | decreases dark | "
        "collisions light | collisions dark |",
        "|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for i, a in enumerate(s.alphas):
        if abs(a * 10 - round(a * 10)) > 1e-9:  # tabulate every 0.1, plot every point
            continue
        cells = [
            s.mean_change.get("light"),
            s.mean_change.get("dark"),
            s.decrease_share.get("light"),
            s.decrease_share.get("dark"),
            s.collision_rate.get("light"),
            s.collision_rate.get("dark"),
        ]
        shown = " | ".join("—" if c is None else f"{c[i]:z.4f}" for c in cells)
        lines.append(f"| {a:g} | {shown} |")
    return [*lines, ""]


def _palette_section(run: Reproduction) -> list[str]:
    assert run.palette is not None
    p = run.palette
    counts = PAPER["palette"]["counts"]
    lines = [
        "## Palette separation (Section 4.3)",
        "",
        f"All {len(p.palette) * (len(p.palette) - 1) // 2} pairs of "
        f"{escape_markdown(', '.join(p.palette))} on each "
        f"canvas ({p.combinations} combinations); {p.random_pairs:,} random pairs on each canvas "
        f"({p.random_combinations:,} combinations).  Counts of combinations are comparable; "
        "smaller-CIEDE2000 and collision counts depend on the unpublished canvases and pair "
        "construction and are comparable in method only.  The paper's random collisions "
        "(617 -> 15,098) are read as alpha 1.1 -> 1.4; at alpha 1.0 distinct 8-bit sources "
        "cannot collide.",
        "",
        *_HEADER,
        _row("palette combinations", p.combinations, counts["combinations"], 0),
        _row("random combinations", p.random_combinations, counts["random_combinations"], 0),
    ]
    for a in p.alphas:
        key = alpha_key(a)
        printed = PAPER["palette"].get(key, {})
        lines += [
            _row(f"alpha {key}: smaller CIEDE2000", p.smaller[a], printed.get("smaller"), 0),
            _row(f"alpha {key}: collisions", p.collisions[a], printed.get("collisions"), 0),
        ]
    for a in p.random_alphas:
        key = alpha_key(a)
        printed = PAPER["palette"].get(key, {})
        lines.append(
            _row(
                f"alpha {key}: random-pair collisions",
                p.random_collisions[a],
                printed.get("random_collisions"),
                0,
            )
        )
    return [*lines, ""]


def render_markdown(run: Reproduction, options: RenderOptions | None = None) -> str:
    """The report: per experiment, the paper's printed values beside ours.

    Theme and canvas names come from input files: escaped like every Markdown
    report (:func:`~alpha_audit.render.common.escape_markdown`).
    """
    lines = [
        "# alpha-audit reproduce: Opacity Is Not Just Opacity, Section 4",
        "",
        f"Theme {escape_markdown(run.theme.name)} ({len(run.theme.canvases)} canvases); "
        f"alphas {', '.join(alpha_key(a) for a in run.alphas)}"
        + (
            "; **quick grids** (not the paper's sizes)."
            if run.quick
            else "; the paper's grid sizes."
        ),
        "",
        "'Comparable in digits' marks values that depend only on what the paper specifies; "
        "for those, 'Matches' says whether ours rounds to the printed value.  Other values are "
        "shown for comparison of method and magnitude, never as a match.",
        "",
    ]
    if run.broad_grid is not None:
        lines += _broad_section(run)
    if run.full_gamut is not None:
        lines += _full_gamut_section(run)
    if run.sweep is not None:
        lines += _sweep_section(run)
    if run.palette is not None:
        lines += _palette_section(run)
    if run.browser is not None:
        lines += browser_markdown(run.browser)
    if run.runtime is not None:
        lines += runtime_markdown(run.runtime)
    return "\n".join(lines).rstrip() + "\n"


# --------------------------------------------------------------------------- tables


def _table(title: str) -> Table:
    """A compact table that fits 80 columns: numbers are never cut or wrapped."""
    return Table(
        title=Text(title),  # theme names come from input files: never rich markup
        title_justify="left",
        box=box.SIMPLE_HEAD,
        collapse_padding=True,
        pad_edge=False,
        caption_justify="left",
    )


def tables(run: Reproduction) -> list[Table]:
    """Rich tables of a run, one per experiment."""
    tables = []
    if run.broad_grid is not None:
        t = _table("Broad grid (paper Table 1 and Section 4.2): paper vs ours")
        for col in ("alpha", "quantity", "paper", "ours", "every digit?"):
            t.add_column(col, justify="left" if col == "quantity" else "right", no_wrap=True)
        # One line per distinct worst case: every alpha usually shares the paper's one.
        worst_cases: dict[str, list[str]] = {}
        paper_grid = run.settings.source_levels == 17 and run.settings.background_levels == 33
        quantities = (
            ("increase_pct", "increase %"),
            ("decrease_pct", "decrease %"),
            ("max_loss", "maximum loss"),
            ("loss_le_0_25_pct", "losses <= 0.25, %"),
        )
        for r in run.broad_grid:
            printed = PAPER["broad_grid"].get(alpha_key(r.alpha), {}) if paper_grid else {}
            for name, label in quantities:
                ours = getattr(r, name)
                paper = printed.get(name)
                if paper is None:
                    t.add_row(alpha_key(r.alpha), label, "—", f"{ours:z.4f}", "—")
                    continue
                ok = matches_printed(ours, paper)
                t.add_row(
                    alpha_key(r.alpha),
                    label,
                    f"{paper.value:.{paper.decimals}f}",
                    f"{ours:.{paper.decimals}f}",
                    Text("yes", style="green") if ok else Text("NO", style="bold red"),
                )
            worst = " > ".join(
                f"{cr:z.4f} (a={alpha_key(a)})" for a, cr in r.worst_contrast.items()
            )
            src, bg = (",".join(f"{v:g}" for v in c) for c in (r.worst_source, r.worst_background))
            case = f"largest loss ({src}) on ({bg}), CR {worst}"
            worst_cases.setdefault(case, []).append(alpha_key(r.alpha))
        t.caption = "\n".join(
            f"alpha {' and '.join(alphas)}: {case}" for case, alphas in worst_cases.items()
        )
        tables.append(t)
    if run.full_gamut is not None:
        # Two tables, not one of nine columns: each fits 60 columns with every
        # figure whole (the nine needed 72).
        halves = (
            ("contrast changes", ("inc %", "dec %", "same %")),
            ("threshold and separation", ("mean", "3:1 %", "Diff", "Excl")),
        )
        for k, (what, columns) in enumerate(halves):
            title = f"Full gamut on {run.theme.name} (comparable to the paper in method only)"
            t = _table(f"{title}: {what}" if k == 0 else f"Full gamut: {what}")
            for col in ("alpha", "group", *columns):
                t.add_column(col, justify="right", no_wrap=True)
            for fg in run.full_gamut:
                rows = [("all", fg.total)] + [(m, fg.group(m)) for m in ("light", "dark")]
                for name, c in rows:
                    if c is None:
                        continue
                    figures = (
                        (c.increase_pct, c.decrease_pct, c.unchanged_pct)
                        if k == 0
                        else (c.mean_change, c.newly_reach_pct, c.mean_difference_change,
                              c.mean_exclusion_change)
                    )  # fmt: skip
                    t.add_row(alpha_key(fg.alpha), name, *(f"{v:z.4f}" for v in figures))
            tables.append(t)
    if run.sweep is not None:
        s = run.sweep
        t = _table(f"Sweep on {s.levels}^3 sources, {s.pairs:,} random pairs (every 0.25)")
        for col in ("alpha", "mean change L/D", "decreases L/D", "collisions L/D"):
            t.add_column(col, justify="right", no_wrap=True)
        for i, a in enumerate(s.alphas):
            if abs(a * 4 - round(a * 4)) > 1e-9:
                continue

            def pair(series: dict[str, tuple[float, ...]], i: int = i) -> str:
                return " / ".join(f"{series[g][i]:z.4f}" for g in ("light", "dark") if g in series)

            t.add_row(f"{a:g}", pair(s.mean_change), pair(s.decrease_share),
                      pair(s.collision_rate))  # fmt: skip
        tables.append(t)
    if run.palette is not None:
        pal = run.palette
        t = _table(f"Palette separation: {pal.combinations} pair x canvas combinations")
        for col in ("alpha", "smaller CIEDE2000", "collisions", "random-pair collisions"):
            t.add_column(col, justify="right", no_wrap=True)
        for a in sorted(set(pal.alphas) | set(pal.random_alphas)):
            t.add_row(
                alpha_key(a),
                str(pal.smaller.get(a, "—")),
                str(pal.collisions.get(a, "—")),
                f"{pal.random_collisions[a]:,} of {pal.random_combinations:,}"
                if a in pal.random_collisions
                else "—",
            )
        tables.append(t)
    return tables + browser_tables(run.browser, run.runtime, _table)


def render_table(run: Reproduction, options: RenderOptions) -> str:
    """Every experiment's table at ``options.width`` columns."""
    return to_text(Group(*tables(run)), options)
