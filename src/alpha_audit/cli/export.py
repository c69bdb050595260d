"""``alpha-audit export``: the displayed colours of token themes, in shippable formats."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from alpha_audit.cli.console import emit, stderr_note
from alpha_audit.cli.options import (
    ConfigOption,
    ForceOption,
    GamutOption,
    in_range,
    read_gamut_option,
)
from alpha_audit.cli.status import ExitStatus
from alpha_audit.ranges import ALPHA

__all__ = ["export_command"]


def export_command(
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
            help='CSS selector per mode; <mode> is replaced. [default: [data-theme="<mode>"]]'
        ),
    ] = None,
    alpha: Annotated[
        float | None,
        typer.Option(
            help="Coefficient for every colour (overrides the tokens).",
            callback=in_range("--alpha", ALPHA),
        ),
    ] = None,
    gamut: GamutOption = None,
    config: ConfigOption = None,
    force: ForceOption = False,
) -> ExitStatus:
    """Write every icon colour's displayed output per mode and canvas.

    Reads the design tokens named by the project config's tokens: table. Each
    colour equals check's output for that icon colour and canvas, to the 8-bit code.
    """
    from alpha_audit.errors import UsageError
    from alpha_audit.export import ExportFormat, render_export, table_from_config, write_export
    from alpha_audit.load.config import project_config

    formats = [f.value for f in ExportFormat]
    if fmt not in formats:
        raise UsageError(f"--format {fmt!r} is not one of {', '.join(formats)}")
    gamut_policy = read_gamut_option(gamut)
    table = table_from_config(project_config(config, Path.cwd()), alpha=alpha, gamut=gamut_policy)
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
