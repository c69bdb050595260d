"""SIGTERM and SIGHUP unwind like Ctrl-C, so every ``with`` block cleans up, then the
process dies of the signal.

A CI cancel, ``timeout``, a container stop or a closed terminal sends SIGTERM or
SIGHUP, whose default action ends the process at once: temporary folders (the
base revision ``check --base`` exports), browsers and half-written files would be
left behind.  :func:`ending_on_signals` makes them an exception
(:class:`Terminated`) that unwinds through every ``with`` block; the CLI runs each
command inside it (:func:`alpha_audit.cli.root.main`).
"""

from __future__ import annotations

import contextlib
import os
import signal
import threading
import time
from collections.abc import Iterator
from types import FrameType

__all__ = ["Terminated", "ending_on_signals"]


class Terminated(BaseException):
    """SIGTERM or SIGHUP arrived: unwind (every ``with`` block cleans up), then die of it."""

    def __init__(self, signum: int) -> None:
        super().__init__(f"received {signal.Signals(signum).name}")
        self.signum = signum


@contextlib.contextmanager
def ending_on_signals() -> Iterator[None]:
    """Within the block, SIGTERM and SIGHUP unwind like SIGINT, then end the process.

    On the way out the signal's default action is restored and the signal sent
    again, so the exit status says "killed by SIGTERM" (143 in a shell) as
    it would have without alpha-audit's clean-up; SIGINT (KeyboardInterrupt)
    does the same.  A second SIGTERM or SIGHUP while the first unwinds is
    ignored, so it cannot cut a clean-up short (SIGKILL still ends the
    process at once).  Only the main thread can receive signals; elsewhere the
    block runs unchanged.
    """
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    raised: list[int] = []

    def raise_terminated(signum: int, frame: FrameType | None) -> None:
        if not raised:
            raised.append(signum)
            raise Terminated(signum)

    handled = (signal.SIGTERM, signal.SIGHUP)
    previous = {sig: signal.signal(sig, raise_terminated) for sig in handled}
    received: int | None = None
    try:
        yield
    except Terminated as exc:
        received = exc.signum
    except KeyboardInterrupt:
        received = signal.SIGINT
    finally:
        for sig, handler in previous.items():
            signal.signal(sig, handler)
    if received is not None:
        signal.signal(received, signal.SIG_DFL)
        os.kill(os.getpid(), received)
        time.sleep(1.0)  # the signal is delivered on return to the interpreter loop
        raise SystemExit(128 + received)  # pragma: no cover - only if the signal is blocked
