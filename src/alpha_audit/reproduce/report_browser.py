"""JSON and Markdown sections for the browser experiments (validation and runtime).

Pure functions of the results, called by :mod:`alpha_audit.reproduce.report`
for its ``browser`` and ``runtime`` keys and sections; numbers are unrounded
in JSON.  The paper's figures (388,800 instances, 1/255; no sustained runtime
increase outside [0, 1]) stand beside ours.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

from rich.table import Table

from alpha_audit.browser import ENGINES
from alpha_audit.render.common import escape_markdown
from alpha_audit.reproduce.browser import (
    PAPER_ICONS,
    PAPER_INSTANCES,
    PAPER_MAX_ERROR,
    BrowserValidationResult,
)
from alpha_audit.reproduce.runtime import BACKGROUNDS, CANVAS, ICON_SIZE, RuntimeResult

__all__ = [
    "browser_json",
    "browser_markdown",
    "browser_tables",
    "runtime_json",
    "runtime_markdown",
]


def _finite(value: float) -> float | None:
    """JSON has no NaN: a ratio without coefficients on one side is ``null``."""
    return value if math.isfinite(value) else None


def _label(engine: str) -> str:
    return ENGINES[engine].LABEL if engine in ENGINES else engine


def browser_json(result: BrowserValidationResult) -> dict[str, Any]:
    """The ``browser`` section: design, then per engine and configuration the errors."""
    return {
        "icons": result.icons,
        "failed_icons": result.failed_icons,
        "sizes": list(result.sizes),
        "canvases": result.canvases,
        "instances": result.instances,
        "max_error_codes": result.max_error,
        "missing_engines": list(result.missing),
        "paper": {"instances": PAPER_INSTANCES, "max_error_codes": PAPER_MAX_ERROR},
        "engines": [
            {
                "engine": e.engine,
                "version": e.version,
                "renderer": e.renderer,
                "instances": e.instances,
                "max_error_codes": e.max_error,
                "max_error_uncovered_codes": e.max_error_uncovered,
                "configurations": [
                    {
                        "configuration": r.configuration.label,
                        "blend": str(r.configuration.blend),
                        "alpha": r.configuration.alpha,
                        "instances": r.instances,
                        "max_error_codes": r.max_error,
                        "max_error_uncovered_codes": r.max_error_uncovered,
                    }
                    for r in e.results
                ],
            }
            for e in result.engines
        ],
    }


def browser_markdown(result: BrowserValidationResult) -> list[str]:
    """Markdown lines: one table of instances and maximum errors per engine and configuration."""
    engines = result.engines
    lines = [
        "## Output validation in browsers (Section 4.4)",
        "",
        f"{result.icons} icons (paper: {PAPER_ICONS}) x {len(result.sizes)} sizes "
        f"({', '.join(map(str, result.sizes))} px) x {result.canvases} canvases x 9 "
        f"configurations per engine; every covered pixel compared with the float64 CPU "
        f"reference.  Paper: {PAPER_INSTANCES:,} instances over three browsers, maximum "
        f"error {PAPER_MAX_ERROR}/255.",
        "",
    ]
    if result.failed_icons:
        lines += [f"{result.failed_icons} selected icons could not be rasterised.", ""]
    if result.missing:
        lines += ["Not installed: " + ", ".join(_label(m) for m in result.missing) + ".", ""]
    lines += [
        "| Configuration | " + " | ".join(_label(e.engine) for e in engines) + " |",
        "|---|" + "---:|" * len(engines),
    ]
    for k, first in enumerate(engines[0].results if engines else ()):
        cells = [f"{e.results[k].instances:,}, max {e.results[k].max_error}/255" for e in engines]
        lines.append(f"| {first.configuration.label} | " + " | ".join(cells) + " |")
    cells = [f"**{e.instances:,}, max {e.max_error}/255**" for e in engines]
    lines.append("| all | " + " | ".join(cells) + " |")
    verdict = "within" if result.max_error <= PAPER_MAX_ERROR else "**outside**"
    lines += [
        "",
        f"All engines: {result.instances:,} instances (paper {PAPER_INSTANCES:,}); maximum "
        f"error {result.max_error}/255, {verdict} the paper's {PAPER_MAX_ERROR}/255.",
        "",
    ]
    for e in engines:
        lines.append(
            f"- {_label(e.engine)}: {escape_markdown(e.version)}; "
            f"WebGL renderer {escape_markdown(e.renderer)}"
        )
    return [*lines, ""]


def runtime_json(result: RuntimeResult) -> dict[str, Any]:
    """The ``runtime`` section: design and, per engine, block means and their summary."""
    s = result.settings
    return {
        "alphas": list(s.alphas),
        "warmups": s.warmups,
        "rounds": s.rounds,
        "frames_per_block": s.frames,
        "seed": s.seed,
        "icons_per_frame": result.icons,
        "distinct_icons": result.distinct_icons,
        "icon_size": ICON_SIZE,
        "canvas": list(CANVAS),
        "backgrounds": dict(BACKGROUNDS),
        "missing_engines": list(result.missing),
        "engines": [
            {
                "engine": e.engine,
                "version": e.version,
                "renderer": e.renderer,
                "median_ms": list(e.median),
                "p10_ms": list(e.p10),
                "p90_ms": list(e.p90),
                "outside_vs_inside": _finite(e.outside_vs_inside),
                "worst_vs_inside": _finite(e.worst_vs_inside),
                "block_means_ms": [list(row) for row in e.samples],
            }
            for e in result.engines
        ],
    }


def runtime_markdown(result: RuntimeResult) -> list[str]:
    """Markdown lines: per engine the median range and the outside/inside [0, 1] ratio."""
    s = result.settings
    lines = [
        "## Runtime across signed coefficients (Section 4.4, Figure 5)",
        "",
        f"{len(s.alphas)} coefficients in [{s.alphas[0]:g}, {s.alphas[-1]:g}], {s.warmups} "
        f"warm-up sweeps, {s.rounds} rounds in seeded Fisher-Yates order, blocks of {s.frames} "
        f"frames; each frame draws {result.icons} icons ({result.distinct_icons} distinct) at "
        f"{ICON_SIZE} px on {CANVAS[0]} x {CANVAS[1]} and reads back one pixel.",
        "",
        "Measured on this machine's WebGL implementation (software GL when there is no GPU): "
        "absolute times are not the paper's.  The claim under test is relative: no sustained "
        "increase outside [0, 1].  The ratio is the median over coefficients outside [0, 1] "
        "of the per-coefficient medians, divided by the same inside [0, 1].",
        "",
        "| Engine | median ms/frame, range | outside / inside [0, 1] | worst outside / inside |",
        "|---|---:|---:|---:|",
    ]
    for e in result.engines:
        lines.append(
            f"| {_label(e.engine)} | {min(e.median):.3f} to {max(e.median):.3f} | "
            f"{e.outside_vs_inside:.3f} | {e.worst_vs_inside:.3f} |"
        )
    if result.missing:
        lines += ["", "Not installed: " + ", ".join(_label(m) for m in result.missing) + "."]
    return [*lines, ""]


def browser_tables(
    browser: BrowserValidationResult | None,
    runtime: RuntimeResult | None,
    table: Callable[[str], Table],
) -> list[Table]:
    """Rich tables of the two experiments that ran, each made by ``table(title)``."""
    tables = []
    if browser is not None:
        b = browser
        t = table(f"Output validation in browsers, {b.icons} icons: instances, max error")
        t.add_column("configuration", no_wrap=True)
        for e in b.engines:
            t.add_column(_label(e.engine), justify="right", no_wrap=True)
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
    if runtime is not None:
        s = runtime.settings
        t = table(f"Runtime, {len(s.alphas)} coefficients x {s.rounds} rounds (relative)")
        t.caption = (
            f"{s.frames}-frame blocks; on software GL absolute times are not the paper's; "
            "the claim is relative: no sustained increase outside [0, 1]"
        )
        for col in ("engine", "median ms/frame", "outside/inside [0,1]", "worst/inside"):
            t.add_column(col, justify="left" if col == "engine" else "right", no_wrap=True)
        for timing in runtime.engines:
            t.add_row(
                _label(timing.engine),
                f"{min(timing.median):.3f}-{max(timing.median):.3f}",
                f"{timing.outside_vs_inside:.3f}",
                f"{timing.worst_vs_inside:.3f}",
            )
        tables.append(t)
    return tables
