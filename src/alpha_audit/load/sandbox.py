"""A pool of sandboxed render processes with a wall-clock limit per icon.

cairosvg runs untrusted SVG from pull requests.  Some inputs take tens of
seconds (a ``<use>`` fan-out under cairosvg's 100k cap), some exhaust memory
or crash the C library, and exceptions escape as many types.  So rendering
happens in worker processes (:mod:`alpha_audit.load._svg_worker`) with
resource limits and an audit hook; this module hands them jobs, enforces
:attr:`RenderLimits.timeout` per job (one icon: all its paint groups at all
its sizes) by killing the worker, and turns every failure into a one-line
reason.  Replies are parsed with fixed-size headers, never unpickled, so even
a compromised worker can only send wrong pixels.

On Linux the workers are forked from one fork server that imported the
renderer once (a third of a second of CPU per worker saved; the pages it
loaded are shared); elsewhere each worker is its own ``python -I`` process.
"""

from __future__ import annotations

import contextlib
import math
import os
import selectors
import signal
import socket
import struct
import subprocess
import sys
import time
from collections import deque
from collections.abc import Iterable, Iterator, Sequence
from dataclasses import dataclass
from pathlib import Path
from types import TracebackType
from typing import IO, Generic, TypeVar

import numpy as np
from numpy.typing import NDArray

__all__ = ["WALL_FACTOR", "Outcome", "PaintsReply", "ReadPaints", "RenderLimits", "RenderPool"]

T = TypeVar("T")

_WORKER = Path(__file__).with_name("_svg_worker.py")
_HEADER = struct.Struct(">BI")
_READY = 2  # the status a worker sends, once, when its start-up is over
_REFUSED = 3  # a paints job's file refused by the paint reader
# Seconds a worker may take to start (import the renderer) before it is given up:
# independent of any input, so generous; a busy machine can take many seconds.
_START_TIMEOUT = 60.0
_MAX_MESSAGE_BYTES = 4096
_MAX_PAINTS_BYTES = 64 << 20  # an SVG of 1 MiB describes far fewer paints
# Jobs sent to a worker before it answers the first: enough that it never waits
# for this process between small jobs.  Their requests stay under a pipe's
# capacity (64 KiB on Linux; 16 KiB is safe everywhere), so writing one never blocks.
_PIPELINE_JOBS = 4
_PIPELINE_BYTES = 16 << 10

Mask = NDArray[np.uint8]  # 8-bit coverage codes, alpha x 255


@dataclass(frozen=True)
class ReadPaints:
    """A job that reads an SVG's paints in the worker and renders each paint group
    (see :func:`alpha_audit.load.paints.paints_and_isolates`)."""

    svg: bytes
    max_groups: int


@dataclass(frozen=True)
class PaintsReply:
    """What a :class:`ReadPaints` job gave: the paints as JSON
    (:func:`~alpha_audit.load.paints.encode_paints`) and per group a mask or a reason
    per size; or ``problem``, why the paints could not be read."""

    paints: bytes
    masks: list[list[Mask | str]]
    problem: str | None = None
    lasting: bool = False  # the paint reader refused the file: it always will


# Per job: a reason string when the whole job failed (time, crash); else, for a job
# of SVGs, per SVG one mask or reason per size, and for a ReadPaints job its reply.
Outcome = str | list[list[Mask | str]] | PaintsReply


class _Incomplete(Exception):
    """The reply is not all in the buffer yet."""


@dataclass(frozen=True)
class RenderLimits:
    """Bounds on rendering one untrusted SVG (documented in docs/ci.md).

    ``timeout`` is the seconds of CPU time each icon gets for reading its
    paints and rendering all its paint groups and sizes (rounded up to whole
    seconds; counted by the worker's kernel, so a busy machine does not shorten
    it), with :data:`WALL_FACTOR` times as much wall-clock time as a backstop;
    ``memory`` the worker's address-space limit in bytes; ``cpu`` a worker's
    CPU-time limit over its life; ``workers`` how many render processes run
    at once.
    """

    timeout: float = 5.0
    memory: int = 1 << 30  # 1 GiB address space: Python + cairo need ~300 MiB
    cpu: int = 600
    workers: int = max(1, min(4, os.cpu_count() or 1))

    @property
    def job_cpu(self) -> int:
        """Whole seconds of CPU time per icon (RLIMIT_CPU counts whole seconds)."""
        return max(1, math.ceil(self.timeout))


