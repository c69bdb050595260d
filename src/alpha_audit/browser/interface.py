"""One small interface for driving a headless browser engine, and its shared plumbing.

Every engine implements :class:`Browser`: ``open`` a URL (or a page given as
HTML), ``evaluate`` a JavaScript expression (awaiting a promise) and get its
value back as JSON data, ``set_viewport`` to a size in CSS pixels,
``screenshot`` what the viewport shows (for what only the compositor sees:
HTML, CSS and SVG paint; page pixels a script can read are better read by
the script), ``close``.  A browser is a context manager, and every
process it starts runs in its own process group that :class:`ProcessGroup`
terminates (then kills) on close, on exceptions and at interpreter exit, so a
failed or timed-out run never leaves Firefox content processes, WebKit web
processes or an Xvfb behind.

Everything listens on loopback only; pages are local files.
"""

from __future__ import annotations

import abc
import contextlib
import json
import os
import shutil
import signal
import subprocess
import tempfile
import time
import weakref
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from types import TracebackType
from typing import ClassVar, Self, TypeAlias

from alpha_audit.errors import AlphaAuditError

__all__ = [
    "Browser",
    "BrowserError",
    "Installation",
    "JSONValue",
    "ProcessGroup",
    "json_expression",
]

JSONValue: TypeAlias = bool | int | float | str | list["JSONValue"] | dict[str, "JSONValue"] | None

# How long a process gets to exit after SIGTERM before it is killed.
_TERMINATE_GRACE = 3.0
# The largest viewport side we ask for: Chromium's headless window and Xvfb's screen
# (webkit.py) are this size at most; screenshots beyond it would be tens of MB anyway.
_MAX_VIEWPORT = 4096
_TWO_FRAMES = (
    "new Promise((done) => requestAnimationFrame(() => requestAnimationFrame(() => done(true))))"
)
# PNG, section 5.2 (ISO/IEC 15948).
_PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


class BrowserError(AlphaAuditError):
    """A browser engine could not be started, did not answer in time, or a script failed."""


@dataclass(frozen=True)
class Installation:
    """Where an engine's programs are: ``binary`` is the browser, ``helpers`` the rest."""

    engine: str
    binary: Path
    helpers: tuple[Path, ...] = ()


def json_expression(expression: str) -> str:
    """Wrap a JS expression so that it evaluates to a promise of its JSON text.

    Engines hand values back in different shapes (CDP's ``returnByValue``,
    BiDi's typed remote values, WebDriver's JSON); serialising in the page
    makes every engine return exactly the same data.  ``undefined`` becomes
    ``null``.

    >>> json_expression("1 + 1")
    '(async () => JSON.stringify(await (1 + 1)) ?? "null")()'
    """
    return f'(async () => JSON.stringify(await ({expression})) ?? "null")()'


