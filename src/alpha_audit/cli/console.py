"""Terminal helpers every command shares: consoles, status lines, progress, report output.

Reports go to stdout (or atomically to a file); everything else goes to
stderr, so a report piped into a file is never mixed with status lines.
"""

from __future__ import annotations

import sys
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path

from rich.console import Console
from rich.progress import (
    BarColumn,
    MofNCompleteColumn,
    Progress,
    ProgressColumn,
    TaskID,
    TextColumn,
    TimeElapsedColumn,
)
from rich.text import Text

from alpha_audit.output import write_text
from alpha_audit.render import RenderOptions
from alpha_audit.safe_text import safe_text

__all__ = [
    "emit",
    "progress_bar",
    "progress_bars",
    "stderr_console",
    "stderr_line",
    "stderr_note",
    "stdout_console",
    "stdout_options",
]


def stderr_console() -> Console:
    """A console on stderr that never reads markup or emoji codes into what it prints."""
    return Console(stderr=True, highlight=False, emoji=False)


def stdout_console() -> Console:
    """A console on stdout, for reports rendered by rich."""
    return Console(highlight=False, emoji=False)


def stdout_options() -> RenderOptions:
    """Width and colour for a report on stdout (colour only on a terminal, never with NO_COLOR)."""
    console = stdout_console()
    return RenderOptions(
        width=max(60, min(console.width, 120)),
        color=console.is_terminal and not console.no_color,
    )


@contextmanager
def _bars(*columns: ProgressColumn) -> Iterator[Progress | None]:
    """Transient progress bars on stderr, timed; None where stderr is not a terminal."""
    console = stderr_console()
    if not console.is_terminal:
        yield None
        return
    with Progress(*columns, TimeElapsedColumn(), console=console, transient=True) as bars:
        yield bars


@contextmanager
def progress_bar(label: str) -> Iterator[tuple[Callable[[int], None], Callable[[], None]]]:
    """A transient stderr progress bar, shown only on a terminal; yields (start, advance)."""
    with _bars(TextColumn(label), BarColumn(), MofNCompleteColumn()) as bars:
        if bars is None:
            yield (lambda total: None), (lambda: None)
            return
        task = bars.add_task(label, total=None)
        yield (lambda total: bars.update(task, total=total)), (lambda: bars.advance(task))


@contextmanager
def progress_bars() -> Iterator[Callable[[str, float], None]]:
    """Transient stderr bars, one per name, each advanced by fractions of 1 (on a terminal)."""
    with _bars(TextColumn("{task.description:<12}"), BarColumn()) as bars:
        tasks: dict[str, TaskID] = {}

        def advance(name: str, fraction: float) -> None:
            if bars is not None:
                if name not in tasks:
                    tasks[name] = bars.add_task(name, total=1.0)
                bars.advance(tasks[name], fraction)

        yield advance


def stderr_line(text: str) -> None:
    """One line on stderr, printed literally and inert.

    Names from input files are not markup, and a control, bidi or surrogate
    character in them (or in a path or value from the command line) is shown
    as an escape: a newline cannot start a workflow command of its own, ESC
    cannot drive the terminal (:func:`~alpha_audit.safe_text.safe_text`).
    """
    stderr_console().print(Text(safe_text(text)), soft_wrap=True)


def stderr_note(message: str) -> None:
    """One status line on stderr (:func:`stderr_line`), after ``alpha-audit:``."""
    stderr_line(f"alpha-audit: {message}")


def emit(text: str, output: Path | None, force: bool) -> None:
    """Report to stdout, or atomically to ``output`` (replacing a file only with ``force``)."""
    if output is None:
        sys.stdout.write(text)
        sys.stdout.flush()
    else:
        write_text(output, text, overwrite=force)
        stderr_line(f"wrote {output}")
