"""Rich tables for ``reproduce --only browser`` and ``--only runtime`` (used by cli.reproduce)."""

from __future__ import annotations

from rich import box
from rich.table import Table
from rich.text import Text

from alpha_audit.browser import ENGINES
from alpha_audit.reproduce.browser import PAPER_INSTANCES, PAPER_MAX_ERROR
from alpha_audit.reproduce.run import Reproduction

__all__ = ["browser_tables"]


def _table(title: str) -> Table:
    return Table(title=Text(title), title_justify="left", box=box.SIMPLE_HEAD,
                 collapse_padding=True, pad_edge=False, caption_justify="left")  # fmt: skip


def browser_tables(run: Reproduction) -> list[Table]:
    """Tables of the browser validation and the runtime measurement, when they ran."""
    tables = []
    if run.browser is not None:
        b = run.browser
        t = _table(f"Output validation in browsers, {b.icons} icons: instances, max error")
        t.add_column("configuration", no_wrap=True)
        for e in b.engines:
            t.add_column(ENGINES[e.engine].LABEL, justify="right", no_wrap=True)
        for k, first in enumerate(b.engines[0].results if b.engines else ()):
            t.add_row(
                first.configuration.label,
                *(f"{e.results[k].instances:,}  {e.results[k].max_error}/255" for e in b.engines),
            )
        t.add_row("all", *(f"{e.instances:,}  {e.max_error}/255" for e in b.engines))
        ok = b.max_error <= PAPER_MAX_ERROR
        t.caption = (
            f"all engines: {b.instances:,} instances (paper {PAPER_INSTANCES:,}), max error "
            f"{b.max_error}/255 (paper {PAPER_MAX_ERROR}/255): "
            + ("within" if ok else "OUTSIDE")
            + ("" if not b.missing else f"; not installed: {', '.join(b.missing)}")
        )
        tables.append(t)
    if run.runtime is not None:
        r = run.runtime
        s = r.settings
        t = _table(f"Runtime, {len(s.alphas)} coefficients x {s.rounds} rounds (relative)")
        t.caption = (
            f"{s.frames}-frame blocks; on software GL absolute times are not the paper's; "
            "the claim is relative: no sustained increase outside [0, 1]"
        )
        for col in ("engine", "median ms/frame", "outside/inside [0,1]", "worst/inside"):
            t.add_column(col, justify="left" if col == "engine" else "right", no_wrap=True)
        for e in r.engines:
            t.add_row(ENGINES[e.engine].LABEL, f"{min(e.median):.3f}-{max(e.median):.3f}",
                      f"{e.outside_vs_inside:.3f}", f"{e.worst_vs_inside:.3f}")  # fmt: skip
        tables.append(t)
    return tables