# A job's wall-clock backstop, in multiples of its CPU time: catches a worker that
# waits without computing; a busy machine's share of CPU rarely falls below a quarter.
WALL_FACTOR = 4


def _worker_env() -> dict[str, str]:
    # HOME (and USER) set: without them the interpreter asks the account
    # database (NSS, /etc/passwd) at start-up, before the guard is installed.
    return {
        "PATH": os.environ.get("PATH", ""),
        "OPENBLAS_NUM_THREADS": "1",
        "LC_ALL": "C",
        "HOME": "/nonexistent",
        "USER": "alpha-audit",
        "LOGNAME": "alpha-audit",
        "TZ": "UTC",  # no /etc/localtime
    }


def _worker_argv(limits: RenderLimits, *extra: str) -> list[str]:
    """The command line of a worker (or, with ``--fork-server``, of the fork server)."""
    limit_args = (limits.memory, limits.cpu, limits.job_cpu)
    return [sys.executable, "-I", str(_WORKER), *map(str, limit_args), *extra]


class _ForkServer:
    """The process the workers are forked from (Linux); see :mod:`._svg_worker`.

    It imports the renderer once; each worker forked from it costs a few
    milliseconds instead of a third of a second of imports.  Its only input is
    this socket: it never reads an SVG.
    """

    def __init__(self, limits: RenderLimits, *, hold: bool = False) -> None:
        ours, theirs = socket.socketpair(socket.AF_UNIX, socket.SOCK_STREAM)
        try:
            self.proc = subprocess.Popen(
                _worker_argv(
                    limits, "--fork-server", str(theirs.fileno()), *(["--hold"] if hold else [])
                ),
                stdin=subprocess.DEVNULL,
                stdout=subprocess.DEVNULL,
                stderr=subprocess.DEVNULL,
                env=_worker_env(),
                cwd=_WORKER.parent,
                pass_fds=(theirs.fileno(),),
                process_group=0,  # so that pause() reaches the workers it forked too
            )
        finally:
            theirs.close()
        self.control = ours
        self.control.settimeout(_CONTROL_TIMEOUT)
        self.next_id = 0
        self.paused = False
        self.held = hold  # started with --hold: nothing loaded until release()

    def release(self) -> None:
        """Let a held server load the renderer and fork the workers asked for."""
        if self.held:
            self.held = False
            with contextlib.suppress(OSError):
                self.control.sendall(b"G" + struct.pack(">I", 0))

    def spawn(self, request_fd: int, reply_fd: int) -> int:
        """Fork a worker reading ``request_fd`` and writing ``reply_fd``; its id."""
        self.next_id += 1
        socket.send_fds(
            self.control, [b"S" + struct.pack(">I", self.next_id)], [request_fd, reply_fd]
        )
        return self.next_id

    def kill(self, worker: int) -> None:
        with contextlib.suppress(OSError):
            self.control.sendall(b"K" + struct.pack(">I", worker))

    def exit_code(self, worker: int) -> int | None:
        """Reap an ended worker: its exit code (negative: the signal), None if unknown."""
        try:
            self.control.sendall(b"R" + struct.pack(">I", worker))
            reply = b""
            while len(reply) < 8:
                chunk = self.control.recv(8 - len(reply))
                if not chunk:
                    return None
                reply += chunk
        except OSError:
            return None
        answered, code = struct.unpack(">Ii", reply)
        return code if answered == worker else None

    def pause(self, paused: bool) -> None:
        """Stop (or continue) the server and, with it, the workers still starting."""
        if paused != self.paused and self.proc.poll() is None:
            with contextlib.suppress(OSError):
                os.killpg(self.proc.pid, signal.SIGSTOP if paused else signal.SIGCONT)
        self.paused = paused

    def close(self) -> None:
        """End the server: told by its socket closing, it kills and reaps its workers (so
        their CPU time is counted as this process's children's) and exits; if it does
        not within :data:`_CLOSE_SECONDS` it is killed, and its workers die with it
        (``PR_SET_PDEATHSIG``)."""
        self.pause(False)
        with contextlib.suppress(OSError):
            self.control.close()
        try:
            self.proc.wait(timeout=_CLOSE_SECONDS)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            self.proc.wait()


