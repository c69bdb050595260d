"""Browser processes that never outlive alpha-audit, on every exit path.

Three layers, each covering what the one before cannot:

* :class:`ProcessGroup` starts every program of an engine (the browser, its
  driver, Xvfb) in a session and process group of its own, so that content
  processes, web processes and helpers are ended with their group; ``close``
  sends SIGTERM, waits, then SIGKILLs.  It runs from ``Browser.close``, from a
  finaliser and at interpreter exit.
* :func:`alpha_audit.signals.ending_on_signals` (around every command) turns
  SIGTERM and SIGHUP (a CI cancel, ``timeout``, a container stop, a closed
  terminal) into an exception, as Python already does for SIGINT, so ``with``
  blocks close their browsers; the process then dies of the same signal, as
  the caller expects.
* a *reaper* (``_reaper.py``) per process group, started in its own session,
  holds the read end of a pipe: when alpha-audit is gone for any reason
  (SIGKILL included) it ends the groups and removes the browser's folder.

Children also get ``TMPDIR`` in the browser's own short runtime folder and
``HOME`` inside the browser's folder, so what they leave there (Chromium's
``org.chromium.Chromium.*``, crash report folders) goes with it.
"""

from __future__ import annotations

import contextlib
import os
import signal
import subprocess
import sys
import time
import weakref
from collections.abc import Sequence
from pathlib import Path

from alpha_audit.errors import AlphaAuditError

__all__ = [
    "BrowserError",
    "ProcessGroup",
    "group_members",
    "resident_bytes",
]

# How long a process gets to exit after SIGTERM before it is killed.
_TERMINATE_GRACE = 3.0
_REAPER = Path(__file__).with_name("_reaper.py")


class BrowserError(AlphaAuditError):
    """A browser engine could not be started, did not answer in time, or a script failed."""


def group_members(group: int) -> list[int]:
    """Process ids whose process group is ``group`` (Linux ``/proc``; empty elsewhere)."""
    members = []
    with contextlib.suppress(OSError):
        for entry in os.scandir("/proc"):
            if not entry.name.isdigit():
                continue
            try:
                with open(f"/proc/{entry.name}/stat", "rb") as fh:
                    stat = fh.read()
            except OSError:
                continue  # exited meanwhile
            # pid (comm) state ppid pgrp ...: comm may hold spaces and parentheses.
            fields = stat[stat.rfind(b")") + 2 :].split()
            if len(fields) > 2 and int(fields[2]) == group:
                members.append(int(entry.name))
    return members


def resident_bytes(pids: Sequence[int]) -> int:
    """Resident memory of ``pids`` together, in bytes (Linux ``/proc``; 0 elsewhere)."""
    page = os.sysconf("SC_PAGE_SIZE") if hasattr(os, "sysconf") else 4096
    total = 0
    for pid in pids:
        try:
            with open(f"/proc/{pid}/statm", "rb") as fh:
                total += int(fh.read().split()[1]) * page
        except (OSError, IndexError, ValueError):
            continue
    return total


class ProcessGroup:
    """Child processes, each started in a new session, ended together.

    ``folder`` (and each folder given to :meth:`also_remove`) is removed with
    them by the reaper should alpha-audit die before ``close``.
    """

    def __init__(self, folder: Path | None = None) -> None:
        self._processes: list[subprocess.Popen[bytes]] = []
        self._reaper: list[subprocess.Popen[bytes]] = []
        self._folders = [] if folder is None else [folder]
        # A finalizer also runs at interpreter exit (weakref.finalize.atexit is True).
        self._finalizer = weakref.finalize(
            self, ProcessGroup._end_all, self._processes, self._reaper
        )

    def _tell_reaper(self, line: str) -> None:
        if not self._reaper:
            try:
                reaper = subprocess.Popen(
                    [sys.executable, "-I", "-S", str(_REAPER)],
                    stdin=subprocess.PIPE,
                    stdout=subprocess.DEVNULL,
                    stderr=subprocess.DEVNULL,
                    start_new_session=True,
                )
            except OSError as exc:
                raise BrowserError(f"cannot start the clean-up watcher: {exc}") from exc
            self._reaper.append(reaper)
            for folder in self._folders:
                self._tell_reaper(f"folder {folder}")
        stdin = self._reaper[0].stdin
        assert stdin is not None
        with contextlib.suppress(OSError):
            stdin.write(line.encode() + b"\n")
            stdin.flush()

    def also_remove(self, folder: Path) -> None:
        """Have the reaper remove ``folder`` too (before any process starts)."""
        if folder not in self._folders:
            self._folders.append(folder)
            if self._reaper:
                self._tell_reaper(f"folder {folder}")

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
        self._tell_reaper(f"group {process.pid}")
        return process

    @staticmethod
    def _end_all(
        processes: list[subprocess.Popen[bytes]], reaper: list[subprocess.Popen[bytes]]
    ) -> None:
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
        for watcher in reaper:  # nothing left for it: end of file, and it exits
            if watcher.stdin is not None:
                with contextlib.suppress(OSError):
                    watcher.stdin.close()
            with contextlib.suppress(subprocess.TimeoutExpired):
                watcher.wait(timeout=_TERMINATE_GRACE * 2)
        reaper.clear()

    @property
    def pids(self) -> tuple[int, ...]:
        """Process ids of the group leaders started so far (each leads its own group)."""
        return tuple(p.pid for p in self._processes)

    def members(self) -> list[int]:
        """Every live process in the groups (content and web processes included)."""
        return [pid for leader in self.pids for pid in group_members(leader)]

    def resident_bytes(self) -> int:
        """Resident memory of every process in the groups, in bytes."""
        return resident_bytes(self.members())

    def close(self) -> None:
        """End every process group (idempotent)."""
        self._finalizer()
