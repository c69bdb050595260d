"""The ``alpha-audit`` application: its commands, ``main`` and the one exit boundary.

Each command function returns an :class:`~alpha_audit.cli.status.ExitStatus`;
only :class:`_Group` here turns results and exceptions into exit codes:

* the command's status (0 passed, 1 gate failed);
* 2 for :class:`~alpha_audit.errors.AlphaAuditError` (bad input or usage),
  a usage error typer found, an OS error on a file, input nested too deeply
  and running out of memory, each as one line on stderr;
* 3 for any other exception: a bug, reported in one line with the exception's
  type and text; the traceback only with ``--debug`` or ``ALPHA_AUDIT_DEBUG=1``.

Command modules never import this module (they import :mod:`.console`,
:mod:`.options` and :mod:`.status`), so the package has no import cycle.
"""

from __future__ import annotations

import errno
import os
import re
import sys
import traceback
from collections.abc import Iterable, Sequence
from functools import cache
from importlib import import_module
from pathlib import Path
from typing import Annotated, Any, NoReturn

import typer
from typer.core import TyperGroup

from alpha_audit import __version__
from alpha_audit.cli.console import stderr_line
from alpha_audit.cli.flags import cli_message
from alpha_audit.cli.options import ARGS, Command, given_options, untyped_flags
from alpha_audit.cli.status import ExitStatus
from alpha_audit.errors import AlphaAuditError
from alpha_audit.safe_text import safe_text
from alpha_audit.signals import ending_on_signals

__all__ = ["COMMANDS", "ExitStatus", "app", "application", "main"]

app: typer.Typer  # every command, built on first use (module __getattr__ below)

DEBUG_ENV = "ALPHA_AUDIT_DEBUG"


def _error_line(message: str) -> None:
    """``alpha-audit: error: ...`` on stderr, one line printed literally (messages quote input)."""
    stderr_line(f"alpha-audit: error: {message}")


def _usage_error(exc: typer.TyperException) -> NoReturn:
    """A usage error typer found, as one line naming the command and where help is."""
    ctx = getattr(exc, "ctx", None)
    path = ctx.command_path if ctx is not None else "alpha-audit"
    message = exc.format_message().rstrip(".")
    param = getattr(exc, "param", None)
    if ctx is not None and param is not None:
        given = given_options(ctx.meta.get(ARGS, []), {"": getattr(param, "opts", [])})
        message = _plain_words(message, given[-1][1] if given else None)
    _error_line(f"{message} (see '{path} --help')")
    raise typer.Exit(ExitStatus.INPUT_ERROR)


# typer 0.29 coerces values with pydantic and passes its wording on; say it plainly.
_PYDANTIC_WORDS = (
    (re.compile(r"Input should be a valid number[^;]*"), "{value} is not a number"),
    (re.compile(r"Input should be a valid integer[^;]*"), "{value} is not a whole number"),
    (re.compile(r"Value error, "), ""),
)


def _plain_words(message: str, value: str | None) -> str:
    """``message`` without pydantic's phrasing, naming the value given where it is known."""
    shown = repr(value) if value is not None else "the value given"
    for pattern, words in _PYDANTIC_WORDS:
        # Split and joined, not pattern.sub(template): a backslash in the value
        # (``-a '1\x2'``) would be read as a group escape and crash.
        message = words.format(value=shown).join(pattern.split(message))
    return message


def _memory_limit() -> str:
    """The address-space limit this process runs under, in words."""
    try:
        import resource
    except ImportError:  # pragma: no cover - not POSIX
        return "the memory available"
    soft, _ = resource.getrlimit(resource.RLIMIT_AS)
    if soft == resource.RLIM_INFINITY:
        return "the memory available (no address-space limit is set)"
    return f"the address-space limit of {soft / (1 << 20):.0f} MiB"


MAX_REASON = 200
"""Characters of an unexpected exception's text kept in its one-line report."""


# Errors of the environment a write meets (errno names): the output, not alpha-audit, failed.
_WRITE_ERRORS = frozenset(
    getattr(errno, n)
    for n in ("ENOSPC", "EIO", "EPIPE", "EBADF", "EFBIG", "EDQUOT", "EROFS")
    if hasattr(errno, n)
)


def _project() -> Path | None:
    """The project root of the working folder, which error lines name files relative to."""
    from alpha_audit.load.paths import PathRefused, project_root

    try:
        return project_root(Path.cwd())
    except (OSError, PathRefused):  # the working folder is gone or unreadable
        return None


