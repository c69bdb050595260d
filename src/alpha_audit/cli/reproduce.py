"""``alpha-audit reproduce``: the paper's numerical evaluation (registered by ``app.py``).

Runs the library (:mod:`alpha_audit.reproduce`), shows progress on stderr
(only on a terminal), prints rich tables, JSON or Markdown on stdout and,
with ``--out``, writes ``results.json``, ``report.md`` and the sweep figures
once everything has been computed, so a failed run leaves no partial files.
"""

from __future__ import annotations

import enum
import sys
from pathlib import Path
from typing import Annotated, assert_never

import typer
from rich import box
from rich.console import Console
from rich.progress import BarColumn, Progress, TextColumn, TimeElapsedColumn
from rich.table import Table
from rich.text import Text

from alpha_audit.bundled import bundled_theme, theme_source
from alpha_audit.cli.status import ExitStatus
from alpha_audit.errors import UsageError
from alpha_audit.load.theme import load_theme
from alpha_audit.reproduce.figures import write_figures
from alpha_audit.reproduce.paper import PAPER, matches_printed
from alpha_audit.reproduce.report import alpha_key, render_json, render_markdown
from alpha_audit.reproduce.run import Experiment, Reproduction, reproduce

__all__ = ["DEFAULT_THEME", "ReproduceFormat", "reproduce_command"]

DEFAULT_THEME = "paper16"
"""The bundled theme with the paper's sixteen canvases, used without ``--theme``."""


class ReproduceFormat(enum.StrEnum):
    """What ``reproduce`` prints on stdout."""

    TABLE = "table"
    JSON = "json"
    MARKDOWN = "markdown"


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


def _tables(run: Reproduction) -> list[Table]:
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
                p = printed.get(name)
                if p is None:
                    t.add_row(alpha_key(r.alpha), label, "—", f"{ours:.4f}", "—")
                    continue
                ok = matches_printed(ours, p)
                t.add_row(
                    alpha_key(r.alpha),
                    label,
                    f"{p.value:.{p.decimals}f}",
                    f"{ours:.{p.decimals}f}",
                    Text("yes", style="green") if ok else Text("NO", style="bold red"),
                )
            worst = " > ".join(f"{cr:.4f} (a={alpha_key(a)})" for a, cr in r.worst_contrast.items())
            src, bg = (",".join(f"{v:g}" for v in c) for c in (r.worst_source, r.worst_background))
            case = f"largest loss ({src}) on ({bg}), CR {worst}"
            worst_cases.setdefault(case, []).append(alpha_key(r.alpha))
        t.caption = "\n".join(
            f"alpha {' and '.join(alphas)}: {case}" for case, alphas in worst_cases.items()
        )
        tables.append(t)
    if run.full_gamut is not None:
        t = _table(f"Full gamut on {run.theme.name} (comparable to the paper in method only)")
        for col in ("alpha", "group", "inc %", "dec %", "same %", "mean", "3:1 %", "Diff", "Excl"):
            t.add_column(col, justify="right", no_wrap=True)
        for r in run.full_gamut:
            rows = [("all", r.total)] + [(m, r.group(m)) for m in ("light", "dark")]
            for name, c in rows:
                if c is None:
                    continue
                t.add_row(
                    alpha_key(r.alpha), name, f"{c.increase_pct:.4f}", f"{c.decrease_pct:.4f}",
                    f"{c.unchanged_pct:.4f}", f"{c.mean_change:.4f}", f"{c.newly_reach_pct:.4f}",
                    f"{c.mean_difference_change:.4f}", f"{c.mean_exclusion_change:.4f}",
                )  # fmt: skip
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
                return " / ".join(f"{series[g][i]:.4f}" for g in ("light", "dark") if g in series)

            t.add_row(f"{a:g}", pair(s.mean_change), pair(s.decrease_share),
                      pair(s.collision_rate))  # fmt: skip
        tables.append(t)
    if run.palette is not None:
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
        tables.append(t)
    return tables


def _run_with_progress(run_kwargs: dict, console: Console) -> Reproduction:
    """``reproduce(**run_kwargs)`` with one progress bar per experiment on stderr."""
    with Progress(
        TextColumn("{task.description:<12}"),
        BarColumn(),
        TimeElapsedColumn(),
        console=console,
        transient=True,
        disable=not console.is_terminal,
    ) as bars:
        tasks: dict[Experiment, int] = {}

        def advance(experiment: Experiment, fraction: float) -> None:
            if experiment not in tasks:
                tasks[experiment] = bars.add_task(experiment.value, total=1.0)
            bars.advance(tasks[experiment], fraction)

        return reproduce(**run_kwargs, progress=advance)


def reproduce_command(
    theme: Annotated[
        Path | None,
        typer.Option(
            "--theme",
            help="Theme YAML with the canvases, or a bundled theme name (default: paper16, "
            "bundled).",
        ),
    ] = None,
    only: Annotated[
        list[Experiment] | None,
        typer.Option(
            "--only",
            metavar="EXPERIMENT",
            help="Run only this experiment (repeatable): full-gamut, broad-grid, sweep, palette.",
            show_default=False,
        ),
    ] = None,
    alphas: Annotated[
        list[float] | None,
        typer.Option(
            "--alpha",
            metavar="A",
            help="Coefficient for full gamut, broad grid and palette (repeatable; default 1.1 "
            "and 1.4).",
            show_default=False,
        ),
    ] = None,
    out: Annotated[
        Path | None,
        typer.Option(
            "--out",
            help="Directory for results.json, report.md and the sweep figures.",
            file_okay=False,
        ),
    ] = None,
    quick: Annotated[
        bool, typer.Option("--quick", help="Small grids (seconds, not the paper's sizes).")
    ] = False,
    output_format: Annotated[
        ReproduceFormat,
        typer.Option("--format", help="What to print on stdout."),
    ] = ReproduceFormat.TABLE,
) -> ExitStatus:
    """Reproduce the paper's numerical evaluation (Section 4) exactly and fast."""
    if out is not None and out.exists() and not out.is_dir():
        raise UsageError(f"--out {out} exists and is not a directory")
    theme_path = bundled_theme(DEFAULT_THEME) if theme is None else theme_source(theme)
    if not theme_path.is_file():
        raise UsageError(f"theme file {theme_path} not found")
    loaded = load_theme(theme_path)
    run = _run_with_progress(
        {
            "theme": loaded,
            "only": only or (),
            "alphas": alphas or (1.1, 1.4),
            "quick": quick,
        },
        Console(stderr=True),
    )
    stdout = Console(highlight=False, emoji=False)
    match output_format:
        case ReproduceFormat.TABLE:
            for table in _tables(run):
                stdout.print(table)
        case ReproduceFormat.JSON:
            sys.stdout.write(render_json(run))  # verbatim: no wrapping or markup
        case ReproduceFormat.MARKDOWN:
            sys.stdout.write(render_markdown(run))
        case _:
            assert_never(output_format)
    if out is not None:
        out.mkdir(parents=True, exist_ok=True)
        (out / "results.json").write_text(render_json(run), encoding="utf-8")
        (out / "report.md").write_text(render_markdown(run), encoding="utf-8")
        if run.sweep is not None:
            write_figures(run.sweep, out)
    return ExitStatus.OK
