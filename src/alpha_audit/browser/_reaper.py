"""Ends a browser's process groups and removes its folder once alpha-audit is gone.

Run as a script (``python -I -S _reaper.py``, standard library only, never
imported by alpha-audit) in a session of its own.  It reads lines from stdin,
``group PGID`` and ``folder PATH``, until end of file: alpha-audit holds the
other end of the pipe, so end of file comes when alpha-audit closed the
browser *or* died in any way (SIGKILL and an out-of-memory kill included).
Then every group gets SIGTERM, a grace period, SIGKILL, and every folder is
removed.  After a normal close there is nothing left to do.
"""

import contextlib
import os
import shutil
import signal
import sys
import time

GRACE = 3.0  # seconds between SIGTERM and SIGKILL


def _alive(group: int) -> bool:
    try:
        os.killpg(group, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


def main() -> None:
    # A Ctrl-C meant for alpha-audit must not stop the clean-up of its browsers.
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGHUP, signal.SIG_IGN)
    groups: list[int] = []
    folders: list[str] = []
    for line in sys.stdin:
        kind, _, value = line.rstrip("\n").partition(" ")
        if kind == "group" and value.isdigit():
            groups.append(int(value))
        elif kind == "folder" and value:
            folders.append(value)
    for sig in (signal.SIGTERM, signal.SIGKILL):
        live = [g for g in groups if _alive(g)]
        for group in live:
            with contextlib.suppress(ProcessLookupError, PermissionError):
                os.killpg(group, sig)
        deadline = time.monotonic() + GRACE
        while live and time.monotonic() < deadline:
            live = [g for g in live if _alive(g)]
            time.sleep(0.05)
    for folder in folders:
        shutil.rmtree(folder, ignore_errors=True)


if __name__ == "__main__":
    main()