def _classify(exc: Exception) -> tuple[ExitStatus, str]:
    """The exit code ``exc`` means and the one line that says why."""
    if isinstance(exc, AlphaAuditError):
        return ExitStatus.INPUT_ERROR, cli_message(exc, _project())
    if isinstance(exc, MemoryError):
        return ExitStatus.INPUT_ERROR, (
            f"out of memory: the inputs need more than {_memory_limit()}; "
            "audit fewer icons, canvases or colours at once"
        )
    if isinstance(exc, RecursionError):
        return ExitStatus.INPUT_ERROR, "input nested too deeply (Python's recursion limit)"
    if isinstance(exc, OSError) and exc.filename is not None:
        # The environment refused (permissions, a full disk): not a bug, and the file says where.
        return ExitStatus.INPUT_ERROR, safe_text(f"{exc.filename}: {exc.strerror or exc}")
    if isinstance(exc, OSError) and exc.errno in _WRITE_ERRORS:
        # Writing a report to stdout failed (a full disk, a closed or broken stream).
        return ExitStatus.INPUT_ERROR, f"cannot write the output: {exc.strerror or exc}"
    reason = " ".join(str(exc).split("\n", 1)[0].split())[:MAX_REASON]
    return ExitStatus.INTERNAL_ERROR, (
        "internal error (a bug in alpha-audit, please report it): "
        + (f"{type(exc).__name__}: {reason}" if reason else type(exc).__name__)
    )


def _stdout_failed(exc: BaseException) -> bool:
    """Whether ``exc`` is a failed write to a stream, not to a named file."""
    return isinstance(exc, OSError) and exc.filename is None and exc.errno in _WRITE_ERRORS


def _detach_stdout() -> None:
    """Point stdout at ``/dev/null``, so that the flush at exit cannot fail a second time.

    Python flushes ``sys.stdout`` as it exits; into a closed pipe that is another
    ``BrokenPipeError``, printed as "Exception ignored" and exit 120 (the recipe of
    the ``signal`` module's documentation, "Note on SIGPIPE").
    """
    try:
        null = os.open(os.devnull, os.O_WRONLY)
        os.dup2(null, sys.stdout.fileno())
        os.close(null)
    except (OSError, ValueError):  # no stdout descriptor (an embedding host): nothing to flush
        pass


def _help_into_closed_pipe(exc: SystemExit) -> None:
    """Exit 2 with one line if rich ended the run because help met a closed pipe.

    typer prints help through rich, whose ``Console.on_broken_pipe`` (documented
    behaviour) points stdout at ``/dev/null`` and raises ``SystemExit(1)``: the
    gate's code.  Commands never raise ``SystemExit(1)`` themselves.
    """
    if exc.code != 1:
        return
    try:
        detached = os.path.samestat(os.fstat(sys.stdout.fileno()), os.stat(os.devnull))
    except (OSError, ValueError):
        return
    if detached:
        _error_line("cannot write the output: Broken pipe")
        raise typer.Exit(ExitStatus.INPUT_ERROR) from exc


def _exit_code(exc: Exception, *, debug: bool) -> ExitStatus:
    """Report ``exc`` on stderr in one line (plus the traceback with ``debug``)."""
    status, line = _classify(exc)
    if _stdout_failed(exc):
        _detach_stdout()
    if status is ExitStatus.INTERNAL_ERROR and not debug:
        line += f" (--debug or {DEBUG_ENV}=1 for details)"
    _error_line(line)
    if debug:
        traceback.print_exception(exc)
    return status


def _cache_notes() -> None:
    """Say why the render cache went unused or was replaced, if the command opened it."""
    cache = sys.modules.get("alpha_audit.load.render_cache")
    for note in cache.take_notes() if cache is not None else ():
        stderr_line(f"alpha-audit: {safe_text(note)}")


class _Group(TyperGroup):
    """The single boundary where results and exceptions become exit codes."""

    def get_params(self, ctx: Any) -> list[Any]:
        return untyped_flags(super().get_params(ctx))

    def parse_args(self, ctx: Any, args: list[str]) -> list[str]:
        alone = not args and self.no_args_is_help  # parsing consumes ``args``
        try:
            try:
                return super().parse_args(ctx, args)
            except typer.TyperException as exc:
                if alone:
                    raise  # ``alpha-audit`` alone: typer shows the help
                _usage_error(exc)
        except OSError as exc:  # --help or --version into a full disk or a closed pipe
            if not _stdout_failed(exc):
                raise
            raise typer.Exit(_exit_code(exc, debug=False)) from exc
        except SystemExit as exc:
            _help_into_closed_pipe(exc)
            raise

    def invoke(self, ctx: Any) -> Any:
        # The command's own arguments, seen here before the group hands them on.
        # To name a bad value in a usage error, and to see --help before workers start.
        ctx.meta[ARGS] = list(ctx.args)
        try:
            status = super().invoke(ctx)
            if not isinstance(status, ExitStatus):
                raise TypeError(f"command returned {status!r}, not an ExitStatus")
        except (typer.Exit, typer.Abort):
            raise  # typer's own ways out (--help, Ctrl-C) keep their meaning
        except SystemExit as exc:  # a command's --help into a closed pipe
            _help_into_closed_pipe(exc)
            raise
        except typer.TyperException as exc:
            _usage_error(exc)
        except Exception as exc:  # the boundary: nothing else turns exceptions into exit codes
            status = _exit_code(exc, debug=bool(ctx.params.get("debug")))
        finally:
            _cache_notes()
        raise typer.Exit(status)


