"""Renderers of a :class:`~alpha_audit.reproduce.run.Reproduction`: table, JSON and Markdown.

Pure functions of the result: no printing, no clock, stable order.  The rich
tables fit 80 columns and never cut a number.  The JSON
schema ``alpha-audit.reproduce/1`` is documented in ``docs/reproduce.md``;
numbers are unrounded.  The Markdown report puts the paper's printed values
beside ours and says, per value, whether it is comparable in digits and
whether ours matches to every printed digit (:mod:`.compare` decides both).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any

from rich import box
from rich.console import Group, RenderableType
from rich.table import Table
from rich.text import Text

from alpha_audit import __version__
from alpha_audit.render.common import RenderOptions, dumps, escape_markdown, to_text
from alpha_audit.reproduce.compare import Comparison, comparisons, setup_differences
from alpha_audit.reproduce.experiments import (
    BroadGridResult,
    ContrastChange,
    FullGamutResult,
    PaletteResult,
    SweepResult,
)
from alpha_audit.reproduce.paper import (
    PAPER,
    PAPER_THEME,
    WORST_BACKGROUND,
    WORST_SOURCE,
    Setup,
    alpha_key,
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
    "render_table",
    "reproduction_json",
    "reproduction_markdown",
    "to_json_dict",
]

SCHEMA = "alpha-audit.reproduce/1"


def _change(change: ContrastChange | None) -> dict[str, Any] | None:
    return None if change is None else change.as_dict()


def to_json_dict(run: Reproduction) -> dict[str, Any]:
    """The ``alpha-audit.reproduce/1`` document as plain Python data."""
    theme = run.theme
    doc: dict[str, Any] = {
        "schema": SCHEMA,
        "tool": {"name": "alpha-audit", "version": __version__},
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
    sections: dict[str, tuple[Any, Callable[[Any], dict[str, Any]]]] = {
        "broad_grid": (run.broad_grid, _broad_grid_json),
        "full_gamut": (run.full_gamut, _full_gamut_json),
        "sweep": (run.sweep, _sweep_json),
        "palette": (run.palette, _palette_json),
        "browser": (run.browser, browser_json),
        "runtime": (run.runtime, runtime_json),
    }
    for key, (result, to_json) in sections.items():
        if result is not None:
            doc[key] = to_json(result)
    doc["paper"] = _paper_json(run)
    return doc


def _broad_grid_json(results: Sequence[BroadGridResult]) -> dict[str, Any]:
    first = results[0]
    section: dict[str, Any] = {
        "source_levels": first.source_levels,
        "background_levels": first.background_levels,
        "combinations": first.combinations,
    }
    for r in results:
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
    return section


def _full_gamut_json(results: Sequence[FullGamutResult]) -> dict[str, Any]:
    fg: dict[str, Any] = {"levels": results[0].levels, "threshold": results[0].threshold}
    for g in results:
        fg[alpha_key(g.alpha)] = {
            "all": _change(g.total),
            "light": _change(g.group("light")),
            "dark": _change(g.group("dark")),
            "canvases": [
                {"name": c.name, "color": c.color, "mode": c.mode} | c.change.as_dict()
                for c in g.canvases
            ],
        }
    return fg


def _sweep_json(s: SweepResult) -> dict[str, Any]:
    return {
        "levels": s.levels,
        "pairs": s.pairs,
        "seed": s.seed,
        "alphas": list(s.alphas),
        "mean_change": {k: list(v) for k, v in s.mean_change.items()},
        "decrease_share": {k: list(v) for k, v in s.decrease_share.items()},
        "collision_rate": {k: list(v) for k, v in s.collision_rate.items()},
    }


def _palette_json(p: PaletteResult) -> dict[str, Any]:
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
    return pal


def _paper_json(run: Reproduction) -> dict[str, Any]:
    """Every printed number of the paper beside ours, by experiment and group."""
    paper: dict[str, Any] = {}
    for c in comparisons(run):
        paper.setdefault(c.experiment, {}).setdefault(c.group, {})[c.name] = {
            "value": c.printed.value,
            "decimals": c.printed.decimals,
            "where": c.printed.where,
            "setup": c.printed.setup.value,
            "ours": c.ours,
            "comparable": c.comparable,
            "why_not_comparable": c.differs,
            "matches": c.matches,
        }
    return paper


def reproduction_json(run: Reproduction, options: RenderOptions | None = None) -> str:
    """``to_json_dict`` as JSON text (``options`` change nothing)."""
    return dumps(to_json_dict(run))


# --------------------------------------------------------------------------- Markdown

_Index = dict[tuple[str, str, str], Comparison]


def _index(run: Reproduction) -> _Index:
    return {(c.experiment, c.group, c.name): c for c in comparisons(run)}


def _fmt(value: float, decimals: int) -> str:
    return f"{value:z,.{decimals}f}"


def _row(label: str, ours: float | None, printed: Comparison | None, decimals: int = 4) -> str:
    shown = "—" if ours is None else _fmt(ours, decimals)
    if printed is None:
        return f"| {label} | — | {shown} | no printed value | — |"
    d = printed.printed.decimals
    paper = _fmt(printed.printed.value, d)
    if ours is not None:
        shown = _fmt(ours, max(d, 4) if d else 0)  # counts stay integers
    where = printed.printed.where
    if printed.comparable:
        verdict = "**yes**" if printed.matches else "**NO**"
        comparable = f"yes ({where})"
    else:
        verdict = "n/a"
        comparable = f"no: {escape_markdown(printed.differs or '')} ({where})"
    return f"| {label} | {paper} | {shown} | {comparable} | {verdict} |"


_HEADER = [
    "| Quantity | Paper | Ours | Comparable in digits? | Matches every printed digit? |",
    "|---|---:|---:|---|---|",
]


def _setup_sentence(subject: str, differs: str | None, same: str) -> str:
    """``subject: same; comparable ...`` or ``subject: not the paper's (why); ...``."""
    if differs is None:
        return f"{subject}: {same}; comparable to every printed digit."
    return f"{subject}: not the paper's ({escape_markdown(differs)}); not comparable in digits."