class ProcessGroup:
    """Child processes, each started in a new session, ended together.

    ``close`` sends SIGTERM to each group, waits briefly, then SIGKILLs what is
    left; it runs from :meth:`Browser.close`, from a finaliser when a browser
    is dropped, and at interpreter exit.
    """

    def __init__(self) -> None:
        self._processes: list[subprocess.Popen[bytes]] = []
        # A finalizer also runs at interpreter exit (weakref.finalize.atexit is True).
        self._finalizer = weakref.finalize(self, ProcessGroup._end_all, self._processes)

    def start(
        self,
        argv: Sequence[str],
        *,
        env: dict[str, str] | None = None,
        pass_fds: Sequence[int] = (),
        stderr: int | None = subprocess.DEVNULL,
        stdout: int | None = subprocess.DEVNULL,
    ) -> subprocess.Popen[bytes]:
        """Start ``argv`` in its own session (process group); remember it for cleanup."""
        try:
            process = subprocess.Popen(
                list(argv),
                env=env,
                pass_fds=tuple(pass_fds),
                stdin=subprocess.DEVNULL,
                stdout=stdout,
                stderr=stderr,
                start_new_session=True,
            )
        except OSError as exc:
            raise BrowserError(f"cannot start {argv[0]}: {exc.strerror or exc}") from exc
        self._processes.append(process)
        return process

    @staticmethod
    def _end_all(processes: list[subprocess.Popen[bytes]]) -> None:
        for sig in (signal.SIGTERM, signal.SIGKILL):
            alive = [p for p in processes if p.poll() is None]
            for process in alive:
                with contextlib.suppress(ProcessLookupError, PermissionError):
                    os.killpg(process.pid, sig)
            deadline = time.monotonic() + _TERMINATE_GRACE
            for process in alive:
                with contextlib.suppress(subprocess.TimeoutExpired):
                    process.wait(timeout=max(0.0, deadline - time.monotonic()))
        # Grandchildren outlive a leader that exited by itself: end what is left of each group.
        for process in processes:
            with contextlib.suppress(ProcessLookupError, PermissionError):
                os.killpg(process.pid, signal.SIGKILL)
        for process in processes:
            for stream in (process.stdout, process.stderr):
                if stream is not None:
                    with contextlib.suppress(OSError):
                        stream.close()
        processes.clear()

    @property
    def pids(self) -> tuple[int, ...]:
        """Process ids of the group leaders started so far (each leads its own group)."""
        return tuple(p.pid for p in self._processes)

    def close(self) -> None:
        """End every process group (idempotent)."""
        self._finalizer()


