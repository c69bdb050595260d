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

# Per job: a reason string when the whole icon failed, else one mask or reason per size.
Outcome = str | list[NDArray[np.uint8] | str]  # 8-bit coverage codes, alpha x 255


class _Worker:
    """One render process and the job it is working on."""

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
        self.job: int | None = None
        self.sizes: tuple[int, ...] = ()
        self.deadline = 0.0
        self.buffer = bytearray()

    def send(self, job: int, svg: bytes, sizes: tuple[int, ...], timeout: float) -> None:
        self.job, self.sizes, self.buffer = job, sizes, bytearray()
        request = struct.pack(f">I{len(sizes)}II", len(sizes), *sizes, len(svg)) + svg
        self.stdin.write(request)
        self.stdin.flush()
        self.deadline = time.monotonic() + timeout

    def parse(self) -> list[NDArray[np.uint8] | str] | None:
        """The complete reply in the buffer, None if incomplete; ValueError if malformed."""
        out: list[NDArray[np.uint8] | str] = []
        pos = 0
        for size in self.sizes:
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
        if pos != len(self.buffer):
            raise ValueError("malformed reply")
        return out

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

        Jobs are pulled from ``jobs`` only when needed: one for each idle
        worker, and up to ``ahead`` (default: twice the pool size) read ahead
        while every worker is busy, so a lazy source (one that parses each
        icon as it is asked for it) works in parallel with the renders.
        Every worker is started first, so their start-up overlaps that work
        too.  Outcomes are yielded in completion order and never kept: memory
        is bounded by the pool, whatever the number of jobs.
        """
        source = iter(jobs)
        exhausted = False
        queued: deque[tuple[T, bytes, tuple[int, ...]]] = deque()
        limit = 2 * self.size if ahead is None else max(0, ahead)
        tags: dict[int, T] = {}
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

        def retire(worker: _Worker) -> None:
            selector.unregister(worker.stdout)
            self._replace(worker)

        try:
            pull()
            while queued and len(self.workers) < self.size:
                start()  # all at once: they start up while the source prepares more work
            serial = 0
            while True:
                done: list[tuple[T, Outcome]] = []
                idle = [w for w in self.workers if w.job is None]
                missing = self.size - len(self.workers)
                while not exhausted and len(queued) < len(idle) + missing:
                    pull()
                while missing > 0 and len(queued) > len(idle):
                    idle.append(start())  # replaces a worker that died or was killed
                    missing -= 1
                for worker in idle:
                    if not queued:
                        break
                    tag, svg, sizes = queued.popleft()
                    try:
                        worker.send(serial, svg, sizes, self.limits.timeout)
                        tags[serial] = tag
                    except (BrokenPipeError, OSError):
                        done.append((tag, worker.death_reason()))
                        retire(worker)
                    serial += 1
                busy = [w for w in self.workers if w.job is not None]
                if not busy:
                    yield from done
                    if not queued and exhausted:
                        return
                    continue
                if not exhausted and len(queued) < limit:
                    pull()  # read ahead while the workers render
                    wait = 0.0
                else:
                    wait = max(0.0, min(w.deadline for w in busy) - time.monotonic())
                for key, _ in selector.select(timeout=wait):
                    worker = key.data
                    try:
                        chunk = os.read(worker.stdout.fileno(), 1 << 20)
                    except BlockingIOError:
                        continue
                    if worker.job is None:  # an idle worker only speaks to say it died
                        retire(worker)
                        continue
                    outcome: Outcome | None
                    if not chunk:
                        outcome = worker.death_reason()
                    else:
                        worker.buffer += chunk
                        try:
                            outcome = worker.parse()
                        except ValueError:
                            outcome = "renderer sent a malformed reply; refused"
                    if outcome is None:
                        continue
                    done.append((tags.pop(worker.job), outcome))
                    worker.job = None
                    if isinstance(outcome, str):
                        retire(worker)
                now = time.monotonic()
                for worker in [w for w in self.workers if w.job is not None]:
                    if worker.deadline <= now and worker.job is not None:
                        reason = f"took longer than {self.limits.timeout:g} s to render; refused"
                        done.append((tags.pop(worker.job), reason))
                        worker.job = None
                        retire(worker)
                yield from done
        finally:
            selector.close()
