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

Everything listens on loopback only.  :class:`LaunchOptions` choose
``prefers-color-scheme`` and send every request through a loopback proxy
except those to the pages' own servers (:mod:`alpha_audit.pages`); the
lifecycle (process groups, signals, a reaper that outlives a killed
alpha-audit) is in :mod:`alpha_audit.browser.lifecycle`.
"""

from __future__ import annotations

import abc
import contextlib
import json
import os
import shutil
import tempfile
import time
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from types import TracebackType
from typing import ClassVar, Literal, Self, TypeAlias

from alpha_audit.browser.lifecycle import BrowserError, ProcessGroup

__all__ = [
    "COLOR_SCHEMES",
    "Browser",
    "BrowserError",
    "Clip",
    "ColorScheme",
    "Installation",
    "JSONValue",
    "LaunchOptions",
    "ProcessGroup",
    "json_expression",
]

JSONValue: TypeAlias = bool | int | float | str | list["JSONValue"] | dict[str, "JSONValue"] | None

# The largest viewport side we ask for: Chromium's headless window and Xvfb's screen
# (webkit.py) are this size at most; screenshots beyond it would be tens of MB anyway.
_MAX_VIEWPORT = 4096
_TWO_FRAMES = (
    "new Promise((done) => requestAnimationFrame(() => requestAnimationFrame(() => done(true))))"
)
# PNG, section 5.2 (ISO/IEC 15948).
_PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
# A launch is tried this many times; each of its calls waits at most LAUNCH_TIMEOUT seconds
# (or the browser's own timeout, if less).
LAUNCH_ATTEMPTS = 2
LAUNCH_TIMEOUT = 60.0
# unix(7): a socket's path (sun_path) holds 108 bytes with its NUL.  Chromium makes its
# singleton socket at $TMPDIR/.org.chromium.Chromium.XXXXXX/SingletonSocket, 47 bytes
# below TMPDIR; a runtime folder longer than the rest makes Chromium die at start.
_SOCKET_PATH_BYTES = 107
_SOCKET_TAIL_BYTES = 47
MAX_RUNTIME_BYTES = _SOCKET_PATH_BYTES - _SOCKET_TAIL_BYTES
# Where a runtime folder goes when the caller's TMPDIR is too long for one: short,
# sticky system folders (mkdtemp makes the folder itself 0700).
_SHORT_BASES = ("/tmp", "/var/tmp", "/dev/shm")
# The engine's HOME and XDG base directories (XDG Base Directory Specification 0.8),
# all inside the browser's folder.
_XDG_VARIABLES = ("XDG_CONFIG_HOME", "XDG_DATA_HOME", "XDG_CACHE_HOME", "XDG_STATE_HOME")
_HOME_FOLDERS = (".config", ".local/share", ".cache", ".local/state")


def runtime_folder(workdir: Path, name: str) -> Path:
    """A private folder for an engine's sockets and temporary files, short whatever TMPDIR is.

    ``workdir/tmp`` when that path leaves room for the longest socket an
    engine makes in it (:data:`MAX_RUNTIME_BYTES`); otherwise a new folder
    (mode 0700) in ``/tmp`` or another short system folder, which the caller
    removes with the browser.
    """
    inside = workdir / "tmp"
    if len(os.fsencode(inside)) <= MAX_RUNTIME_BYTES:
        inside.mkdir()
        return inside
    for base in _SHORT_BASES:
        # mkdtemp adds "alpha-audit-<engine>-" and 8 characters to the base.
        if len(os.fsencode(base)) + len(name) + 22 > MAX_RUNTIME_BYTES or not os.path.isdir(base):
            continue
        try:
            return Path(tempfile.mkdtemp(prefix=f"alpha-audit-{name}-", dir=base))
        except OSError:
            continue
    raise BrowserError(
        f"the temporary folder {workdir.parent} is too long for the browser's sockets "
        f"(at most {MAX_RUNTIME_BYTES - 31} bytes) and no short folder such as /tmp is "
        "writable: set TMPDIR to a shorter folder"
    )


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


ColorScheme = Literal["light", "dark"]
COLOR_SCHEMES: tuple[ColorScheme, ...] = ("light", "dark")


@dataclass(frozen=True)
class LaunchOptions:
    """How an engine is started; the defaults are what the WebGL validation needs.

    ``color_scheme`` is what ``prefers-color-scheme`` matches (``None``: the
    engine's default, light).  ``proxy`` is a loopback ``host:port`` every
    request goes through except those to ``direct`` (``host:port`` origins of
    the pages' own servers): alpha-audit's blocking proxy
    (:mod:`alpha_audit.pages.proxy`) answers everything else with an error and
    records it, so untrusted pages reach nothing but their server.
    """

    color_scheme: ColorScheme | None = None
    proxy: str | None = None
    direct: tuple[str, ...] = ()
    scale: int = 1
    """Device pixels per CSS pixel for engines that fix it at start (WebKitGTK's GDK_SCALE)."""


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
    LIVE_COLOR_SCHEME: ClassVar[bool] = False
    # Hosts the engine asks by itself despite its flags, whatever the page (a report says
    # so: a page that requests nothing still shows them blocked).
    OWN_HOSTS: ClassVar[frozenset[str]] = frozenset()
    """Whether :meth:`emulate_color_scheme` works without a restart."""
    ISOLATED_SCRIPTS: ClassVar[bool] = False
    """Whether ``evaluate(..., isolated=True)`` runs apart from the page's own scripts."""

    def __init__(
        self,
        installation: Installation | None = None,
        *,
        timeout: float = 60.0,
        options: LaunchOptions | None = None,
    ) -> None:
        found = installation or self.find()
        if found is None:
            raise BrowserError(f"{self.LABEL} is not installed: {self.INSTALL_HINT}")
        self.installation = found
        self.options = options or LaunchOptions()
        self.version = ""
        self.scale = 1.0
        self.viewport: tuple[int, int] | None = None  # the last size asked for
        for attempt in range(1, LAUNCH_ATTEMPTS + 1):
            # Every call of a launch waits at most LAUNCH_TIMEOUT: an engine that hangs
            # while starting (a CI run once saw WebKitWebDriver's POST /session never
            # answer) is started again, from nothing, rather than waited on.
            self.timeout = min(float(timeout), LAUNCH_TIMEOUT)
            self.workdir = Path(tempfile.mkdtemp(prefix=f"alpha-audit-{self.NAME}-"))
            self.runtime = self.workdir  # until runtime_folder() has made the real one
            self.processes = ProcessGroup(self.workdir)
            self._closed = False
            try:
                self.runtime = runtime_folder(self.workdir, self.NAME)
                self.processes.also_remove(self.runtime)
                for folder in _HOME_FOLDERS:
                    (self.workdir / "home" / folder).mkdir(parents=True)
                self._start()
            except BrowserError:
                self.close()
                if attempt == LAUNCH_ATTEMPTS:
                    raise
            except BaseException:
                self.close()
                raise
            else:
                break
        self.timeout = float(timeout)

    def child_env(self, base: dict[str, str] | None = None) -> dict[str, str]:
        """The environment for the engine's programs: nothing of the caller's folders.

        ``TMPDIR`` and ``XDG_RUNTIME_DIR`` are the browser's short runtime
        folder (:func:`runtime_folder`: Chromium's singleton socket lives
        there), ``HOME`` and the XDG folders are inside the browser's own
        folder: the crash reports, settings and downloads folders an engine
        makes (Chromium's and Firefox's ``Crash Reports``, Firefox's
        ``Downloads``) are removed with the browser and never touch the
        user's home.
        """
        env = dict(os.environ if base is None else base)
        home = self.workdir / "home"
        env["HOME"] = str(home)
        for variable, folder in zip(_XDG_VARIABLES, _HOME_FOLDERS, strict=True):
            env[variable] = str(home / folder)
        env["TMPDIR"] = str(self.runtime)
        env["XDG_RUNTIME_DIR"] = str(self.runtime)
        return env

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
    def _evaluate_text(self, expression: str, timeout: float, isolated: bool) -> str:
        """Evaluate ``expression`` (a promise of a string) and return the string."""

    @abc.abstractmethod
    def _set_viewport(self, width: int, height: int, scale: float) -> None:
        """Ask for a ``width`` x ``height`` CSS-pixel viewport at device pixel ratio ``scale``."""

    @abc.abstractmethod
    def _screenshot(self, clip: Clip | None) -> bytes:
        """A PNG of the viewport (or of ``clip``, in CSS pixels), ``scale`` pixels per CSS px."""

    @abc.abstractmethod
    def _shutdown(self) -> None:
        """Ask the engine politely to quit (errors are ignored by :meth:`close`)."""

    def emulate_color_scheme(self, scheme: ColorScheme | None) -> None:
        """Make ``prefers-color-scheme`` match ``scheme`` from the next page on.

        Engines that can only choose it at start (``LIVE_COLOR_SCHEME`` false)
        refuse a change; start another browser with :class:`LaunchOptions`.
        """
        if scheme != self.options.color_scheme:
            raise BrowserError(
                f"{self.LABEL} chooses prefers-color-scheme when it starts; "
                f"it was started with {self.options.color_scheme or 'the default'}"
            )

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

    def evaluate(
        self, expression: str, *, timeout: float | None = None, isolated: bool = False
    ) -> JSONValue:
        """The value of a JS expression, after awaiting it if it is a promise, as JSON data.

        ``isolated`` runs it in a world of its own where the engine has one
        (``ISOLATED_SCRIPTS``): it sees the page's DOM but none of the page's
        JavaScript, and the page's scripts see nothing of it.
        """
        self._check_open()
        text = self._evaluate_text(json_expression(expression), timeout or self.timeout, isolated)
        try:
            value: JSONValue = json.loads(text)
        except (TypeError, json.JSONDecodeError) as exc:
            raise BrowserError(f"{self.LABEL} returned no JSON for {expression[:60]!r}") from exc
        return value

    def wait_for(
        self, expression: str, *, timeout: float | None = None, isolated: bool = False
    ) -> JSONValue:
        """Poll ``expression`` until it is truthy; return its value."""
        deadline = time.monotonic() + (timeout or self.timeout)
        while True:
            value = self.evaluate(expression, isolated=isolated)
            if value:
                return value
            if time.monotonic() > deadline:
                raise BrowserError(f"{self.LABEL}: timed out waiting for {expression[:60]!r}")
            time.sleep(0.05)

    def set_viewport(self, width: int, height: int, scale: float = 1.0) -> None:
        """Make the page's viewport ``width`` x ``height`` CSS pixels, ``scale`` device px each.

        Returns once the page itself reports that size (``innerWidth``,
        ``innerHeight``, ``devicePixelRatio``), so layout code that runs on
        resize has seen it.
        """
        self._check_open()
        if not (0 < width <= _MAX_VIEWPORT and 0 < height <= _MAX_VIEWPORT):
            raise BrowserError(
                f"viewport {width} x {height} px: each side must be 1 to {_MAX_VIEWPORT}"
            )
        if not 1 <= scale <= 4:
            raise BrowserError(f"device scale {scale:g}: must be 1 to 4")
        self._set_viewport(int(width), int(height), float(scale))
        self.scale = float(scale)
        self.viewport = (int(width), int(height))
        check = (
            f"innerWidth === {int(width)} && innerHeight === {int(height)}"
            f" && devicePixelRatio === {float(scale)!r}"
        )
        try:
            self.wait_for(check, timeout=min(self.timeout, 10.0))
        except BrowserError:
            got = self.evaluate("[innerWidth, innerHeight, devicePixelRatio]")
            raise BrowserError(
                f"{self.LABEL}: asked for a {width} x {height} viewport at ratio {scale:g}, "
                f"got {got}"
            ) from None

    def screenshot(self, clip: Clip | None = None) -> bytes:
        """A PNG of what the viewport shows now (or the ``clip`` box of it, CSS pixels).

        The image has ``scale`` pixels per CSS pixel (:meth:`set_viewport`).
        Two animation frames are awaited first, so that changes a script made
        have been painted and composited (WebKitGTK's driver does not wait by
        itself: a first screenshot right after loading could show a stale frame).
        """
        self._check_open()
        self.evaluate(_TWO_FRAMES, isolated=self.ISOLATED_SCRIPTS)
        png = self._screenshot(clip)
        if not png.startswith(_PNG_SIGNATURE):
            raise BrowserError(f"{self.LABEL} returned a screenshot that is not a PNG")
        return png

    def matched_styles(
        self, elements: str, pseudos: Sequence[str | None]
    ) -> dict[str, JSONValue] | None:
        """The author declarations that match each element, from the engine's devtools.

        ``elements`` is a JS expression (evaluated like ``evaluate(...,
        isolated=True)``) whose value is an array of elements; ``pseudos``
        names, per element, the pseudo-element (``"before"``, ``"after"``) to
        match instead of the element itself.  The answer has the shape of the
        page probe's ``cascade()`` (``pages/probe.js``): ``sheets`` (``url``,
        ``inline``) and, per element, its declarations of colours, backgrounds
        and custom properties with their rank in the cascade and where the
        engine says they are written (``line`` and ``column``, 0-based, in the
        served file).  ``None`` where the engine has no such protocol: the
        probe then walks the cascade itself from ``document.styleSheets``.
        """
        return None

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
            shutil.rmtree(self.runtime, ignore_errors=True)  # gone already if inside workdir

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


@dataclass(frozen=True)
class Clip:
    """A box of the viewport in CSS pixels (whole pixels: a device-pixel grid at any scale)."""

    x: int
    y: int
    width: int
    height: int


def deadline_after(seconds: float) -> float:
    """A ``time.monotonic`` deadline ``seconds`` from now."""
    return time.monotonic() + seconds


def time_left(deadline: float, what: str) -> float:
    """Seconds until ``deadline``; raises :class:`BrowserError` naming ``what`` when past."""
    left = deadline - time.monotonic()
    if left <= 0:
        raise BrowserError(f"{what} did not answer in time")
    return left