class Browser(abc.ABC):
    """A headless browser engine driven from Python.

    Subclasses set ``NAME`` and implement :meth:`find`, :meth:`_start`,
    :meth:`_navigate`, :meth:`_evaluate_text`, :meth:`_set_viewport`,
    :meth:`_screenshot` and :meth:`_shutdown`; this base
    class owns the temporary directory, the process group and the JSON
    convention, so those exist once.

    Use as a context manager::

        with Chromium() as browser:
            browser.open_html("<p>hi</p>")
            browser.evaluate("document.body.textContent")
    """

    NAME: ClassVar[str]
    LABEL: ClassVar[str]
    INSTALL_HINT: ClassVar[str]

    def __init__(self, installation: Installation | None = None, *, timeout: float = 60.0) -> None:
        found = installation or self.find()
        if found is None:
            raise BrowserError(f"{self.LABEL} is not installed: {self.INSTALL_HINT}")
        self.installation = found
        self.timeout = float(timeout)
        self.workdir = Path(tempfile.mkdtemp(prefix=f"alpha-audit-{self.NAME}-"))
        self.processes = ProcessGroup()
        self.version = ""
        self._closed = False
        try:
            self._start()
        except BaseException:
            self.close()
            raise

    @classmethod
    @abc.abstractmethod
    def find(cls) -> Installation | None:
        """The engine's programs on this machine, or ``None`` when missing."""

    @abc.abstractmethod
    def _start(self) -> None:
        """Start the engine's processes and set ``self.version``."""

    @abc.abstractmethod
    def _navigate(self, url: str) -> None:
        """Load ``url`` and wait until its load event has fired."""

    @abc.abstractmethod
    def _evaluate_text(self, expression: str, timeout: float) -> str:
        """Evaluate ``expression`` (a promise of a string) and return the string."""

    @abc.abstractmethod
    def _set_viewport(self, width: int, height: int) -> None:
        """Ask for a ``width`` x ``height`` CSS-pixel viewport at device pixel ratio 1."""

    @abc.abstractmethod
    def _screenshot(self) -> bytes:
        """A PNG of the viewport, one image pixel per CSS pixel."""

    @abc.abstractmethod
    def _shutdown(self) -> None:
        """Ask the engine politely to quit (errors are ignored by :meth:`close`)."""

    # ---------------------------------------------------------------- public API

    def open(self, url: str) -> None:
        """Load ``url`` (normally a ``file://`` URI) in the browser's one tab."""
        self._check_open()
        self._navigate(url)

    def open_html(self, html: str, name: str = "page.html") -> Path:
        """Write ``html`` into the browser's temporary directory and open it."""
        self._check_open()
        path = self.workdir / name
        path.write_text(html, encoding="utf-8")
        self._navigate(path.as_uri())
        return path

    def evaluate(self, expression: str, *, timeout: float | None = None) -> JSONValue:
        """The value of a JS expression, after awaiting it if it is a promise, as JSON data."""
        self._check_open()
        text = self._evaluate_text(json_expression(expression), timeout or self.timeout)
        try:
            value: JSONValue = json.loads(text)
        except (TypeError, json.JSONDecodeError) as exc:
            raise BrowserError(f"{self.LABEL} returned no JSON for {expression[:60]!r}") from exc
        return value

    def wait_for(self, expression: str, *, timeout: float | None = None) -> JSONValue:
        """Poll ``expression`` until it is truthy; return its value."""
        deadline = time.monotonic() + (timeout or self.timeout)
        while True:
            value = self.evaluate(expression)
            if value:
                return value
            if time.monotonic() > deadline:
                raise BrowserError(f"{self.LABEL}: timed out waiting for {expression[:60]!r}")
            time.sleep(0.05)

    def set_viewport(self, width: int, height: int) -> None:
        """Make the page's viewport ``width`` x ``height`` CSS pixels, one device pixel each.

        Returns once the page itself reports that size (``innerWidth``,
        ``innerHeight``, ``devicePixelRatio``), so layout code that runs on
        resize has seen it.
        """
        self._check_open()
        if not (0 < width <= _MAX_VIEWPORT and 0 < height <= _MAX_VIEWPORT):
            raise BrowserError(
                f"viewport {width} x {height} px: each side must be 1 to {_MAX_VIEWPORT}"
            )
        self._set_viewport(int(width), int(height))
        check = (
            f"innerWidth === {int(width)} && innerHeight === {int(height)}"
            " && devicePixelRatio === 1"
        )
        try:
            self.wait_for(check, timeout=min(self.timeout, 10.0))
        except BrowserError:
            got = self.evaluate("[innerWidth, innerHeight, devicePixelRatio]")
            raise BrowserError(
                f"{self.LABEL}: asked for a {width} x {height} viewport at ratio 1, got {got}"
            ) from None

    def screenshot(self) -> bytes:
        """A PNG of what the viewport shows now, one image pixel per CSS pixel (ratio 1).

        Two animation frames are awaited first, so that changes a script made
        have been painted and composited (WebKitGTK's driver does not wait by
        itself: a first screenshot right after loading could show a stale frame).
        """
        self._check_open()
        self.evaluate(_TWO_FRAMES)
        png = self._screenshot()
        if not png.startswith(_PNG_SIGNATURE):
            raise BrowserError(f"{self.LABEL} returned a screenshot that is not a PNG")
        return png

    def close(self) -> None:
        """Quit the engine, end its processes and delete its temporary files (idempotent)."""
        if self._closed:
            return
        self._closed = True
        try:
            with contextlib.suppress(Exception):  # the engine may already be gone
                self._shutdown()
        finally:
            self.processes.close()
            shutil.rmtree(self.workdir, ignore_errors=True)

    def __enter__(self) -> Self:
        return self

    def __exit__(
        self,
        exc_type: type[BaseException] | None,
        exc: BaseException | None,
        tb: TracebackType | None,
    ) -> None:
        self.close()

    def _check_open(self) -> None:
        if self._closed:
            raise BrowserError(f"{self.LABEL} is closed")


def deadline_after(seconds: float) -> float:
    """A ``time.monotonic`` deadline ``seconds`` from now."""
    return time.monotonic() + seconds


def time_left(deadline: float, what: str) -> float:
    """Seconds until ``deadline``; raises :class:`BrowserError` naming ``what`` when past."""
    left = deadline - time.monotonic()
    if left <= 0:
        raise BrowserError(f"{what} did not answer in time")
    return left
