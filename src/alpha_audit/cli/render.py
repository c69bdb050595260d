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
from pathlib import Path
from typing import TYPE_CHECKING, Annotated

import typer

from alpha_audit import ranges
from alpha_audit.browser import COLOR_SCHEMES
from alpha_audit.cli.console import progress_bar, stderr_note
from alpha_audit.cli.options import (
    ConfigOption,
    ExitZeroOption,
    ForceOption,
    FormatsOption,
    OutputsOption,
    WriteBaselineOption,
    baseline_option,
    fail_on_option,
    ranged,
)
from alpha_audit.cli.status import ExitStatus
from alpha_audit.errors import UsageError
from alpha_audit.pages.states import State, state_matrix
from alpha_audit.render import CheckFormat
from alpha_audit.rules import RENDER_DEFAULT_RULES, RENDER_RULES, RULES
from alpha_audit.safe_text import safe_text

if TYPE_CHECKING:
    from alpha_audit.observed import PageRun

__all__ = ["render_command"]

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


# render's own options (the gate's shared ones are in cli/options.py).
_Sources = Annotated[
    list[str] | None,
    typer.Argument(
        help="Built Storybook folders (storybook-static/), folders of HTML pages, or "
        "http://localhost URLs. [default: the render: table of alpha-audit.yaml]",
        show_default=False,
    ),
]
_Stories = Annotated[
    list[str] | None,
    typer.Option("--stories", help="Glob over story ids or Title/Name (repeatable)."),
]
_Globals = Annotated[
    list[str] | None,
    typer.Option("--globals", help="Storybook globals of one state, NAME:VALUE;... (repeatable)."),
]
_ColorScheme = Annotated[
    list[str] | None,
    typer.Option("--color-scheme", help="Emulated prefers-color-scheme: light, dark."),
]
_HtmlAttribute = Annotated[
    list[str] | None,
    typer.Option("--html-attribute", help="NAME=VALUE set on <html> (repeatable)."),
]
_HtmlClass = Annotated[
    list[str] | None,
    typer.Option("--html-class", help="A class set on <html> (repeatable; '' for none)."),
]
_Selector = Annotated[
    str | None, typer.Option(help="CSS selector of more elements to audit as icons.")
]
_Engine = Annotated[
    list[str] | None,
    typer.Option("--engine", help="chromium (default), firefox, webkit (repeatable)."),
]
_Iconset = Annotated[Path | None, typer.Option(help="Icon-set manifest the icons are mapped to.")]
_Workers = Annotated[
    int | None,
    ranged(
        "--workers",
        allowed=ranges.WORKERS,
        help="Pages in parallel.",
        show_default="CPUs, at most 4",
    ),
]
_Timeout = Annotated[
    float | None,
    ranged(
        "--timeout",
        allowed=ranges.PAGE_SECONDS,
        help="Seconds per page and state.",
        show_default="30",
    ),
]
_FailOn = Annotated[
    list[str] | None,
    fail_on_option(
        (r.value for r in RENDER_RULES),
        (r.value for r in RENDER_RULES if r in RENDER_DEFAULT_RULES),
        "the render: table's",
        _NOT_RENDER,
        "it is a rule of check",
    ),
]


def _said_problems(run: PageRun) -> bool:
    """The blocked requests and the page states that could not be audited, on stderr;
    whether there were any of the latter (render then exits 2)."""
    from alpha_audit.render.pages import blocked_line, problems_line

    if run.blocked:
        stderr_note(blocked_line(run.blocked))
    if run.problems:
        stderr_note(safe_text(problems_line(run)))
    return bool(run.problems)


def render_command(
    ctx: typer.Context,
    sources: _Sources = None,
    stories: _Stories = None,
    globals_values: _Globals = None,
    color_scheme: _ColorScheme = None,
    html_attribute: _HtmlAttribute = None,
    html_class: _HtmlClass = None,
    selector: _Selector = None,
    engine: _Engine = None,
    iconset: _Iconset = None,
    workers: _Workers = None,
    timeout: _Timeout = None,
    fail_on: _FailOn = None,
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
    from alpha_audit.cli.check import gate_status, report_targets, write_reports
    from alpha_audit.load.iconset import load_iconset
    from alpha_audit.pages import audit_pages, page_report
    from alpha_audit.pages.config import resolve_render_config
    from alpha_audit.pages.crops import MAX_CROPS

    pairs = report_targets(ctx, fmt, output, write_baseline, force)
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
        # Crops are cut while each page state is measured, for the html report only.
        crops=MAX_CROPS if any(kind is CheckFormat.HTML for kind, _ in pairs) else None,
    )
    base = settings.baseline if write_baseline is None else None
    known = read_baseline(base) if base is not None else None
    manifest = load_iconset(settings.iconset) if settings.iconset is not None else None
    with progress_bar("rendering") as progress:
        run, paints = audit_pages(settings, manifest, progress=progress)
    report = page_report(
        run, paints, settings.policy, manifest, threshold=settings.threshold, baseline=known
    )
    write_reports(report, pairs, write_baseline, force)
    if _said_problems(run):
        return ExitStatus.INPUT_ERROR
    return gate_status(
        report.gate, writing_baseline=write_baseline is not None, exit_zero=exit_zero
    )
