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
from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn
from rich.text import Text

from alpha_audit.output import write_text
from alpha_audit.render import RenderOptions
from alpha_audit.safe_text import safe_text

__all__ = [
    "emit",
    "progress_bar",
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
def progress_bar(label: str) -> Iterator[tuple[Callable[[int], None], Callable[[], None]]]:
    """A transient stderr progress bar, shown only on a terminal; yields (start, advance)."""
    console = stderr_console()
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
