"""A pool of sandboxed render processes with a wall-clock limit per icon.

cairosvg runs untrusted SVG from pull requests.  Some inputs take tens of
seconds (a ``<use>`` fan-out under cairosvg's 100k cap), some exhaust memory
or crash the C library, and exceptions escape as many types.  So rendering
happens in worker processes (:mod:`alpha_audit.load._svg_worker`) with
resource limits and an audit hook; this module hands them jobs, enforces
:attr:`RenderLimits.timeout` per icon by killing the worker, and turns every
failure into a one-line reason.  Replies are parsed with fixed-size headers,
never unpickled, so even a compromised worker can only send wrong pixels.
"""

from __future__ import annotations

import contextlib
import os
import selectors
import signal
import struct
import subprocess
import sys
import time
from collections import deque
from collections.abc import Iterable, Iterator, Sequence
from pathlib import Path
from types import TracebackType
from typing import TYPE_CHECKING, TypeVar

import numpy as np
from numpy.typing import NDArray

if TYPE_CHECKING:  # svg imports this module to render: a run-time import back would be a cycle
    from alpha_audit.load.svg import RenderLimits

__all__ = ["Outcome", "RenderPool"]

T = TypeVar("T")

_WORKER = Path(__file__).with_name("_svg_worker.py")
_HEADER = struct.Struct(">BI")
_MAX_MESSAGE_BYTES = 4096
# Jobs sent to a worker before it answers the first: enough that it never waits
# for this process between small jobs.  Their requests stay under a pipe's
# capacity (64 KiB on Linux; 16 KiB is safe everywhere), so writing one never blocks.
_PIPELINE_JOBS = 4
_PIPELINE_BYTES = 16 << 10

# Per job: a reason string when the whole icon failed, else one mask or reason per size.
Outcome = str | list[NDArray[np.uint8] | str]  # 8-bit coverage codes, alpha x 255


