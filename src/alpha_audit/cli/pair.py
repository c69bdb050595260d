"""``alpha-audit pair``: one colour on a few backgrounds at a few coefficients."""

from __future__ import annotations

from typing import Annotated

import typer

from alpha_audit.cli.console import emit, stdout_options
from alpha_audit.cli.options import ranged, read_gamut_option
from alpha_audit.cli.status import ExitStatus
from alpha_audit.constants import DEFAULT_GAMUT
from alpha_audit.ranges import ALPHA
from alpha_audit.render import PairFormat

__all__ = ["pair_command"]


def pair_command(
    color: Annotated[
        str,
        typer.Argument(help="Source colour: any CSS colour (#rrggbb, rgb(), oklch(), a name)."),
    ],
    on: Annotated[
        list[str],
        typer.Option(
            "--on", metavar="COLOR", help="Background colour (repeatable).", show_default=False
        ),
    ],
    alpha: Annotated[
        list[float] | None,
        ranged(
            "--alpha",
            "-a",
            allowed=ALPHA,
            metavar="A",
            help="Coefficient (repeatable). [default: 1, 1.1, 1.4]",
        ),
    ] = None,
    fmt: Annotated[
        PairFormat, typer.Option("--format", "-f", help="table or json.", case_sensitive=False)
    ] = PairFormat.TABLE,
    gamut: Annotated[
        str,
        typer.Option(
            "--gamut",
            metavar="clip|map|error",
            help="A colour outside sRGB (Tailwind v4's -500 steps): clip each channel (what "
            "browsers draw on an sRGB screen), map (CSS Color 4 gamut mapping) or error. "
            "The report says how far it moved.",
        ),
    ] = DEFAULT_GAMUT,
) -> ExitStatus:
    """Show one colour on a few backgrounds at a few coefficients.

    Output colour (8-bit hex), contrast at a = 1 -> at a, the gain, CIEDE2000 from the
    source colour, and whether any channel clipped.

    Example: [bold]alpha-audit pair "#ee7733" --on white --on "#0d1117" -a 1 -a 1.2[/]
    """
    from alpha_audit.pair import pair_report

    policy = read_gamut_option(gamut)
    report = pair_report(color, on, alpha or [1.0, 1.1, 1.4], gamut=policy or DEFAULT_GAMUT)
    emit(PairFormat(fmt).renderer()(report, stdout_options()), None, False)
    return ExitStatus.OK