# The broad grid's quantities beside the paper's, as the report names them.
_BROAD_QUANTITIES = (
    ("increase_pct", "increase %"),
    ("decrease_pct", "decrease %"),
    ("max_loss", "maximum loss"),
    ("loss_le_0_25_pct", "decreases with loss <= 0.25, %"),
)


def _broad_section(run: Reproduction, index: _Index) -> list[str]:
    assert run.broad_grid is not None
    first = run.broad_grid[0]
    differs = setup_differences(run)[Setup.BROAD_GRID]
    lines = [
        "## Broad grid (Table 1, Section 4.2)",
        "",
        f"{first.source_levels}^3 sources x {first.background_levels}^3 backgrounds, uniform in "
        f"encoded sRGB with endpoints; {first.combinations:,} combinations per alpha.  "
        + _setup_sentence("Setup", differs, "the paper's grids"),
        "",
        *_HEADER,
    ]
    for r in run.broad_grid:
        key = alpha_key(r.alpha)
        quantities = [(label, getattr(r, name), name) for name, label in _BROAD_QUANTITIES]
        quantities += [
            (label, r.worst_contrast[a], f"worst_contrast_{alpha_key(a)}")
            for label, a in (
                ("worst case, contrast at 1", 1.0),
                (f"worst case, contrast at {key}", r.alpha),
            )
        ]
        lines += [
            _row(f"alpha {key}: {label}", ours, index.get(("broad_grid", key, name)))
            for label, ours, name in quantities
        ]
    lines.append("")
    for r in run.broad_grid:
        same = r.worst_source == WORST_SOURCE and r.worst_background == WORST_BACKGROUND
        verdict = ("the same as" if same else "NOT the same as") if differs is None else "unlike"
        contrasts = " -> ".join(
            f"{cr:z.4f} (alpha {alpha_key(a)})" for a, cr in r.worst_contrast.items()
        )
        lines.append(
            f"- alpha {alpha_key(r.alpha)}: largest loss for source sRGB {r.worst_source} on "
            f"{r.worst_background}, {verdict} the paper's (0, 0, 0.8125) on (1, 1, 0); "
            f"contrast {contrasts}."
        )
    return [*lines, ""]


