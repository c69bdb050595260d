"""``alpha-audit render``: audit icons as a browser draws them, and gate on what they show.

Parses flags, runs the page audit (:func:`alpha_audit.pages.audit_pages`),
makes its paints rows and judges them with the one gate
(:func:`alpha_audit.pages.page_report`) and writes each ``--format`` with
``check``'s renderers (:class:`~alpha_audit.render.CheckFormat`).  Exit 0
passed, 1 the gate failed, 2 bad input or a page state that could not be
audited (one line says which), 3 a bug.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace
from pathlib import Path
from typing import Annotated

import typer

from alpha_audit import ranges
from alpha_audit.browser import COLOR_SCHEMES
from alpha_audit.cli.console import progress_bar, stderr_note
from alpha_audit.cli.options import (
    ARGS,
    ConfigOption,
    ExitZeroOption,
    ForceOption,
    FormatsOption,
    OutputsOption,
    WriteBaselineOption,
    baseline_option,
    given_order,
    in_range,
    rules_flag,
)
from alpha_audit.cli.status import ExitStatus
from alpha_audit.errors import UsageError
from alpha_audit.pages.states import State, state_matrix
from alpha_audit.render import CheckFormat
from alpha_audit.rules import RENDER_DEFAULT_RULES, RENDER_RULES, RULES
from alpha_audit.safe_text import safe_text

__all__ = ["render_command"]

_ORDER = {"format": ("-f", "--format"), "output": ("-o", "--output")}
_NOT_RENDER = tuple(r.value for r in RULES if r not in RENDER_RULES)


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
    ctx: typer.Context,
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
    fail_on: Annotated[
        list[str] | None,
        typer.Option(
            "--fail-on",
            metavar="RULE",
            help="Rule that fails the gate (repeatable; replaces the policy): "
            + ", ".join(r.value for r in RENDER_RULES)
            + " (docs/rules.md).",
            show_default="the render: table's, else "
            + ", ".join(r.value for r in RENDER_RULES if r in RENDER_DEFAULT_RULES),
            callback=rules_flag("--fail-on", _NOT_RENDER, "it is a rule of check"),
        ),
    ] = None,
    exit_zero: ExitZeroOption = False,
    fmt: FormatsOption = None,
    output: OutputsOption = None,
    baseline: Annotated[Path | None, baseline_option("the render: table's baseline:")] = None,
    write_baseline: WriteBaselineOption = None,
    config: ConfigOption = None,
    force: ForceOption = False,
) -> ExitStatus:
    """Audit icons as a browser draws them, in every state, and gate on the contrast shown.

    Each page or story is loaded in each state (Storybook globals,
    prefers-color-scheme, a class or attribute on <html>), captured twice at
    device scale 2 (icons drawn, icons hidden) and every icon paint measured
    from the pixels: its colour at full coverage and the backdrop under it
    (the pair that limits), and the model's prediction under the linear and
    css pipelines.  Each paint is a row judged as check judges its rows:
    below-threshold fails the gate; render-drift (the page draws another
    colour than the manifest) and paints too thin to measure are reported.
    Pages reach nothing but loopback.  -f html writes one page that runs
    no script, with crops of each finding's icon as drawn and its backdrop.

    Exit codes: 0 the gate passed, 1 the gate failed, 2 bad input or a page
    that could not be audited, 3 a bug.

    [bold]alpha-audit render storybook-static --globals theme:light --globals theme:dark[/]
    """
    from alpha_audit.baseline import read_baseline
    from alpha_audit.cli.check import gate_status, pair_outputs, write_reports
    from alpha_audit.load.iconset import load_iconset
    from alpha_audit.output import check_targets
    from alpha_audit.pages import audit_pages, page_report
    from alpha_audit.pages.config import resolve_render_config
    from alpha_audit.render.pages import blocked_line

    order = given_order(ctx.meta.get(ARGS, ()), _ORDER)
    pairs = pair_outputs(list(fmt or [CheckFormat.TABLE]), list(output or []), order)
    files = [out for _, out in pairs if out is not None] + [write_baseline] * bool(write_baseline)
    check_targets([f for f in files if f is not None], overwrite=force)  # before the work
    settings = resolve_render_config(
        sources or [],
        config_path=config,
        start=Path.cwd(),
        stories=stories or (),
        states=states_from_flags(
            globals_values or [], color_scheme or [], html_attribute or [], html_class or []
        ),
        fail_on=fail_on or (),
        selector=selector,
        engines=tuple(dict.fromkeys(engine)) if engine else None,
        iconset=iconset,
        workers=workers,
        timeout=timeout,
        baseline=baseline,
    )
    if any(kind is CheckFormat.HTML for kind, _ in pairs):
        from alpha_audit.pages.crops import MAX_CROPS

        settings = replace(settings, crops=MAX_CROPS)  # cut while each page state is measured
    known = None
    if settings.baseline is not None and write_baseline is None:
        known = read_baseline(settings.baseline)
    manifest = load_iconset(settings.iconset) if settings.iconset is not None else None
    with progress_bar("rendering") as (start, advance):
        started = False

        def progress(done: int, total: int) -> None:
            nonlocal started
            if not started:
                start(total)
                started = True
            advance()

        run, paints = audit_pages(settings, manifest, progress=progress)
    report = page_report(
        run, paints, settings.policy, manifest, threshold=settings.threshold, baseline=known
    )
    write_reports(report, pairs, write_baseline, force)
    if run.blocked:
        stderr_note(blocked_line(run.blocked))
    if run.problems:
        first = run.problems[0]
        stderr_note(
            safe_text(
                f"error: {len(run.problems)} of {run.audited} page states could not be "
                f"audited; first: {first.source} [{first.state}, {first.engine}]: {first.message}"
            )
        )
        return ExitStatus.INPUT_ERROR
    return gate_status(
        report.gate, writing_baseline=write_baseline is not None, exit_zero=exit_zero
    )
