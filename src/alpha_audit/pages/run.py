"""Audit every source x state x engine: workers, browsers, limits and the measured paints.

:func:`audit_pages` serves the source folders on loopback, starts one browser
per worker (each behind its own blocking proxy, so refused requests are
attributed to the page that made them), and runs the page x state jobs in
parallel, one capture pair each (when the config asks for crops, the icons a
finding may show are cut out of it into one bounded
:class:`~alpha_audit.pages.crops.CropStore`).  A guard thread per worker ends
the browser when a page passes its time limit or the browser's processes
together pass the memory cap; that page becomes a :class:`PageProblem` and the
worker starts a fresh browser.  Browsers never outlive the call (nor alpha-audit:
:mod:`alpha_audit.browser.lifecycle`).
"""

from __future__ import annotations

import contextlib
import queue
import threading
import time
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass, replace
from pathlib import Path
from typing import NamedTuple

from alpha_audit.browser import Browser, BrowserError, LaunchOptions, engine_class
from alpha_audit.browser.server import BlockingProxy, PageServer
from alpha_audit.errors import AlphaAuditError, UsageError
from alpha_audit.model import IconSet, Location
from alpha_audit.observed import BlockedRequest, MeasuredPaint, PageProblem, PageRun
from alpha_audit.pages.capture import FoundIcon, capture_page
from alpha_audit.pages.config import RenderConfig
from alpha_audit.pages.crops import CropStore
from alpha_audit.pages.declarations import ServedFiles, paint_locations
from alpha_audit.pages.mapping import ManifestIndex
from alpha_audit.pages.measure import PageContext, measure_capture
from alpha_audit.pages.sources import FolderSource, StorybookSource, Target, targets, url_origin
from alpha_audit.pages.states import State, globals_param
from alpha_audit.pages.stillness import PageUnstable
from alpha_audit.results import Progress
from alpha_audit.safe_text import shorten
from alpha_audit.signals import ending_on_signals

__all__ = ["MAX_REASON", "Job", "PageAudit", "audit_pages", "plan_jobs"]

_GUARD_PERIOD = 0.25  # seconds between checks of a page's time and its browser's memory
MAX_REASON = 500  # characters of a page problem's message


class PageAudit(NamedTuple):
    """What :func:`audit_pages` measured: the run, and every paint in report order."""

    run: PageRun
    paints: tuple[MeasuredPaint, ...]


@dataclass(frozen=True)
class Job:
    """One page in one state in one engine."""

    order: int
    target: Target
    state: State
    engine: str

    def url(self, server: PageServer | None) -> str:
        """The page's URL, with the state's Storybook globals."""
        if self.target.mount is None or server is None:
            url = self.target.path
        else:
            url = server.url(self.target.mount, self.target.path)
        if self.state.globals and self.target.storybook:
            url += ("&" if "?" in url else "?") + "globals=" + globals_param(self.state.globals)
        return url


def plan_jobs(config: RenderConfig) -> list[Job]:
    """Every target x state x engine, grouped so each engine restarts as little as it must."""
    pages = targets(config.sources)
    jobs = [
        Job(0, target, state, engine)
        for engine in config.engines
        for state in config.states
        for target in pages
    ]
    jobs.sort(key=lambda j: (config.engines.index(j.engine), j.state.color_scheme or ""))
    return [Job(k, j.target, j.state, j.engine) for k, j in enumerate(jobs)]


class _Guard:
    """Ends a worker's browser when the current page runs out of time or memory."""

    def __init__(self, timeout: float, memory_bytes: int) -> None:
        self.timeout = timeout
        self.memory_bytes = memory_bytes
        self.browser: Browser | None = None
        self.deadline: float | None = None
        self.reason: str | None = None
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._watch, daemon=True)
        self._thread.start()

    def _watch(self) -> None:
        while not self._stop.wait(_GUARD_PERIOD):
            browser = self.browser
            if browser is None or self.deadline is None:
                continue
            if time.monotonic() > self.deadline:
                self.reason = f"took longer than the limit of {self.timeout:g} s per page"
            elif browser.processes.resident_bytes() > self.memory_bytes:
                self.reason = (
                    f"the browser used more than the memory cap of {self.memory_bytes >> 20} MiB"
                )
            else:
                continue
            browser.processes.close()  # the worker's call fails at once; it starts afresh

    @contextlib.contextmanager
    def page(self, browser: Browser) -> Iterator[None]:
        self.browser, self.reason = browser, None
        self.deadline = time.monotonic() + self.timeout
        try:
            yield
        finally:
            self.deadline = None

    def close(self) -> None:
        self._stop.set()
        self._thread.join()