class _Worker:
    """One render process and the jobs sent to it, oldest (the one it is on) first."""

    def __init__(self, limits: RenderLimits) -> None:
        self.limits = limits
        # HOME (and USER) set: without them the interpreter asks the account
        # database (NSS, /etc/passwd) at start-up, before the guard is installed.
        env = {
            "PATH": os.environ.get("PATH", ""),
            "OPENBLAS_NUM_THREADS": "1",
            "LC_ALL": "C",
            "HOME": "/nonexistent",
            "USER": "alpha-audit",
            "LOGNAME": "alpha-audit",
            "TZ": "UTC",  # no /etc/localtime
        }
        self.proc = subprocess.Popen(
            [sys.executable, "-I", str(_WORKER), str(limits.memory), str(limits.cpu)],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            stderr=subprocess.DEVNULL,
            env=env,
            cwd=_WORKER.parent,
        )
        assert self.proc.stdin is not None and self.proc.stdout is not None
        self.stdin, self.stdout = self.proc.stdin, self.proc.stdout
        os.set_blocking(self.stdout.fileno(), False)
        # (job, sizes, request bytes) in the order sent; the worker answers in that order.
        self.jobs: deque[tuple[int, tuple[int, ...], int]] = deque()
        self.started = 0.0  # when the oldest job began: the reply before it came then
        self.buffer = bytearray()

    @property
    def pending_bytes(self) -> int:
        return sum(n for _, _, n in self.jobs)

    def deadline(self, timeout: float) -> float:
        """When the job it is on runs out of time (each job gets ``timeout`` of its own)."""
        return self.started + timeout

    def send(self, job: int, svg: bytes, sizes: tuple[int, ...]) -> None:
        request = struct.pack(f">I{len(sizes)}II", len(sizes), *sizes, len(svg)) + svg
        self.stdin.write(request)
        self.stdin.flush()
        if not self.jobs:
            self.started = time.monotonic()
        self.jobs.append((job, sizes, len(request)))

    def replies(self) -> Iterator[tuple[int, list[NDArray[np.uint8] | str]]]:
        """``(job, masks)`` for each complete reply in the buffer; ValueError if malformed."""
        while self.jobs:
            parsed = self._parse(self.jobs[0][1])
            if parsed is None:
                return
            reply, used = parsed
            del self.buffer[:used]
            job, _, _ = self.jobs.popleft()
            self.started = time.monotonic()  # the next job starts now
            yield job, reply
        if self.buffer:
            raise ValueError("malformed reply")

    def _parse(self, sizes: tuple[int, ...]) -> tuple[list[NDArray[np.uint8] | str], int] | None:
        """The first reply in the buffer and its length, None if incomplete."""
        out: list[NDArray[np.uint8] | str] = []
        pos = 0
        for size in sizes:
            if len(self.buffer) < pos + _HEADER.size:
                return None
            status, n = _HEADER.unpack_from(self.buffer, pos)
            pos += _HEADER.size
            if (status == 0 and n != size * size) or (status == 1 and n > _MAX_MESSAGE_BYTES):
                raise ValueError("malformed reply")
            if status not in (0, 1):
                raise ValueError("malformed reply")
            if len(self.buffer) < pos + n:
                return None
            chunk = bytes(self.buffer[pos : pos + n])
            pos += n
            if status == 0:
                # Kept as cairo's 8-bit codes: 1 byte a pixel instead of 8.
                out.append(np.frombuffer(chunk, dtype=np.uint8).reshape(size, size))
            else:
                text = chunk.decode("utf-8", "replace")
                out.append("".join(ch if ch.isprintable() else " " for ch in text))
        return out, pos

    def kill(self) -> None:
        if self.proc.poll() is None:
            self.proc.kill()
        self.proc.wait()
        for stream in (self.stdin, self.stdout):
            with contextlib.suppress(OSError):
                stream.close()

    def death_reason(self) -> str:
        """Why the worker ended mid-job, as a problem message."""
        code = self.proc.wait()
        if code < 0:
            try:
                name = signal.Signals(-code).name
            except ValueError:
                name = f"signal {-code}"
            if name == "SIGXCPU":
                return f"renderer ran out of CPU time (limit {self.limits.cpu} s); refused"
            return (
                f"renderer crashed ({name}); the file may need more than the "
                f"{self.limits.memory >> 20} MiB render memory limit"
            )
        return f"renderer stopped unexpectedly (exit code {code})"