class _Worker:
    """One render process and the jobs sent to it, oldest (the one it is on) first."""

    def __init__(self, limits: RenderLimits, server: _ForkServer | None = None) -> None:
        self.limits = limits
        self.server = server
        self.proc: subprocess.Popen[bytes] | None = None
        self.stdin: IO[bytes]
        self.stdout: IO[bytes]
        if server is not None:
            request_r, request_w = os.pipe()
            reply_r, reply_w = os.pipe()
            try:
                self.id = server.spawn(request_r, reply_w)
            except OSError:
                os.close(request_w)
                os.close(reply_r)
                raise
            finally:  # the worker holds its ends now (or there is no worker)
                os.close(request_r)
                os.close(reply_w)
            self.stdin = open(request_w, "wb")  # noqa: SIM115  # closed in kill()
            self.stdout = open(reply_r, "rb")  # noqa: SIM115  # closed in kill()
        else:
            self.proc = subprocess.Popen(
                _worker_argv(limits),
                stdin=subprocess.PIPE,
                stdout=subprocess.PIPE,
                stderr=subprocess.DEVNULL,
                env=_worker_env(),
                cwd=_WORKER.parent,
            )
            assert self.proc.stdin is not None and self.proc.stdout is not None
            self.stdin, self.stdout = self.proc.stdin, self.proc.stdout
        os.set_blocking(self.stdout.fileno(), False)
        # (job, SVGs or ReadPaints' group cap as -cap, sizes, request bytes) in the order
        # sent; the worker answers in that order.
        self.jobs: deque[tuple[int, int, tuple[int, ...], int]] = deque()
        self.started = 0.0  # when the oldest job began: the reply before it came then
        self.spawned = time.monotonic()
        self.ready = False  # it said so: its start-up is over
        self.buffer = bytearray()
        self.ended: int | None = None  # exit code once known

    @property
    def pending_bytes(self) -> int:
        return sum(n for _, _, _, n in self.jobs)

    def deadline(self, timeout: float) -> float:
        """When the job it is on runs out of wall-clock time (each job gets ``timeout``
        times :data:`WALL_FACTOR` of its own, from when the worker was ready; its start-up
        gets :data:`_START_TIMEOUT`)."""
        if not self.ready:
            return self.spawned + max(timeout, _START_TIMEOUT)
        return self.started + timeout * WALL_FACTOR

    def send(self, job: int, request: bytes, svgs: int, sizes: tuple[int, ...]) -> None:
        """Write one request; ``svgs`` is its SVG count, or minus the group cap of a
        :class:`ReadPaints` job."""
        self.stdin.write(request)
        self.stdin.flush()
        if not self.jobs:
            self.started = time.monotonic()
        self.jobs.append((job, svgs, sizes, len(request)))

    def replies(self) -> Iterator[tuple[int, list[list[Mask | str]] | PaintsReply]]:
        """``(job, reply)`` for each complete reply in the buffer; ValueError if malformed."""
        if not self.ready:
            if len(self.buffer) < _HEADER.size:
                return
            if _HEADER.unpack_from(self.buffer) != (_READY, 0):
                raise ValueError("malformed reply")
            del self.buffer[: _HEADER.size]
            self.ready = True
            self.started = time.monotonic()  # the first job starts now
        while self.jobs:
            _, svgs, sizes, _ = self.jobs[0]
            cursor = _Cursor(self.buffer)
            try:
                reply = self._parse(cursor, svgs, sizes)
            except _Incomplete:
                return
            del self.buffer[: cursor.pos]
            job = self.jobs.popleft()[0]
            self.started = time.monotonic()  # the next job starts now
            yield job, reply
        if self.buffer:
            raise ValueError("malformed reply")

    @staticmethod
    def _parse(
        cursor: _Cursor, svgs: int, sizes: tuple[int, ...]
    ) -> list[list[Mask | str]] | PaintsReply:
        """One reply (see :mod:`._svg_worker`); _Incomplete if it has not all come."""
        if svgs >= 0:
            return [[cursor.entry(size) for size in sizes] for _ in range(svgs)]
        status, paints = cursor.header(_MAX_PAINTS_BYTES)
        if status != 0:
            return PaintsReply(b"", [], _printable(paints), lasting=status == _REFUSED)
        (groups,) = struct.unpack(">I", cursor.take(4))
        if groups > -svgs:
            raise ValueError("malformed reply")
        return PaintsReply(paints, [[cursor.entry(size) for size in sizes] for _ in range(groups)])

    def kill(self) -> None:
        if self.proc is not None:
            if self.proc.poll() is None:
                self.proc.kill()
            self.proc.wait()
        elif self.server is not None and self.ended is None:
            self.server.kill(self.id)
        for stream in (self.stdin, self.stdout):
            with contextlib.suppress(OSError):
                stream.close()

    def exit_code(self) -> int | None:
        """The ended worker's exit code (negative: the signal), None if unknown."""
        if self.proc is not None:
            return self.proc.wait()
        if self.ended is None and self.server is not None:
            self.ended = self.server.exit_code(self.id)
        return self.ended

    def death_reason(self) -> str:
        """Why the worker ended mid-job, as a problem message."""
        code = self.exit_code()
        if code is None:
            return "renderer stopped unexpectedly"
        if code < 0:
            try:
                name = signal.Signals(-code).name
            except ValueError:
                name = f"signal {-code}"
            if name == "SIGXCPU":  # its CPU time for this icon (or, rarely, for its life)
                return f"took longer than {self.limits.timeout:g} s to render (CPU time); refused"
            return (
                f"renderer crashed ({name}); the file may need more than the "
                f"{self.limits.memory >> 20} MiB render memory limit"
            )
        return f"renderer stopped unexpectedly (exit code {code})"


