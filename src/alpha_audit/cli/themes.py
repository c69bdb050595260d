"""``alpha-audit themes``: the bundled themes and their canvases."""

from __future__ import annotations

import enum
from typing import Annotated, Any, assert_never

import typer
from rich import box
from rich.table import Table

from alpha_audit.bundled import load_bundled_themes
from alpha_audit.cli.console import emit, stdout_options
from alpha_audit.cli.status import ExitStatus
from alpha_audit.model import Theme
from alpha_audit.render.common import dumps, fitted_table, name_column, number_column, to_text

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
    """Names wrap, hex codes never cut (render.common.fitted_table)."""
    rows = [
        (name if i == 0 else "", canvas.name, canvas.color, str(canvas.mode))
        for name, theme in themes
        for i, canvas in enumerate(theme.canvases)
    ]
    columns = [name_column("theme", 6), name_column("canvas", 8)]
    columns += [number_column("colour", "left"), name_column("mode", 5)]
    ends, n = set(), -1
    for _, theme in themes:
        n += len(theme.canvases)
        ends.add(n)
    return fitted_table(
        columns,
        rows,
        section_ends=frozenset(ends),
        box=box.SIMPLE_HEAD,
        pad_edge=False,
        collapse_padding=True,
    )


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
            # Rendered like every report: no escape codes with NO_COLOR or off a terminal.
            emit(to_text(_table(themes), stdout_options()), None, False)
        case ThemesFormat.JSON:
            emit(dumps(themes_document(themes)), None, False)
        case _:
            assert_never(fmt)
    return ExitStatus.OK