class _Worker:
    """One thread: one browser (restarted as needed) behind one proxy."""

    def __init__(
        self,
        config: RenderConfig,
        server: PageServer | None,
        direct: tuple[str, ...],
        files: ServedFiles | None = None,
    ):
        self.config = config
        self.server = server
        self.files = files
        self.direct = direct
        self.proxy = BlockingProxy()
        self.guard = _Guard(config.timeout, config.memory_mb << 20)
        self.browser: Browser | None = None
        self.versions: dict[str, str] = {}
        self._closing = threading.Lock()

    def _browser(self, job: Job) -> Browser:
        scheme = job.state.color_scheme
        current = self.browser
        if current is not None and job.engine == current.NAME:
            if current.options.color_scheme == scheme:
                return current
            if current.LIVE_COLOR_SCHEME:
                current.emulate_color_scheme(scheme)
                current.options = replace(current.options, color_scheme=scheme)
                return current
        self.close_browser()
        options = LaunchOptions(scheme, self.proxy.address, self.direct, self.config.scale)
        self.browser = engine_class(job.engine)(timeout=self.config.timeout, options=options)
        self.versions[job.engine] = self.browser.version
        return self.browser

    def close_browser(self) -> None:
        # The run's thread closes every worker on the way out (a signal, a failure)
        # while the worker's own thread may be closing the same browser after the
        # error that closing caused: only one of them takes it.
        with self._closing:
            browser, self.browser = self.browser, None
        if browser is not None:
            # End the processes first: another thread may be mid-call on this browser.
            browser.processes.close()
            browser.close()

    def run(
        self, job: Job, index: ManifestIndex, crops: CropStore | None, rank: int
    ) -> tuple[list[MeasuredPaint], PageProblem | None, list[str], int]:
        url = job.url(self.server)
        self.proxy.take()
        try:
            browser = self._browser(job)
            with self.guard.page(browser):
                capture = capture_page(
                    browser,
                    url,
                    job.state,
                    storybook=job.target.storybook,
                    viewport=self.config.viewport,
                    scale=self.config.scale,
                    selector=self.config.selector,
                    attribute=self.config.attribute,
                    max_icon_size=self.config.max_icon_size,
                )
        except BrowserError as exc:
            # The message may quote the page (a script's error): bounded like its names.
            reason = shorten(self.guard.reason or str(exc), MAX_REASON)
            if not isinstance(exc, PageUnstable):  # a page that moves leaves its browser fine
                self.close_browser()
            problem = PageProblem(job.target.name, job.state.name, job.engine, reason)
            return [], problem, self.proxy.take(), 0
        page = PageContext(
            job.target.name, job.target.kind, job.state.name, job.engine, job.target.file
        )
        matches = [index.match(icon.keys) for icon in capture.icons]
        files = self.files

        def locate(icon: FoundIcon, paint: int | None) -> tuple[Location, ...]:
            if files is None:
                return ()
            return tuple(p.location() for p in paint_locations(icon, paint, job.target, files))

        paints = measure_capture(capture, page, matches, locate)
        if crops is not None:
            crops.keep(capture, paints, rank)
        return paints, None, self.proxy.take(), len(capture.icons)

    def close(self) -> None:
        try:
            self.close_browser()
        finally:
            self.guard.close()
            self.proxy.close()


def _mounts(config: RenderConfig) -> list[Path | None]:
    """Each source's folder on the page server; a URL source has none (its own server)."""
    return [s.folder if isinstance(s, StorybookSource | FolderSource) else None
            for s in config.sources]  # fmt: skip


def _blocked(job: Job, url: str) -> BlockedRequest:
    """A refused request of ``job``, said to be the engine's own where it asks that host."""
    request = BlockedRequest(job.target.name, job.state.name, job.engine, url)
    engine = engine_class(job.engine)
    return replace(request, own=engine.LABEL) if request.host in engine.OWN_HOSTS else request