# Seconds to wait for the fork server's answer about a worker that ended, and for
# the server to end its workers and exit when the pool closes.
_CONTROL_TIMEOUT = 10.0
_CLOSE_SECONDS = 2.0
# Fork the workers from one server where fork is safe after loading cairo and
# fontconfig (Linux; macOS's system libraries are not fork-safe).
_FORK = sys.platform == "linux"


class _Cursor:
    """Reads a reply's entries from a buffer, raising _Incomplete past its end."""

    def __init__(self, buffer: bytearray) -> None:
        self.buffer = buffer
        self.pos = 0

    def take(self, n: int) -> bytes:
        if len(self.buffer) < self.pos + n:
            raise _Incomplete
        chunk = bytes(self.buffer[self.pos : self.pos + n])
        self.pos += n
        return chunk

    def header(self, ok_limit: int) -> tuple[int, bytes]:
        """An entry's status and bytes; status 0 may carry up to ``ok_limit`` bytes."""
        status, n = _HEADER.unpack(self.take(_HEADER.size))
        if status not in (0, 1, _REFUSED) or n > (ok_limit if status == 0 else _MAX_MESSAGE_BYTES):
            raise ValueError("malformed reply")
        return status, self.take(n)

    def entry(self, size: int) -> Mask | str:
        """One mask (status 0, exactly ``size * size`` bytes) or reason (status 1)."""
        status, chunk = self.header(size * size)
        if status == _REFUSED:
            raise ValueError("malformed reply")
        if status == 0:
            if len(chunk) != size * size:
                raise ValueError("malformed reply")
            # Kept as cairo's 8-bit codes: 1 byte a pixel instead of 8.
            return np.frombuffer(chunk, dtype=np.uint8).reshape(size, size)
        return _printable(chunk)


def _printable(chunk: bytes) -> str:
    text = chunk.decode("utf-8", "replace")
    return "".join(ch if ch.isprintable() else " " for ch in text)


def _request(what: Sequence[bytes] | ReadPaints, sizes: Sequence[int]) -> tuple[bytes, int]:
    """One job as the worker reads it (see :mod:`._svg_worker`), and what its reply holds
    (the SVG count, or minus the group cap of a :class:`ReadPaints` job)."""
    head = struct.pack(f">BI{len(sizes)}I", int(isinstance(what, ReadPaints)), len(sizes), *sizes)
    if isinstance(what, ReadPaints):
        body = struct.pack(">II", what.max_groups, len(what.svg)) + what.svg
        return head + body, -what.max_groups
    parts = [head, struct.pack(">I", len(what))]
    for svg in what:
        parts += [struct.pack(">I", len(svg)), svg]
    return b"".join(parts), len(what)


