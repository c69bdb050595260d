"""``alpha-audit themes``: the bundled themes and their canvases."""

from __future__ import annotations

import enum
from typing import Annotated, Any, assert_never

import typer
from rich import box
from rich.table import Table
from rich.text import Text

from alpha_audit.bundled import load_bundled_themes
from alpha_audit.cli.console import emit, stdout_console
from alpha_audit.cli.status import ExitStatus
from alpha_audit.model import Theme
from alpha_audit.render.json import dumps

__all__ = ["ThemesFormat", "themes_command", "themes_document"]

THEMES_SCHEMA = "alpha-audit/themes/1"


class ThemesFormat(enum.StrEnum):
    """What ``themes`` prints."""

    TABLE = "table"
    JSON = "json"


def themes_document(themes: tuple[tuple[str, Theme], ...]) -> dict[str, Any]:
    """The bundled themes as a JSON document: name, title, threshold and canvases."""
    return {
        "schema": THEMES_SCHEMA,
        "themes": [
            {
                "name": name,
                "title": theme.name,
                "threshold": theme.threshold,
                "canvases": [
                    {"name": c.name, "color": c.color, "mode": c.mode} for c in theme.canvases
                ],
            }
            for name, theme in themes
        ],
    }


def _table(themes: tuple[tuple[str, Theme], ...]) -> Table:
    table = Table(box=box.SIMPLE_HEAD, pad_edge=False, collapse_padding=True)
    for column in ("theme", "canvas", "colour", "mode"):
        table.add_column(column, no_wrap=True)
    for name, theme in themes:
        for i, canvas in enumerate(theme.canvases):
            table.add_row(
                Text(name if i == 0 else ""),
                Text(canvas.name),
                Text(canvas.color),
                Text(str(canvas.mode)),
                end_section=i == len(theme.canvases) - 1,
            )
    return table


def themes_command(
    fmt: Annotated[
        ThemesFormat,
        typer.Option("--format", "-f", help="table or json.", case_sensitive=False),
    ] = ThemesFormat.TABLE,
) -> ExitStatus:
    """List the bundled themes and their canvases.

    A THEME argument that is not an existing file may name one of these, and
    ICONSET may be [bold]vibrant[/] (the bundled example icon set), so this works
    from any folder:

    [bold]alpha-audit check github-primer vibrant[/]
    """
    themes = load_bundled_themes()
    match fmt:
        case ThemesFormat.TABLE:
            stdout_console().print(_table(themes))
        case ThemesFormat.JSON:
            emit(dumps(themes_document(themes)), None, False)
        case _:
            assert_never(fmt)
    return ExitStatus.OK
