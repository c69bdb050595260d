"""``alpha-audit themes``: the bundled themes and their canvases."""

from __future__ import annotations

from typing import Annotated

import typer

from alpha_audit.cli.console import emit, stdout_options
from alpha_audit.cli.status import ExitStatus
from alpha_audit.render import ThemesFormat

__all__ = ["themes_command"]


def themes_command(
    fmt: Annotated[
        ThemesFormat,
        typer.Option("--format", "-f", help="Output format.", case_sensitive=False),
    ] = ThemesFormat.TABLE,
) -> ExitStatus:
    """List the bundled themes and their canvases.

    A THEME argument that is not an existing file may name one of these, and
    ICONSET may be [bold]vibrant[/] (the bundled example icon set), so this works
    from any folder:

    [bold]alpha-audit check github-primer vibrant[/]
    """
    from alpha_audit.load.theme import load_bundled_themes

    emit(fmt.renderer()(load_bundled_themes(), stdout_options()), None, False)
    return ExitStatus.OK
