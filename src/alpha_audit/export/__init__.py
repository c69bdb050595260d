"""``alpha-audit export``: per-theme displayed colours in formats a product can ship.

No browser applies an alpha above 1 (CSS clamps ``opacity`` and alpha to
[0, 1]), so the audit's displayed colours are written out instead: DTCG
tokens, CSS custom properties, a Tailwind v4 ``@theme`` block, SVG filters
that do the compositing, and JSON.  :func:`export_project` audits the
project as ``check`` does and :func:`export_table` names the rows' outputs;
each format's renderer is a pure function of that table returning
``{file name: text}``; :func:`write_export` writes them atomically.
"""

from __future__ import annotations

import fnmatch
from dataclasses import replace
from enum import StrEnum
from pathlib import Path
from typing import TYPE_CHECKING, assert_never

from alpha_audit.color import Pipeline
from alpha_audit.errors import InputError, UsageError
from alpha_audit.export.table import ExportTable, export_table
from alpha_audit.load.config import ProjectConfig
from alpha_audit.model import GamutAdjustment, Theme

if TYPE_CHECKING:
    from alpha_audit.model import IconSet
    from alpha_audit.pipeline import Work

__all__ = [
    "ExportFormat",
    "ExportTable",
    "export_project",
    "export_table",
    "render_export",
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


def export_project(project: ProjectConfig) -> ExportTable:
    """The export of a resolved project config: ``check``'s rows of every icon colour.

    Every input is loaded and checked as ``check`` loads it
    (:func:`~alpha_audit.pipeline.plan`: YAML themes and manifests, design-token
    modes, the pipeline in force, the project's alpha), and each theme x icon set
    is audited by ``check``'s own :func:`~alpha_audit.pipeline.audit_pair`, each
    icon its manifest colour (no SVG is read: an icon's colour and coefficient are
    what is exported).  A project with design tokens and no icon set exports the
    token colours its ``tokens: colors:`` select, each audited as an icon of that
    colour at its token's coefficient.
    """
    from alpha_audit.pipeline import audit_pair, plan

    if project.path is None and not project.iconsets and project.tokens is None:
        raise UsageError(
            "no project config found (alpha-audit.yaml, .alpha-audit.yaml or "
            "[tool.alpha-audit] in pyproject.toml, from here up to the project root) and no "
            "THEME ICONSET given; export writes the colours of what check audits"
        )
    if project.iconsets:
        work, moved, notes = plan(project)
    else:
        work, moved, notes = _token_work(project)
    results = [
        audit_pair(project, theme, iconset, kind, None)
        for w in work
        for (theme, iconset), kind in zip(w.pairs, w.pipelines, strict=True)
    ]
    tokens = project.tokens
    if tokens is not None:
        source = tokens.file.name
    else:
        source = ", ".join(dict.fromkeys(Path(s).name for s in project.iconsets))
    gamut = project.gamut or (tokens.gamut if tokens is not None else None)
    aliases = [a for w in work for a in w.aliases]
    return export_table(
        results,
        source=source,
        gamut=gamut,
        adjusted=moved,
        notes=notes,
        aliases=list(dict.fromkeys(aliases)),
    )


def _token_work(
    project: ProjectConfig,
) -> tuple[list[Work], tuple[GamutAdjustment, ...], tuple[str, ...]]:
    """No icon set: every token colour the ``tokens: colors:`` select, as an icon of that
    colour at its token's coefficient, on each mode's canvases (and the config's YAML
    themes, with the first mode's colours, as ``check`` pairs them)."""
    from alpha_audit.load.theme import load_theme
    from alpha_audit.load.tokens.themes import load_token_themes
    from alpha_audit.model import Icon, IconSet
    from alpha_audit.pipeline import Work
    from alpha_audit.rows import check_combinations, check_pipeline, resolve_pipeline

    config = project.tokens
    if config is None:
        raise UsageError(
            "the project config names no iconsets: and no tokens:; export writes the "
            "colours of what check audits",
            path=project.path,
        )
    if not config.colors:
        raise UsageError(
            "the tokens: table has no colors: and the config names no iconsets:; name the "
            'icon-colour tokens (colors: "color.icon.*") or the icon sets',
            path=project.path,
        )
    if project.gamut is not None:
        config = replace(config, gamut=project.gamut)
    themes = load_token_themes(config)
    for pattern in config.colors:  # a glob that matches nothing would write an empty file
        if not any(fnmatch.fnmatchcase(p, pattern) for m in themes.modes for p in m.colors):
            raise InputError(
                f"colors: {pattern!r} matches no colour token of {config.file.name} "
                f"(modes {', '.join(m.name for m in themes.modes)})",
                path=project.path,
            )
    pairs: list[tuple[Theme, IconSet]] = []
    for mode in themes.modes:
        icons = []
        for path, color in mode.colors.items():
            alpha = color.alpha if color.alpha is not None else project.alpha
            if alpha is None:
                token = color.token
                raise InputError(
                    f"icon colour {path} (mode {mode.name}) has no coefficient: add "
                    "$extensions {com.alpha-audit: {alpha: ...}} to the token, alpha: to the "
                    "project config, or name the icon sets (iconsets:) whose alpha: applies",
                    path=token.file,
                    line=token.line,
                )
            icons.append(
                Icon(
                    path,
                    Path(path),
                    color.css,
                    float(alpha),
                    path,
                    token_file=color.token.file,
                    token_line=color.token.line,
                )
            )
        pairs.append((mode.theme, IconSet(mode.name, tuple(icons), path=config.file)))
    first = pairs[0][1] if pairs else IconSet("tokens", ())
    pairs += [(load_theme(t, gamut=project.gamut), first) for t in project.themes]
    canvases = sum(len(t.canvases) for t, _ in pairs)
    check_combinations(len(first.icons), canvases, 1, config.file, project.max_combinations)
    kinds: list[Pipeline] = []
    for theme, iconset in pairs:
        kind = resolve_pipeline(project.pipeline, theme.pipeline)
        check_pipeline(iconset, kind, project.alpha)
        kinds.append(kind)
    work = [Work(tuple(pairs), tuple(kinds), tuple(themes.aliases.items()))]
    return work, themes.adjusted, themes.notes
