"""``alpha-audit export``: per-theme displayed colours in formats a product can ship.

No browser applies an alpha above 1 (CSS clamps ``opacity`` and alpha to
[0, 1]), so the audit's displayed colours are written out instead: DTCG
tokens, CSS custom properties, a Tailwind v4 ``@theme`` block, SVG filters
that do the compositing, and JSON.  :func:`export_table` computes the
numbers; each format's renderer is a pure function of that table returning
``{file name: text}``; :func:`write_export` writes them atomically.
"""

from __future__ import annotations

import fnmatch
from enum import StrEnum
from pathlib import Path
from typing import assert_never

from alpha_audit.color.css import GamutPolicy
from alpha_audit.errors import InputError, UsageError
from alpha_audit.export.table import ExportTable, export_table
from alpha_audit.load.config import ProjectConfig

__all__ = [
    "ExportFormat",
    "ExportTable",
    "export_table",
    "render_export",
    "table_from_config",
    "write_export",
]


class ExportFormat(StrEnum):
    """Output formats of ``alpha-audit export``."""

    DTCG = "dtcg"
    RESOLVER = "resolver"
    CSS = "css"
    TAILWIND = "tailwind"
    SVG = "svg"
    JSON = "json"


def render_export(
    table: ExportTable, fmt: ExportFormat | str, *, selector: str | None = None
) -> dict[str, str]:
    """``{file name: text}`` of ``table`` in ``fmt`` (one file, or one per mode for dtcg)."""
    fmt = ExportFormat(fmt)
    if fmt is ExportFormat.DTCG:
        from alpha_audit.export.dtcg import render_dtcg

        return render_dtcg(table)
    if fmt is ExportFormat.RESOLVER:
        from alpha_audit.export.dtcg import render_resolver

        return {"colors.resolver.json": render_resolver(table)}
    if fmt is ExportFormat.CSS:
        from alpha_audit.export.css import DEFAULT_SELECTOR, render_css

        return {"colors.css": render_css(table, selector=selector or DEFAULT_SELECTOR)}
    if fmt is ExportFormat.TAILWIND:
        from alpha_audit.export.tailwind import render_tailwind

        return {"theme.css": render_tailwind(table)}
    if fmt is ExportFormat.SVG:
        from alpha_audit.export.svg import render_svg

        return {"filters.svg": render_svg(table)}
    if fmt is ExportFormat.JSON:
        from alpha_audit.export.json import render_json

        return {"colors.json": render_json(table)}
    assert_never(fmt)


def write_export(
    files: dict[str, str], folder: str | Path, *, overwrite: bool = False
) -> list[Path]:
    """Write every file into ``folder`` (created if missing) through the one writer.

    Every target is checked first (:func:`alpha_audit.output.check_targets`), so
    nothing is written if any would be refused; each file is replaced atomically.
    """
    from alpha_audit.output import Output, check_targets, make_folder, write_files

    out = Path(folder)
    if out.exists() and not out.is_dir():
        raise UsageError("is not a folder", path=out)
    targets = [out / name for name in files]
    if out.is_dir():
        check_targets(targets, overwrite=overwrite)
    make_folder(out)
    return write_files([Output.text(t, files[t.name]) for t in targets], overwrite=overwrite)


def table_from_config(
    config: ProjectConfig, *, alpha: float | None = None, gamut: GamutPolicy | None = None
) -> ExportTable:
    """The export table of a project config's ``tokens:`` (``gamut`` overrides its policy).

    Colours without a coefficient in their token take ``alpha``, else the
    config's ``alpha:``.
    """
    from dataclasses import replace

    from alpha_audit.load.tokens.themes import load_token_themes

    if config.tokens is None:
        if config.path is None:
            raise UsageError(
                "no project config found (alpha-audit.yaml, .alpha-audit.yaml or "
                "[tool.alpha-audit] in pyproject.toml, from here up to the project root); "
                "export reads the design tokens its tokens: table names"
            )
        raise UsageError(
            f"the project config ({config.path}) has no tokens: table; export reads tokens"
        )
    tokens = config.tokens if gamut is None else replace(config.tokens, gamut=gamut)
    if not tokens.colors:
        raise UsageError(
            f"the tokens: table of {config.path} has no colors:; export writes icon colours"
        )
    themes = load_token_themes(tokens)
    for pattern in tokens.colors:  # a glob that matches nothing would write an empty file
        if not any(fnmatch.fnmatchcase(p, pattern) for m in themes.modes for p in m.colors):
            raise InputError(
                f"colors: {pattern!r} matches no colour token of {tokens.file.name} "
                f"(modes {', '.join(m.name for m in themes.modes)})",
                path=config.path,
            )
    return export_table(themes, alpha=alpha, default_alpha=config.alpha)
