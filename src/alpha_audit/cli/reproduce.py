"""``alpha-audit reproduce``: the paper's numerical evaluation (registered by ``app.py``).

Runs the library (:mod:`alpha_audit.reproduce`), shows progress on stderr
(only on a terminal), prints rich tables, JSON or Markdown on stdout and,
with ``--out``, writes ``results.json``, ``report.md`` and the sweep figures
once everything has been computed, so a failed run leaves no partial files.
"""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from alpha_audit.cli.console import emit, progress_bars, stderr_note, stdout_options
from alpha_audit.cli.options import ranged
from alpha_audit.cli.status import ExitStatus
from alpha_audit.errors import UsageError
from alpha_audit.ranges import ALPHA
from alpha_audit.reproduce.experiment import Experiment
from alpha_audit.reproduce.formats import ReproduceFormat

__all__ = ["DEFAULT_THEME", "ReproduceFormat", "reproduce_command"]

DEFAULT_THEME = "paper16"
"""The bundled theme with the paper's sixteen canvases, used without ``--theme``."""


# reproduce's options.
_Theme = Annotated[
    Path | None,
    typer.Option(
        "--theme",
        help="Theme YAML with the canvases, or a bundled theme name (default: paper16, bundled).",
    ),
]
_Only = Annotated[
    list[Experiment] | None,
    typer.Option(
        "--only",
        metavar="EXPERIMENT",
        help="Run only this experiment (repeatable): full-gamut, broad-grid, sweep, palette; "
        "browser and runtime (in browsers, never by default) need --icons.",
        show_default=False,
    ),
]
_Alphas = Annotated[
    list[float] | None,
    ranged(
        "--alpha",
        allowed=ALPHA,
        metavar="A",
        help="Coefficient for full gamut, broad grid and palette (repeatable; default 1.1 "
        "and 1.4).",
        show_default=False,
    ),
]
_Out = Annotated[
    Path | None,
    typer.Option(
        "--out",
        help="Directory for results.json, report.md and the sweep figures.",
        file_okay=False,
    ),
]
_Quick = Annotated[
    bool, typer.Option("--quick", help="Small grids (seconds, not the paper's sizes).")
]
_OutputFormat = Annotated[
    ReproduceFormat,
    typer.Option("--format", help="What to print on stdout."),
]
_Force = Annotated[
    bool, typer.Option("--force", help="Replace existing files in the --out folder.")
]
_Icons = Annotated[
    Path | None,
    typer.Option(
        "--icons",
        help="Directory of SVG icons for browser and runtime (the first 300 by SHA-256 "
        "of their path).",
        file_okay=False,
    ),
]
_Engines = Annotated[
    list[str] | None,
    typer.Option(
        "--engine",
        metavar="ENGINE",
        help="Browser engine for browser and runtime (repeatable: chromium, firefox, "
        "webkit; default every installed one).",
        show_default=False,
    ),
]


def reproduce_command(
    theme: _Theme = None,
    only: _Only = None,
    alphas: _Alphas = None,
    out: _Out = None,
    quick: _Quick = False,
    output_format: _OutputFormat = ReproduceFormat.TABLE,
    force: _Force = False,
    icons: _Icons = None,
    engines: _Engines = None,
) -> ExitStatus:
    """Reproduce the paper's numerical evaluation (Section 4) exactly and fast."""
    from alpha_audit.bundled import bundled_theme, theme_source
    from alpha_audit.load.theme import load_theme
    from alpha_audit.reproduce.files import check_results_folder, write_results
    from alpha_audit.reproduce.run import reproduce

    if out is not None and out.exists() and not out.is_dir():
        raise UsageError(f"--out {out} exists and is not a directory")
    if out is not None:
        check_results_folder(out, only or (), overwrite=force)  # before minutes of work
    theme_path = bundled_theme(DEFAULT_THEME) if theme is None else theme_source(theme)
    if not theme_path.is_file():
        raise UsageError(f"theme file {theme_path} not found")
    loaded = load_theme(theme_path)
    with progress_bars() as advance:
        run = reproduce(
            loaded,
            only or (),
            alphas=alphas or (1.1, 1.4),
            quick=quick,
            icons=icons,
            engines=engines or None,
            progress=lambda experiment, fraction: advance(experiment.value, fraction),
        )
    emit(output_format.renderer()(run, stdout_options()), None, False)
    if out is not None:
        for path in write_results(run, out, overwrite=force):
            stderr_note(f"wrote {path}")
    return ExitStatus.OK