_PAPER_CANVASES = (
    f"the paper's sixteen canvases (bundled theme {PAPER_THEME}, from the authors' public "
    "evaluation protocol)"
)


def _full_gamut_section(run: Reproduction, index: _Index) -> list[str]:
    assert run.full_gamut is not None
    first = run.full_gamut[0]
    differs = setup_differences(run)[Setup.FULL_GAMUT]
    lines = [
        "## Full gamut (Section 4.2, Table 1)",
        "",
        f"All {first.levels}^3 sources on the {len(first.canvases)} canvases of theme "
        f"{escape_markdown(first.theme)}.  "
        + _setup_sentence("Setup", differs, f"every 8-bit source on {_PAPER_CANVASES}"),
        "",
        *_HEADER,
    ]
    for r in run.full_gamut:
        key = alpha_key(r.alpha)
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
            lines.append(
                _row(
                    f"alpha {key}: {label}", getattr(t, name), index.get(("full_gamut", key, name))
                )
            )
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
        "no sweep values, only the figures: compare `sweep-1-2.png` and `sweep-0-2.png` with its "
        "Figures 3 and 6 in shape.",
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


def _palette_section(run: Reproduction, index: _Index) -> list[str]:
    assert run.palette is not None
    p = run.palette
    differences = setup_differences(run)
    palette, random = differences[Setup.PALETTE], differences[Setup.RANDOM_PAIRS]
    lines = [
        "## Palette separation (Section 4.3)",
        "",
        f"All {len(p.palette) * (len(p.palette) - 1) // 2} pairs of "
        f"{escape_markdown(', '.join(p.palette))} on each "
        f"canvas ({p.combinations} combinations); {p.random_pairs:,} random pairs (seed "
        f"{p.seed}) on each canvas ({p.random_combinations:,} combinations).  "
        + _setup_sentence("Palette pairs", palette, f"Tol's Vibrant on {_PAPER_CANVASES}")
        + "  "
        + _setup_sentence("Random pairs", random, "the paper's count and seed on its canvases")
        + "  The paper's random collisions (617 -> 15,098) are read as alpha 1.1 -> 1.4; at "
        "alpha 1.0 distinct 8-bit sources cannot collide.",
        "",
        *_HEADER,
    ]
    rows = [
        ("palette combinations", p.combinations, "counts", "combinations"),
        ("random combinations", p.random_combinations, "counts", "random_combinations"),
    ]
    for a in p.alphas:
        key = alpha_key(a)
        rows += [
            (f"alpha {key}: smaller CIEDE2000", p.smaller[a], key, "smaller"),
            (f"alpha {key}: collisions", p.collisions[a], key, "collisions"),
        ]
    rows += [
        (f"alpha {alpha_key(a)}: random-pair collisions", p.random_collisions[a], alpha_key(a),
         "random_collisions")
        for a in p.random_alphas
    ]  # fmt: skip
    lines += [
        _row(label, n, index.get(("palette", group, name)), 0) for label, n, group, name in rows
    ]
    return [*lines, ""]


def _tally(run: Reproduction) -> str:
    """One sentence: how many printed figures were comparable and how many match."""
    compared = [c for c in comparisons(run) if c.comparable]
    if not compared:
        return "No printed figure of the paper is comparable in digits in this run."
    missed = [c for c in compared if not c.matches]
    text = (
        f"{len(compared) - len(missed)} of the {len(compared)} printed figures comparable in "
        "this run match every printed digit"
    )
    if missed:
        text += "; NOT matching: " + ", ".join(f"{c.experiment} {c.group} {c.name}" for c in missed)
    return text + "."


