"""``alpha-audit export``: the displayed colours of what ``check`` audits, in shippable formats."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from alpha_audit.cli.console import emit, stderr_note
from alpha_audit.cli.options import (
    AlphaOption,
    ConfigOption,
    ForceOption,
    GamutOption,
    IconsetArgument,
    PipelineOption,
    ThemeArgument,
    input_overrides,
)
from alpha_audit.cli.status import ExitStatus

__all__ = ["export_command"]


def export_command(
    theme: ThemeArgument = None,
    iconset: IconsetArgument = None,
    fmt: Annotated[
        str,
        typer.Option(
            "--format",
            "-f",
            metavar="FORMAT",
            help="dtcg (one file per mode), resolver, css, tailwind, svg or json.",
        ),
    ] = "css",
    out: Annotated[
        Path | None,
        typer.Option(
            "--out",
            "-o",
            help="Folder to write into (default: stdout; dtcg needs a folder).",
        ),
    ] = None,
    selector: Annotated[
        str | None,
        typer.Option(
            help="CSS selector per mode; <mode> is replaced by the mode's name and by each "
            "name it shares its colours with.",
            show_default='[data-theme="<mode>"]',
        ),
    ] = None,
    alpha: AlphaOption = None,
    pipeline: PipelineOption = None,
    gamut: GamutOption = None,
    config: ConfigOption = None,
    force: ForceOption = False,
) -> ExitStatus:
    """Write every icon colour's displayed output per theme and canvas.

    Exports what check audits, with the alpha and the pipeline check uses: the
    project config's themes (or design-token modes) and icon sets, or THEME
    ICONSET. Each colour is check's output for that icon colour and canvas, to
    the 8-bit code: export reads the rows check computes.

    Example: [bold]alpha-audit export paper16 vibrant -f json[/]
    """
    from alpha_audit.errors import UsageError
    from alpha_audit.export import ExportFormat, export_project, render_export, write_export
    from alpha_audit.load.config import resolve_config

    formats = [f.value for f in ExportFormat]
    if fmt not in formats:
        raise UsageError(f"--format {fmt!r} is not one of {', '.join(formats)}")
    overrides = input_overrides(
        theme, iconset, config=config, alpha=alpha, pipeline=pipeline, gamut=gamut
    )
    table = export_project(resolve_config(overrides, Path.cwd()))
    for note in table.notes:
        stderr_note(note)
    for a in table.adjusted:
        stderr_note(
            f"{a.token} ({a.mode}) is outside sRGB; gamut {a.policy} gives {a.output} "
            f"(CIEDE2000 {a.delta_e:.2f})"
        )
    files = render_export(table, fmt, selector=selector)
    if out is None:
        if len(files) > 1:
            raise UsageError(f"--format {fmt} writes {len(files)} files; give --out FOLDER")
        emit(next(iter(files.values())), None, False)
        return ExitStatus.OK
    for path in write_export(files, out, overwrite=force):
        stderr_note(f"wrote {path}")
    return ExitStatus.OK