class RenderPool:
    """Up to ``workers`` render processes; use as a context manager."""

    def __init__(self, limits: RenderLimits, *, workers: int = 1) -> None:
        self.limits = limits
        self.size = max(1, workers)
        self.workers: list[_Worker] = []
        self._server: _ForkServer | None = None
        self._no_server = not _FORK

    def __enter__(self) -> RenderPool:
        return self

    def __exit__(
        self,
        exc_type: type[BaseException] | None,
        exc: BaseException | None,
        tb: TracebackType | None,
    ) -> None:
        self.close()

    def close(self) -> None:
        """Stop every worker (and the fork server); the pool can start them again."""
        # Idle workers hold nothing worth a clean exit (their interpreter's
        # shutdown costs tens of ms each), and a busy one is abandoned anyway.
        for w in self.workers:
            w.kill()
        self.workers.clear()
        if self._server is not None:
            self._server.close()
            self._server = None

    def prestart(self) -> RenderPool:
        """Start every worker now, without waiting for them.

        A worker takes a few tenths of a second to start (the renderer's
        import); a caller that starts them before reading its inputs has them
        ready by the time it has work.  When the render cache holds entries
        (a run that may find everything there) the fork server starts but
        loads nothing until the first job: a run that renders nothing then
        costs nothing here, and one that does waits a few hundredths longer.
        """
        from alpha_audit.load.render_cache import probably_warm

        if self._server is None and not self._no_server:
            try:
                self._server = _ForkServer(self.limits, hold=probably_warm())
            except OSError:
                self._no_server = True
        while len(self.workers) < self.size:
            self.workers.append(self._new_worker(release=False))
        return self

    def pause(self) -> None:
        """Let the workers still starting up wait, using no CPU, until work comes.

        For a caller that found nothing to render (every mask cached): the
        start-up it began early would otherwise compete with its own work.
        :meth:`stream` continues them.  Only forked workers can wait this way.
        """
        if self._server is not None and not any(w.jobs for w in self.workers):
            self._server.pause(True)

    def _new_worker(self, *, release: bool = True) -> _Worker:
        if not self._no_server:
            try:
                if self._server is None or self._server.proc.poll() is not None:
                    if self._server is not None:
                        self._server.close()
                    self._server = _ForkServer(self.limits)
                self._server.pause(False)
                if release:
                    self._server.release()
                return _Worker(self.limits, self._server)
            except OSError:
                self._no_server = True  # no fork server here: one process per worker
        return _Worker(self.limits)

    def _replace(self, worker: _Worker) -> None:
        worker.kill()
        self.workers.remove(worker)

    def stream(
        self,
        jobs: Iterable[tuple[T, Sequence[bytes] | ReadPaints, tuple[int, ...]]],
        *,
        ahead: int | None = None,
    ) -> Iterator[tuple[T, Outcome]]:
        """Render ``(tag, svgs, sizes)`` jobs; ``(tag, outcome)`` as each one finishes.

        A job is one icon: its SVGs (or, for a :class:`ReadPaints` job, the
        SVG of each of its paint groups, split by the worker) are rendered at
        every size by one worker within one :attr:`RenderLimits.timeout`, and
        its outcome holds, per SVG, a mask or a reason per size (a
        :class:`PaintsReply` for ReadPaints), or one reason for the whole job.

        Jobs are pulled from ``jobs`` only when needed, so a lazy source (one
        that parses each icon as it is asked for it) works while the workers
        render, and up to ``ahead`` jobs (default: twice the pool size) wait
        ready.  Every worker is started first, so their start-up overlaps that
        work too.  Each worker is sent a few small jobs ahead
        (:data:`_PIPELINE_JOBS`, at most :data:`_PIPELINE_BYTES` unread, which
        the pipe holds without blocking), so it never waits for this process
        between jobs; the time limit still counts per job, from the reply
        before it.  A worker that dies or runs out of time fails only the job
        it was on; the jobs queued behind it go to another worker.  Outcomes
        are yielded in completion order and never kept: memory is bounded by
        the pool, whatever the number of jobs.
        """
        run = _Run(self, iter(jobs), 2 * self.size if ahead is None else max(0, ahead))
        try:
            yield from run.outcomes()
        finally:
            run.selector.close()