class RenderPool:
    """Up to ``workers`` render processes; use as a context manager."""

    def __init__(self, limits: RenderLimits, *, workers: int = 1) -> None:
        self.limits = limits
        self.size = max(1, workers)
        self.workers: list[_Worker] = []

    def __enter__(self) -> RenderPool:
        return self

    def __exit__(
        self,
        exc_type: type[BaseException] | None,
        exc: BaseException | None,
        tb: TracebackType | None,
    ) -> None:
        # Idle workers hold nothing worth a clean exit (their interpreter's
        # shutdown costs tens of ms each), and a busy one is abandoned anyway.
        for w in self.workers:
            w.kill()
        self.workers.clear()

    def prestart(self) -> RenderPool:
        """Start every worker now, without waiting for them.

        A worker takes a few tenths of a second to start (the renderer's
        import); a caller that starts them before reading its inputs has them
        ready by the time it has work.
        """
        while len(self.workers) < self.size:
            self.workers.append(_Worker(self.limits))
        return self

    def _replace(self, worker: _Worker) -> None:
        worker.kill()
        self.workers.remove(worker)

    def map(self, jobs: Sequence[tuple[bytes, tuple[int, ...]]]) -> list[Outcome]:
        """Render every ``(svg bytes, sizes)`` job; outcomes in job order."""
        results: list[Outcome] = ["not rendered"] * len(jobs)
        for index, outcome in self.stream((i, svg, sizes) for i, (svg, sizes) in enumerate(jobs)):
            results[index] = outcome
        return results

    def stream(
        self, jobs: Iterable[tuple[T, bytes, tuple[int, ...]]], *, ahead: int | None = None
    ) -> Iterator[tuple[T, Outcome]]:
        """Render ``(tag, svg bytes, sizes)`` jobs; ``(tag, outcome)`` as each one finishes.

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
        source = iter(jobs)
        exhausted = False
        queued: deque[tuple[T, bytes, tuple[int, ...]]] = deque()
        limit = 2 * self.size if ahead is None else max(0, ahead)
        timeout = self.limits.timeout
        sent: dict[int, tuple[T, bytes, tuple[int, ...]]] = {}  # by serial, until answered
        selector = selectors.DefaultSelector()
        for kept in self.workers:  # workers kept from an earlier call
            selector.register(kept.stdout, selectors.EVENT_READ, kept)

        def pull() -> None:
            nonlocal exhausted
            try:
                queued.append(next(source))
            except StopIteration:
                exhausted = True

        def start() -> _Worker:
            worker = _Worker(self.limits)
            self.workers.append(worker)
            selector.register(worker.stdout, selectors.EVENT_READ, worker)
            return worker

        def fail(worker: _Worker, reason: str, done: list[tuple[T, Outcome]]) -> None:
            """The job ``worker`` was on fails; those behind it go back to the queue."""
            selector.unregister(worker.stdout)
            self._replace(worker)
            if worker.jobs:
                head, *rest = worker.jobs
                done.append((sent.pop(head[0])[0], reason))
                queued.extendleft(sent.pop(job) for job, _, _ in reversed(rest))

        def room(worker: _Worker, request: bytes) -> bool:
            if not worker.jobs:
                return True
            return (
                len(worker.jobs) < _PIPELINE_JOBS
                and worker.pending_bytes + len(request) + 12 <= _PIPELINE_BYTES
            )

        try:
            pull()
            while queued and len(self.workers) < self.size:
                start()  # all at once: they start up while the source prepares more work
            serial = 0
            while True:
                done: list[tuple[T, Outcome]] = []
                missing = self.size - len(self.workers)
                idle = sum(not w.jobs for w in self.workers) + missing
                while not exhausted and len(queued) < max(idle, 1):
                    pull()
                while missing > 0 and len(queued) > sum(not w.jobs for w in self.workers):
                    start()  # replaces a worker that died or was killed
                    missing -= 1
                # Fill the least loaded workers first, while their pipes have room.
                for worker in sorted(self.workers, key=lambda w: len(w.jobs)):
                    while queued and worker in self.workers and room(worker, queued[0][1]):
                        job = queued.popleft()
                        try:
                            worker.send(serial, job[1], job[2])
                            sent[serial] = job
                        except (BrokenPipeError, OSError):
                            if worker.jobs:  # it died on an earlier job: seen when read
                                queued.appendleft(job)
                                break
                            done.append((job[0], worker.death_reason()))
                            selector.unregister(worker.stdout)
                            self._replace(worker)
                        serial += 1
                busy = [w for w in self.workers if w.jobs]
                if not busy:
                    yield from done
                    if not queued and exhausted:
                        return
                    continue
                if not exhausted and len(queued) < limit:
                    pull()  # read ahead while the workers render
                    wait = 0.0
                else:
                    wait = max(0.0, min(w.deadline(timeout) for w in busy) - time.monotonic())
                for key, _ in selector.select(timeout=wait):
                    worker = key.data
                    try:
                        chunk = os.read(worker.stdout.fileno(), 1 << 20)
                    except BlockingIOError:
                        continue
                    if not worker.jobs:  # an idle worker only speaks to say it died
                        fail(worker, "renderer stopped unexpectedly", done)
                        continue
                    if not chunk:
                        fail(worker, worker.death_reason(), done)
                        continue
                    worker.buffer += chunk
                    try:
                        for job, reply in worker.replies():
                            done.append((sent.pop(job)[0], reply))
                    except ValueError:
                        fail(worker, "renderer sent a malformed reply; refused", done)
                now = time.monotonic()
                for worker in [w for w in self.workers if w.jobs]:
                    if worker.deadline(timeout) <= now:
                        reason = f"took longer than {timeout:g} s to render; refused"
                        fail(worker, reason, done)
                yield from done
        finally:
            selector.close()
