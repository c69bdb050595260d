"""The ``alpha-audit`` command line: a thin typer layer over the library.

Exit codes: 0 the audit ran (and the gate passed), 1 the gate failed,
2 bad input or usage.  Only this module turns exceptions into exit codes.
"""

from __future__ import annotations

import math
import sys
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from enum import IntEnum
from pathlib import Path
from typing import Annotated, Any

import typer
from rich.console import Console
from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn
from rich.text import Text
from typer.core import TyperGroup

from alpha_audit import __version__
from alpha_audit.errors import AlphaAuditError, UsageError
from alpha_audit.render import RenderOptions

__all__ = ["ExitStatus", "app", "main"]


class ExitStatus(IntEnum):
    """Process exit codes, documented in ``--help`` and the README."""

    OK = 0
    GATE_FAILED = 1
    INPUT_ERROR = 2


try:  # typer >= 0.22 vendors click
    from typer._click import exceptions as _click_exceptions
except ImportError:  # pragma: no cover - typer on a separate click
    from click import exceptions as _click_exceptions  # type: ignore[no-redef]

_ClickUsageError = _click_exceptions.UsageError
# `alpha-audit` alone prints help through this subclass: not an error line.
_NoArgsIsHelp = getattr(_click_exceptions, "NoArgsIsHelpError", ())


def _usage_line(exc: Exception) -> typer.Exit:
    """A click usage error as one line on stderr (typer would draw a boxed panel)."""
    ctx = getattr(exc, "ctx", None)
    message = " ".join(str(exc.format_message()).split())  # type: ignore[attr-defined]
    hint = f" (see '{ctx.command_path} -h')" if ctx is not None else ""
    _stderr().print(Text(f"alpha-audit: error: {message}{hint}"), soft_wrap=True)
    return typer.Exit(code=ExitStatus.INPUT_ERROR)


class _Group(TyperGroup):
    """The single boundary where library errors become one line and exit 2."""

    def make_context(self, *args: Any, **kwargs: Any) -> Any:
        try:
            return super().make_context(*args, **kwargs)
        except _NoArgsIsHelp:
            raise
        except _ClickUsageError as exc:  # the group's own options
            raise _usage_line(exc) from None

    def invoke(self, ctx: Any) -> Any:
        try:
            return super().invoke(ctx)
        except _NoArgsIsHelp:
            raise
        except _ClickUsageError as exc:  # a command's arguments and options
            raise _usage_line(exc) from None
        except AlphaAuditError as exc:
            _stderr().print(Text(f"alpha-audit: error: {exc}"), soft_wrap=True)
            raise typer.Exit(code=ExitStatus.INPUT_ERROR) from None
        except RecursionError:
            _stderr().print("alpha-audit: error: input nested too deeply", soft_wrap=True)
            raise typer.Exit(code=ExitStatus.INPUT_ERROR) from None


def _stderr() -> Console:
    return Console(stderr=True, highlight=False, emoji=False)


def _stdout() -> Console:
    return Console(highlight=False, emoji=False)


def stdout_options() -> RenderOptions:
    """Width and colour for a report on stdout (colour only on a terminal, never with NO_COLOR)."""
    console = _stdout()
    return RenderOptions(
        width=max(60, min(console.width, 120)),
        color=console.is_terminal and not console.no_color,
    )


@contextmanager
def progress_bar(label: str) -> Iterator[tuple[Callable[[int], None], Callable[[], None]]]:
    """A transient stderr progress bar, shown only on a terminal; yields (start, advance)."""
    console = _stderr()
    if not console.is_terminal:
        yield (lambda total: None), (lambda: None)
        return
    with Progress(
        TextColumn(label),
        BarColumn(),
        MofNCompleteColumn(),
        TimeElapsedColumn(),
        console=console,
        transient=True,
    ) as progress:
        task = progress.add_task(label, total=None)
        yield (lambda total: progress.update(task, total=total)), (lambda: progress.advance(task))


app = typer.Typer(
    cls=_Group,
    name="alpha-audit",
    help=(
        "Audit icon sets across light and dark themes with extended-alpha compositing.\n\n"
        "Each icon keeps a fixed source colour Cs and coefficient a; on a canvas Cb it shows "
        "as clip(Cb + a(Cs - Cb)) in linear sRGB. With a > 1 the icon moves away from whatever "
        "canvas it lands on. alpha-audit measures what that does to WCAG contrast, 8-bit "
        "collisions and CIEDE2000 separation on your icons and themes.\n\n"
        "Exit codes: 0 ran (gate passed), 1 gate failed (check), 2 bad input or usage."
    ),
    no_args_is_help=True,
    rich_markup_mode="rich",
    add_completion=False,
    pretty_exceptions_enable=False,
    context_settings={"help_option_names": ["-h", "--help"], "max_content_width": 100},
)


def _version(value: bool) -> None:
    if value:
        typer.echo(f"alpha-audit {__version__}")
        raise typer.Exit()


@app.callback()
def _root(
    version: Annotated[
        bool,
        typer.Option("--version", callback=_version, is_eager=True, help="Show the version."),
    ] = False,
) -> None:
    """Audit icon sets across light and dark themes with extended-alpha compositing."""


def require_finite(value: float | None, option: str) -> float | None:
    if value is not None and not math.isfinite(value):
        raise UsageError(f"{option} must be a finite number, got {value}")
    return value


def stderr_note(message: str) -> None:
    """One status line on stderr (never mixed into a report on stdout)."""
    _stderr().print(Text(f"alpha-audit: {message}"), soft_wrap=True)


def emit(text: str, output: Path | None, force: bool) -> None:
    """Report to stdout, or atomically to ``output``."""
    from alpha_audit.output import write_text

    if output is None:
        sys.stdout.write(text)
        sys.stdout.flush()
    else:
        write_text(output, text, overwrite=force)
        _stderr().print(f"wrote {output}", soft_wrap=True, markup=False)


from alpha_audit.cli_check import check_command  # noqa: E402  (commands register below)

app.command("check")(check_command)
from alpha_audit.cli_suggest import suggest_command  # noqa: E402

app.command("suggest")(suggest_command)
from alpha_audit.cli_preview import preview_command  # noqa: E402

app.command("preview")(preview_command)
from alpha_audit.cli_pair import pair_command  # noqa: E402

app.command("pair")(pair_command)
from alpha_audit.cli_reproduce import reproduce_command  # noqa: E402

app.command("reproduce")(reproduce_command)


def main() -> None:
    """Console-script entry point."""
    app()