class _Run(Generic[T]):
    """One :meth:`RenderPool.stream` call: the jobs pulled but not yet answered."""

    def __init__(
        self,
        pool: RenderPool,
        source: Iterator[tuple[T, Sequence[bytes] | ReadPaints, tuple[int, ...]]],
        limit: int,
    ) -> None:
        self.pool = pool
        self.source = source
        self.exhausted = False
        self.limit = limit
        # (tag, request bytes, SVGs in it, sizes)
        self.queued: deque[tuple[T, bytes, int, tuple[int, ...]]] = deque()
        self.sent: dict[int, tuple[T, bytes, int, tuple[int, ...]]] = {}  # by serial
        self.serial = 0
        self.done: list[tuple[T, Outcome]] = []
        self.selector = selectors.DefaultSelector()
        for kept in pool.workers:  # workers kept from an earlier call
            self.selector.register(kept.stdout, selectors.EVENT_READ, kept)
        if pool._server is not None:
            pool._server.pause(False)
            pool._server.release()

    def outcomes(self) -> Iterator[tuple[T, Outcome]]:
        """``(tag, outcome)`` batches as jobs finish, until the source is exhausted."""
        pool = self.pool
        self.pull()
        while self.queued and len(pool.workers) < pool.size:
            self.start()  # all at once: they start up while the source prepares more work
        while True:
            self.done = []
            self.dispatch()
            busy = [w for w in pool.workers if w.jobs]
            if not busy:
                yield from self.done
                if not self.queued and self.exhausted:
                    return
                continue
            if not self.exhausted and len(self.queued) < self.limit:
                self.pull()  # read ahead while the workers render
                wait = 0.0
            else:
                timeout = pool.limits.timeout
                wait = max(0.0, min(w.deadline(timeout) for w in busy) - time.monotonic())
            self.read(wait)
            self.expire()
            yield from self.done

    def pull(self) -> None:
        """Take the next job from the source into the queue."""
        try:
            tag, what, sizes = next(self.source)
        except StopIteration:
            self.exhausted = True
            return
        self.queued.append((tag, *_request(what, sizes), tuple(sizes)))

    def start(self) -> _Worker:
        worker = self.pool._new_worker()
        self.pool.workers.append(worker)
        self.selector.register(worker.stdout, selectors.EVENT_READ, worker)
        return worker

    def fail(self, worker: _Worker, reason: str) -> None:
        """The job ``worker`` was on fails; those behind it go back to the queue."""
        self.selector.unregister(worker.stdout)
        self.pool._replace(worker)
        if worker.jobs:
            head, *rest = worker.jobs
            self.done.append((self.sent.pop(head[0])[0], reason))
            self.queued.extendleft(self.sent.pop(job) for job, _, _, _ in reversed(rest))

    def dispatch(self) -> None:
        """Pull enough jobs for the idle workers, replace dead ones, and send jobs out."""
        workers = self.pool.workers
        missing = self.pool.size - len(workers)
        idle = sum(not w.jobs for w in workers) + missing
        while not self.exhausted and len(self.queued) < max(idle, 1):
            self.pull()
        while missing > 0 and len(self.queued) > sum(not w.jobs for w in workers):
            self.start()  # replaces a worker that died or was killed
            missing -= 1
        # Fill the least loaded workers first, while their pipes have room.
        for worker in sorted(workers, key=lambda w: len(w.jobs)):
            while self.queued and worker in workers and _room(worker, self.queued[0][1]):
                job = self.queued.popleft()
                try:
                    worker.send(self.serial, job[1], job[2], job[3])
                    self.sent[self.serial] = job
                except (BrokenPipeError, OSError):
                    if worker.jobs:  # it died on an earlier job: seen when read
                        self.queued.appendleft(job)
                        break
                    self.done.append((job[0], worker.death_reason()))
                    self.selector.unregister(worker.stdout)
                    self.pool._replace(worker)
                self.serial += 1

    def read(self, wait: float) -> None:
        """Wait up to ``wait`` seconds for replies and collect the complete ones."""
        for key, _ in self.selector.select(timeout=wait):
            worker = key.data
            try:
                chunk = os.read(worker.stdout.fileno(), 1 << 20)
            except BlockingIOError:
                continue
            if not chunk:
                self.fail(worker, worker.death_reason())
                continue
            worker.buffer += chunk
            try:
                for job, reply in worker.replies():
                    self.done.append((self.sent.pop(job)[0], reply))
            except ValueError:
                self.fail(worker, "renderer sent a malformed reply; refused")

    def expire(self) -> None:
        """Fail the jobs whose worker ran out of time."""
        timeout = self.pool.limits.timeout
        now = time.monotonic()
        for worker in [w for w in self.pool.workers if w.jobs]:
            if worker.deadline(timeout) <= now:
                reason = (
                    f"took longer than {timeout:g} s to render (over "
                    f"{timeout * WALL_FACTOR:g} s of wall-clock time); refused"
                    if worker.ready
                    else f"renderer did not start within {_START_TIMEOUT:g} s"
                )
                self.fail(worker, reason)


def _room(worker: _Worker, request: bytes) -> bool:
    """Whether ``worker``'s pipe takes ``request`` without blocking (see _PIPELINE_JOBS)."""
    if not worker.jobs:
        return True
    return (
        len(worker.jobs) < _PIPELINE_JOBS and worker.pending_bytes + len(request) <= _PIPELINE_BYTES
    )