# Every command: its module and function, imported only when the command runs
# (``render`` alone would add the browser drivers and coloraide to every start-up).
COMMANDS = {
    "check": "alpha_audit.cli.check:check_command",
    "suggest": "alpha_audit.cli.suggest:suggest_command",
    "preview": "alpha_audit.cli.preview:preview_command",
    "pair": "alpha_audit.cli.pair:pair_command",
    "reproduce": "alpha_audit.cli.reproduce:reproduce_command",
    "themes": "alpha_audit.cli.themes:themes_command",
    "export": "alpha_audit.cli.export:export_command",
    "render": "alpha_audit.cli.render:render_command",
}


def application(commands: Iterable[str] = COMMANDS) -> typer.Typer:
    """The ``alpha-audit`` application with ``commands`` registered, in :data:`COMMANDS` order."""
    built = typer.Typer(**_SETTINGS)
    built.callback()(_root)
    wanted = set(commands)
    for name, target in COMMANDS.items():
        if name in wanted:
            module, function = target.split(":")
            built.command(name, cls=Command)(getattr(import_module(module), function))
    return built


_SETTINGS: dict[str, Any] = dict(
    cls=_Group,
    name="alpha-audit",
    help=(
        "Audit icon sets across light and dark themes with extended-alpha compositing.\n\n"
        "Each icon keeps a fixed source colour Cs and coefficient a; on a canvas Cb it shows "
        "as clip(Cb + a(Cs - Cb)) in linear sRGB. With a > 1 the icon moves away from whatever "
        "canvas it lands on. alpha-audit measures what that does to WCAG contrast, 8-bit "
        "collisions and CIEDE2000 separation on your icons and themes.\n\n"
        "Exit codes: 0 ran (gate passed), 1 gate failed (check, render), 2 bad input or usage "
        "(or a resource limit), 3 internal error (a bug)."
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


# Commands that render icons: their render workers start as soon as the command
# is known, before its options are parsed and its inputs read.
_RENDERING = frozenset({"check", "suggest"})


def _root(
    ctx: typer.Context,
    version: Annotated[
        bool,
        typer.Option("--version", callback=_version, is_eager=True, help="Show the version."),
    ] = False,
    debug: Annotated[
        bool,
        typer.Option(
            "--debug",
            envvar=DEBUG_ENV,
            help="On an internal error, print the traceback too.",
            show_envvar=True,
        ),
    ] = False,
) -> None:
    """Audit icon sets across light and dark themes with extended-alpha compositing."""
    wants_help = {"-h", "--help"} & set(ctx.meta.get(ARGS, ()))
    if ctx.invoked_subcommand in _RENDERING and not wants_help:
        from alpha_audit.pipeline import render_pool

        # The workers take a few tenths of a second to start; the command finds
        # them in ctx.obj and they stop with the command (or its usage error).
        ctx.obj = ctx.with_resource(render_pool())


@cache
def _every_command() -> typer.Typer:
    return application()


def __getattr__(name: str) -> Any:
    """``app``: the application with every command (for typer's test runner and the docs)."""
    if name == "app":
        return _every_command()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def main(argv: Sequence[str] | None = None) -> None:
    """Console-script entry point: run one command and exit with its status.

    Only the command named is imported (the root options take no values, so it
    is the first argument not starting with ``-``); anything else, help and
    unknown names included, gets the application with every command.
    """
    args = sys.argv[1:] if argv is None else list(argv)
    name = next((a for a in args if not a.startswith("-")), None)
    chosen = application([name]) if name in COMMANDS else _every_command()
    # SIGTERM and SIGHUP unwind every command like Ctrl-C: temporary folders (the base
    # revision of --base), browsers and outputs are cleaned up before the process dies.
    with ending_on_signals():
        chosen(args=args, prog_name="alpha-audit")
