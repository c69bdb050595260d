"""``alpha-audit render``: audit icons as a browser draws them (provisional).

Prints the measured paints (:mod:`alpha_audit.pages`) as a table or as JSON
(``alpha-audit.render/1``).  Until the measured paints become paint rows, this
command has no gate: it exits 0 when every page and state was audited, 2 when
the input is unusable or a page could not be audited (one line says which).
"""

from __future__ import annotations

import enum
from collections.abc import Sequence
from pathlib import Path
from typing import Annotated, assert_never

import typer
from rich import box

from alpha_audit import ranges
from alpha_audit.browser import COLOR_SCHEMES
from alpha_audit.cli.console import emit, progress_bar, stderr_note, stdout_options
from alpha_audit.cli.options import ConfigOption, ForceOption, in_range
from alpha_audit.cli.status import ExitStatus
from alpha_audit.errors import UsageError
from alpha_audit.pages.states import State, state_matrix

__all__ = ["RenderFormat", "render_command"]


class RenderFormat(enum.StrEnum):
    """What ``render`` prints."""

    TABLE = "table"
    JSON = "json"


def _figure(value: float | None) -> str:
    return "-" if value is None else f"{value:.2f}"


def _table_text(result: object) -> str:
    from alpha_audit.pages import RenderResult
    from alpha_audit.render.common import fitted_table, name_column, number_column, to_text

    assert isinstance(result, RenderResult)
    rows = []
    for p in result.paints:
        linear, css = p.prediction("linear"), p.prediction("css")
        rows.append(
            (
                p.source,
                p.state,
                p.icon or p.dom_path.rsplit(" > ", 1)[-1],
                p.drawn or "-",
                p.behind or "-",
                _figure(p.contrast_worst),
                _figure(p.contrast_median),
                _figure(linear.contrast if linear else None),
                _figure(css.contrast if css else None),
                _figure(p.render_drift),
            )
        )
    columns = [name_column("source", 8), name_column("state", 5), name_column("icon", 6)]
    columns += [number_column(h, "left") for h in ("drawn", "behind")]
    columns += [number_column(h) for h in ("worst", "median", "linear", "css", "drift")]
    table = fitted_table(columns, rows, box=box.SIMPLE_HEAD, pad_edge=False)
    summary = (
        f"{result.audited} page states, {result.icons} icons, {len(result.paints)} paints; "
        f"{len(result.failing)} below {result.paints[0].threshold if result.paints else 3:g}:1 "
        f"at their worst pixel; {len(result.blocked)} requests blocked\n"
    )
    return to_text(table, stdout_options()) + summary


def parse_globals(text: str) -> tuple[tuple[str, str], ...]:
    """``theme:dark;density:compact`` (a ``--globals`` value) -> pairs; ``:`` is required."""
    pairs = []
    for part in text.split(";"):
        name, sep, value = part.partition(":")
        if not sep or not name.strip() or not value.strip():
            raise UsageError(
                f"--globals {text!r}: write NAME:VALUE pairs joined by ';' (theme:dark)"
            )
        pairs.append((name.strip(), value.strip()))
    return tuple(pairs)


def parse_attribute(text: str) -> tuple[str, str]:
    """``data-theme=dark`` (an ``--html-attribute`` value) -> ``(name, value)``."""
    name, sep, value = text.partition("=")
    if not sep or not name.strip():
        raise UsageError(f"--html-attribute {text!r}: write NAME=VALUE (data-theme=dark)")
    return name.strip(), value.strip()


def states_from_flags(
    globals_values: Sequence[str],
    schemes: Sequence[str],
    attributes: Sequence[str],
    classes: Sequence[str],
) -> tuple[State, ...] | None:
    """The state matrix the flags ask for, or None when no state flag was given."""
    if not (globals_values or schemes or attributes or classes):
        return None
    for scheme in schemes:
        if scheme not in COLOR_SCHEMES:
            raise UsageError(f"--color-scheme {scheme!r}: choose light or dark")
    return state_matrix(
        [parse_globals(g) for g in globals_values],
        [s for s in schemes if s in COLOR_SCHEMES],
        [parse_attribute(a) for a in attributes],
        list(classes),
    )