def reproduction_markdown(run: Reproduction, options: RenderOptions | None = None) -> str:
    """The report: per experiment, the paper's printed values beside ours.

    Theme and canvas names come from input files: escaped like every Markdown
    report (:func:`~alpha_audit.render.common.escape_markdown`).
    """
    index = _index(run)
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
        "'Comparable in digits' marks values computed with the paper's setup (its grids, its "
        "sixteen canvases, Tol's Vibrant palette, 65,536 random pairs from seed 20260913); for "
        "those, 'Matches' says whether ours rounds to the printed value.  Other values are shown "
        "for comparison of magnitude, never as a match.  " + _tally(run),
        "",
    ]
    if run.broad_grid is not None:
        lines += _broad_section(run, index)
    if run.full_gamut is not None:
        lines += _full_gamut_section(run, index)
    if run.sweep is not None:
        lines += _sweep_section(run)
    if run.palette is not None:
        lines += _palette_section(run, index)
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


# (alpha, quantity, ours, the printed value or None, decimals when nothing is printed)
_Versus = tuple[str, str, float, Comparison | None, int]


def _versus_table(title: str, rows: list[_Versus], notes: Sequence[str] = ()) -> RenderableType:
    """Paper beside ours, to the printed decimals, and whether every printed digit matches.

    A value computed with a setup other than the paper's shows the printed
    value but no verdict; a note below the table says why.
    """
    t = _table(title)
    for col in ("alpha", "quantity", "paper", "ours", "match?"):
        t.add_column(col, justify="left" if col == "quantity" else "right", no_wrap=True)
    reasons: dict[str, None] = {}
    for alpha, label, ours, printed, decimals in rows:
        if printed is None:
            t.add_row(alpha, label, "—", f"{ours:z,.{decimals}f}", "—")
            continue
        d = printed.printed.decimals
        verdict: str | Text = "—"
        if printed.comparable:
            ok = printed.matches
            verdict = Text("yes", style="green") if ok else Text("NO", style="bold red")
        elif printed.differs:
            reasons[printed.differs] = None
        t.add_row(alpha, label, f"{printed.printed.value:z,.{d}f}", f"{ours:z,.{d}f}", verdict)
    notes = [*(f"not the paper's setup: {r}" for r in reasons), *notes]
    if not notes:
        return t
    # Below the table, not its caption: a caption wraps at the table's (narrow) width.
    return Group(t, Text("\n".join(notes)), Text())  # reasons name the theme: never markup


def _broad_table(run: Reproduction, index: _Index) -> RenderableType:
    assert run.broad_grid is not None
    rows: list[_Versus] = []
    # One line per distinct worst case: every alpha usually shares the paper's one.
    worst_cases: dict[str, list[str]] = {}
    for r in run.broad_grid:
        key = alpha_key(r.alpha)
        for name, label in (
            ("increase_pct", "increase %"),
            ("decrease_pct", "decrease %"),
            ("max_loss", "maximum loss"),
            ("loss_le_0_25_pct", "losses <= 0.25, %"),
        ):
            rows.append((key, label, getattr(r, name), index.get(("broad_grid", key, name)), 4))
        worst = " > ".join(f"{cr:z.4f} (a={alpha_key(a)})" for a, cr in r.worst_contrast.items())
        src, bg = (",".join(f"{v:g}" for v in c) for c in (r.worst_source, r.worst_background))
        worst_cases.setdefault(f"largest loss ({src}) on ({bg}), CR {worst}", []).append(key)
    notes = [f"alpha {' and '.join(alphas)}: {case}" for case, alphas in worst_cases.items()]
    return _versus_table("Broad grid (Table 1, Section 4.2): paper vs ours", rows, notes)