def audit_pages(
    config: RenderConfig,
    iconset: IconSet | None = None,
    *,
    progress: Progress | None = None,
) -> PageAudit:
    """Measure every source x state x engine of ``config``; ``progress`` is told the number
    of jobs (page x state x engine) first, then each one done (as ``check``'s).

    Returns what the run saw and every paint it measured, in report order
    (source, state, engine, DOM order): :func:`alpha_audit.pages.audit.page_report`
    makes them rows and judges them.

    Raises :class:`UsageError` for sources that do not exist or select
    nothing and for engines that are not installed; a page that fails (a
    script error, a time or memory limit) is a :class:`PageProblem` in the
    result instead.
    """
    for engine in config.engines:
        if engine_class(engine).find() is None:
            cls = engine_class(engine)
            raise UsageError(f"{cls.LABEL} is not installed: {cls.INSTALL_HINT}")
    jobs = plan_jobs(config)
    if progress is not None:
        progress[0](len(jobs))
    ordered = sorted(jobs, key=lambda j: (j.target.name, j.state.name, j.engine))  # the report's
    rank = {job.order: k for k, job in enumerate(ordered)}
    crops = CropStore(config.crops, config.policy, config.threshold) if config.crops > 0 else None
    index = ManifestIndex.of(iconset)
    with ending_on_signals(), PageServer(_mounts(config), Path(config.root)) as server:
        # Where each page's CSS is written (one resolver for the run, shared by workers).
        files = ServedFiles(server.local_file, Path(config.root))
        direct = tuple(
            dict.fromkeys(
                [server.address, server.address.replace("127.0.0.1", "localhost")]
                + [url_origin(j.target.path) for j in jobs if j.target.mount is None]
            )
        )
        workers = [
            _Worker(config, server, direct, files)
            for _ in range(max(1, min(config.workers, len(jobs))))
        ]
        results = _run_jobs(
            workers,
            jobs,
            lambda worker, job: worker.run(job, index, crops, rank[job.order]),
            progress,
        )
    return _page_audit(jobs, ordered, results, workers, crops)


_Outcome = tuple[list[MeasuredPaint], PageProblem | None, list[str], int]


def _run_jobs(
    workers: Sequence[_Worker],
    jobs: Sequence[Job],
    run: Callable[[_Worker, Job], _Outcome],
    progress: Progress | None,
) -> dict[int, _Outcome]:
    """Each job's outcome by its order, the workers taking jobs in parallel (a thread each);
    the first exception of any worker stops them all and is raised here."""
    results: dict[int, _Outcome] = {}
    todo: queue.Queue[Job] = queue.Queue()
    for job in jobs:
        todo.put(job)
    failure: list[BaseException] = []
    lock = threading.Lock()

    def work(worker: _Worker) -> None:
        while not failure:
            try:
                job = todo.get_nowait()
            except queue.Empty:
                return
            try:
                outcome = run(worker, job)
            except BaseException as exc:  # handed to the caller's thread below
                failure.append(exc)
                return
            with lock:
                results[job.order] = outcome
                if progress is not None:
                    progress[1]()

    threads = [threading.Thread(target=work, args=(w,), daemon=True) for w in workers]
    try:
        for thread in threads:
            thread.start()
        for thread in threads:
            while thread.is_alive():
                thread.join(0.1)  # short joins: SIGTERM and Ctrl-C are handled meanwhile
    finally:
        failure.append(AlphaAuditError("stopped"))  # tells the other workers to stop
        for worker in workers:
            worker.close()
        for thread in threads:
            thread.join(5)
    if len(failure) > 1:
        raise failure[0]
    return results


def _page_audit(
    jobs: Sequence[Job],
    ordered: Sequence[Job],
    results: dict[int, _Outcome],
    workers: Sequence[_Worker],
    crops: CropStore | None,
) -> PageAudit:
    """The run and its paints in report order (``ordered``) from each job's outcome."""
    versions: dict[str, str] = {}
    for worker in workers:
        versions.update(worker.versions)
    paints: list[MeasuredPaint] = []
    problems: list[PageProblem] = []
    blocked: list[BlockedRequest] = []
    icons = 0
    for job in ordered:
        found, problem, refused, count = results[job.order]
        paints.extend(found)
        icons += count
        if problem is not None:
            problems.append(problem)
        blocked.extend(_blocked(job, url) for url in refused)
    run = PageRun(
        problems=tuple(problems),
        blocked=tuple(blocked),
        audited=len(jobs),
        icons=icons,
        paints=len(paints),
        engines=tuple(sorted(versions.items())),
        pages=tuple(dict.fromkeys((j.target.name, j.state.name) for j in jobs)),
        files=tuple(dict.fromkeys((j.target.name, j.target.file) for j in ordered)),
        crops=crops.crops if crops is not None else (),
        crops_left_out=crops.left_out if crops is not None else 0,
    )
    return PageAudit(run, tuple(paints))
