"""Reports for ``alpha-audit themes``: the bundled themes as a table or ``alpha-audit/themes/1``."""

from __future__ import annotations

from typing import Any

from rich.console import RenderableType

from alpha_audit.model import Theme
from alpha_audit.render.common import (
    RenderOptions,
    dumps,
    fitted_table,
    name_column,
    number_column,
    to_text,
)

__all__ = ["THEMES_SCHEMA", "render_json", "render_table", "themes_document"]

THEMES_SCHEMA = "alpha-audit/themes/1"
Themes = tuple[tuple[str, Theme], ...]


def themes_document(themes: Themes) -> dict[str, Any]:
    """The themes as a JSON document: name, title, threshold and canvases."""
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


def _table(themes: Themes) -> RenderableType:
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
    return fitted_table(columns, rows, section_ends=frozenset(ends), collapse_padding=True)


def render_table(themes: Themes, options: RenderOptions) -> str:
    """One row per canvas, a rule between themes."""
    return to_text(_table(themes), options)


def render_json(themes: Themes, options: RenderOptions) -> str:
    """The ``alpha-audit/themes/1`` document (``options`` change nothing)."""
    return dumps(themes_document(themes))