def render_command(
    sources: Annotated[
        list[str] | None,
        typer.Argument(
            help="Built Storybook folders (storybook-static/), folders of HTML pages, or "
            "http://localhost URLs. [default: the render: table of alpha-audit.yaml]",
            show_default=False,
        ),
    ] = None,
    stories: Annotated[
        list[str] | None,
        typer.Option("--stories", help="Glob over story ids or Title/Name (repeatable)."),
    ] = None,
    globals_values: Annotated[
        list[str] | None,
        typer.Option(
            "--globals", help="Storybook globals of one state, NAME:VALUE;... (repeatable)."
        ),
    ] = None,
    color_scheme: Annotated[
        list[str] | None,
        typer.Option("--color-scheme", help="Emulated prefers-color-scheme: light, dark."),
    ] = None,
    html_attribute: Annotated[
        list[str] | None,
        typer.Option("--html-attribute", help="NAME=VALUE set on <html> (repeatable)."),
    ] = None,
    html_class: Annotated[
        list[str] | None,
        typer.Option("--html-class", help="A class set on <html> (repeatable; '' for none)."),
    ] = None,
    selector: Annotated[
        str | None, typer.Option(help="CSS selector of more elements to audit as icons.")
    ] = None,
    engine: Annotated[
        list[str] | None,
        typer.Option("--engine", help="chromium (default), firefox, webkit (repeatable)."),
    ] = None,
    iconset: Annotated[
        Path | None, typer.Option(help="Icon-set manifest the icons are mapped to.")
    ] = None,
    workers: Annotated[
        int | None,
        typer.Option(
            help="Pages in parallel.",
            callback=in_range("--workers", ranges.WORKERS),
            show_default="CPUs, at most 4",
        ),
    ] = None,
    timeout: Annotated[
        float | None,
        typer.Option(
            help="Seconds per page and state.",
            callback=in_range("--timeout", ranges.PAGE_SECONDS),
            show_default="30",
        ),
    ] = None,
    fmt: Annotated[
        RenderFormat,
        typer.Option("--format", "-f", help="table or json.", case_sensitive=False),
    ] = RenderFormat.TABLE,
    output: Annotated[
        Path | None, typer.Option("--output", "-o", help="Write the report to FILE.")
    ] = None,
    config: ConfigOption = None,
    force: ForceOption = False,
) -> ExitStatus:
    """Audit icons as a browser draws them, in every state (provisional: no gate yet).

    Each page or story is loaded in each state (Storybook globals,
    prefers-color-scheme, a class or attribute on <html>), captured twice at
    device scale 2 (icons drawn, icons hidden) and every icon paint measured
    from the pixels: drawn colour, backdrop, WCAG contrast (worst and median
    pixel), and the model's prediction under the linear and css pipelines.
    Pages reach nothing but loopback.

    [bold]alpha-audit render storybook-static --globals theme:light --globals theme:dark[/]
    """
    from alpha_audit.load.iconset import load_iconset
    from alpha_audit.pages import audit_pages
    from alpha_audit.pages.config import resolve_render_config
    from alpha_audit.pages.report import render_document
    from alpha_audit.render.common import dumps

    settings = resolve_render_config(
        sources or [],
        config_path=config,
        start=Path.cwd(),
        stories=stories or (),
        states=states_from_flags(
            globals_values or [], color_scheme or [], html_attribute or [], html_class or []
        ),
        selector=selector,
        engines=tuple(dict.fromkeys(engine)) if engine else None,
        iconset=iconset,
        workers=workers,
        timeout=timeout,
    )
    manifest = load_iconset(settings.iconset) if settings.iconset is not None else None
    with progress_bar("rendering") as (start, advance):
        started = False

        def progress(done: int, total: int) -> None:
            nonlocal started
            if not started:
                start(total)
                started = True
            advance()

        result = audit_pages(settings, manifest, progress=progress)
    match fmt:
        case RenderFormat.TABLE:
            emit(_table_text(result), output, force)
        case RenderFormat.JSON:
            emit(dumps(render_document(result)), output, force)
        case _:
            assert_never(fmt)
    if result.blocked:
        stderr_note(f"{len(result.blocked)} requests to anything but the pages' server blocked")
    if result.problems:
        first = result.problems[0]
        stderr_note(
            f"error: {len(result.problems)} of {result.audited} page states could not be "
            f"audited; first: {first.source} [{first.state}, {first.engine}]: {first.message}"
        )
        return ExitStatus.INPUT_ERROR
    return ExitStatus.OK