def _full_gamut_tables(run: Reproduction, index: _Index) -> list[RenderableType]:
    assert run.full_gamut is not None
    tables: list[RenderableType] = []
    # Two tables, not one of nine columns: each fits 60 columns with every
    # figure whole (the nine needed 72).
    halves = (
        ("contrast changes", ("inc %", "dec %", "same %")),
        ("threshold and separation", ("mean", "3:1 %", "Diff", "Excl")),
    )
    for k, (what, columns) in enumerate(halves):
        t = _table(f"Full gamut on {run.theme.name}: {what}" if k == 0 else f"Full gamut: {what}")
        for col in ("alpha", "group", *columns):
            t.add_column(col, justify="right", no_wrap=True)
        for fg in run.full_gamut:
            groups = [("all", fg.total)] + [(m, fg.group(m)) for m in ("light", "dark")]
            for name, c in groups:
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
    labels = {
        "increase_pct": "increase %",
        "decrease_pct": "decrease %",
        "mean_change": "mean change",
        "newly_reach_pct": "newly 3:1, % of all",
        "mean_difference_change": "Difference, mean",
        "mean_exclusion_change": "Exclusion, mean",
    }
    rows: list[_Versus] = [
        (c.group, labels[c.name], c.ours, c, 4)
        for c in index.values()
        if c.experiment == "full_gamut" and c.ours is not None
    ]
    if rows:
        tables.append(_versus_table("Full gamut (Section 4.2, Table 1): paper vs ours", rows))
    return tables


def _palette_tables(run: Reproduction, index: _Index) -> list[RenderableType]:
    assert run.palette is not None
    p = run.palette
    t = _table(f"Palette separation: {p.combinations} pair x canvas combinations")
    for col in ("alpha", "smaller CIEDE2000", "collisions", "random-pair collisions"):
        t.add_column(col, justify="right", no_wrap=True)
    for a in sorted(set(p.alphas) | set(p.random_alphas)):
        t.add_row(
            alpha_key(a),
            str(p.smaller.get(a, "—")),
            str(p.collisions.get(a, "—")),
            f"{p.random_collisions[a]:,} of {p.random_combinations:,}"
            if a in p.random_collisions
            else "—",
        )
    counts = {name: index.get(("palette", "counts", name)) for name in PAPER["palette"]["counts"]}
    rows: list[_Versus] = [
        ("", "pairs x canvases", p.combinations, counts["combinations"], 0),
        ("", "random x canvases", p.random_combinations, counts["random_combinations"], 0),
    ]
    for a in sorted(set(p.alphas) | set(p.random_alphas)):
        key = alpha_key(a)
        for name, label, values in (
            ("smaller", "smaller CIEDE2000", p.smaller),
            ("collisions", "collisions", p.collisions),
            ("random_collisions", "random collisions", p.random_collisions),
        ):
            if a in values and ("palette", key, name) in index:
                rows.append((key, label, values[a], index[("palette", key, name)], 0))
    return [t, _versus_table("Palette separation (Section 4.3): paper vs ours", rows)]


def _sweep_table(run: Reproduction) -> Table:
    assert run.sweep is not None
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
    return t


def render_table(run: Reproduction, options: RenderOptions) -> str:
    """Every experiment's table (notes below some) at ``options.width`` columns, then the
    tally of printed figures."""
    index = _index(run)
    tables: list[RenderableType] = []
    if run.broad_grid is not None:
        tables.append(_broad_table(run, index))
    if run.full_gamut is not None:
        tables += _full_gamut_tables(run, index)
    if run.sweep is not None:
        tables.append(_sweep_table(run))
    if run.palette is not None:
        tables += _palette_tables(run, index)
    tables += browser_tables(run.browser, run.runtime, _table)
    return to_text(Group(*tables, Text(_tally(run))), options)
