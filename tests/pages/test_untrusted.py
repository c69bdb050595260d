"""Untrusted pages: loopback only (the rest refused and reported), time limits, the root,
and no browser process or profile left after SIGTERM mid-run, in every engine."""

from __future__ import annotations

import contextlib
import os
import signal
import socket
import subprocess
import sys
import threading
import time
import urllib.error
import urllib.request
from pathlib import Path

import pytest

from alpha_audit.browser import ENGINES
from alpha_audit.browser.server import PageServer
from alpha_audit.pages import FolderSource, RenderConfig, audit_pages

ICON = (
    '<svg data-icon="x" width="24" height="24" viewBox="0 0 24 24">'
    '<rect x="4" y="4" width="16" height="16" fill="#333"/></svg>'
)


def _listener() -> tuple[socket.socket, list[bytes]]:
    """A loopback service a page must not reach (a WebDriver port, say)."""
    server = socket.create_server(("127.0.0.1", 0))
    got: list[bytes] = []

    def accept() -> None:
        while True:
            try:
                conn, _ = server.accept()
            except OSError:
                return
            got.append(conn.recv(100))
            conn.close()

    threading.Thread(target=accept, daemon=True).start()
    return server, got


def test_requests_beyond_the_pages_server_are_refused_and_reported(site, tmp_path):
    (tmp_path / ".git").mkdir()
    pages = tmp_path / "pages"
    pages.mkdir()
    service, got = _listener()
    port = service.getsockname()[1]
    (pages / "leak.html").write_text(
        f"<!doctype html><body>{ICON}<img src='http://example.com/pixel.png'>"
        f"<script>fetch('http://127.0.0.1:{port}/session', {{method: 'POST', mode: 'no-cors'}})"
        ".catch(() => 0); fetch('https://example.org/x').catch(() => 0);</script>",
        encoding="utf-8",
    )
    result = audit_pages(RenderConfig((FolderSource(pages),), root=tmp_path, workers=1))
    service.close()
    urls = [b.url for b in result.run.blocked]
    assert "http://example.com/pixel.png" in urls
    assert f"http://127.0.0.1:{port}/session" in urls
    assert "https://example.org:443" in urls
    assert got == []  # the loopback service never saw a connection
    assert [p.icon for p in result.paints] == [None] and result.paints[0].drawn == "#333333"


def test_a_page_that_never_settles_is_a_problem_within_its_time_limit(site, tmp_path):
    (tmp_path / ".git").mkdir()
    pages = tmp_path / "pages"
    pages.mkdir()
    (pages / "busy.html").write_text(
        f"<!doctype html><body>{ICON}<script>setTimeout(() => {{ while (true) {{}} }}, 50)"
        "</script>",
        encoding="utf-8",
    )
    (pages / "fine.html").write_text(f"<!doctype html><body>{ICON}", encoding="utf-8")
    result = audit_pages(RenderConfig((FolderSource(pages),), root=tmp_path, workers=1, timeout=3))
    assert [
        (p.source, "limit" in p.message or "time" in p.message) for p in result.run.problems
    ] == [("busy.html", True)]
    assert [p.source for p in result.paints] == ["fine.html"]  # the next page ran afresh


def test_the_server_keeps_to_its_folder_and_the_project(tmp_path):
    (tmp_path / ".git").mkdir()
    site_dir = tmp_path / "site"
    site_dir.mkdir()
    (site_dir / "a.html").write_text("ok", encoding="utf-8")
    outside = tmp_path.parent / f"{tmp_path.name}-secret.txt"
    outside.write_text("secret", encoding="utf-8")
    (site_dir / "link.txt").symlink_to(outside)
    (tmp_path / "private.txt").write_text("not served", encoding="utf-8")
    opener = urllib.request.build_opener(urllib.request.ProxyHandler({}))
    with PageServer([site_dir], tmp_path) as server:
        assert opener.open(server.url(0, "a.html")).read() == b"ok"
        for path in ("link.txt", "../private.txt", "%2e%2e/private.txt", "nope.html"):
            with pytest.raises(urllib.error.HTTPError) as err:
                opener.open(server.url(0, path))
            assert err.value.code == 404, path
    outside.unlink()


def _processes_naming(folder: Path) -> list[int]:
    """Live processes whose environment or command line names ``folder``."""
    found = []
    needle = str(folder).encode()
    for entry in os.scandir("/proc"):
        if not entry.name.isdigit() or int(entry.name) == os.getpid():
            continue
        try:
            with open(f"/proc/{entry.name}/environ", "rb") as fh:
                environ = fh.read()
            with open(f"/proc/{entry.name}/cmdline", "rb") as fh:
                cmdline = fh.read()
            with open(f"/proc/{entry.name}/stat", "rb") as fh:
                zombie = fh.read().rsplit(b")", 1)[1].split()[0] == b"Z"
        except OSError:
            continue
        if not zombie and (needle in environ or needle in cmdline):
            found.append(int(entry.name))
    return found


@pytest.mark.parametrize("sig", [signal.SIGTERM, signal.SIGINT])
def test_a_signal_mid_run_leaves_no_process_and_no_profile(project, tmp_path, sig):
    temp = tmp_path / "run-tmp"
    temp.mkdir()
    exe = Path(sys.executable).with_name("alpha-audit")
    run = subprocess.Popen(
        [str(exe), "render", "storybook-static", "page", "--globals", "theme:light",
         "--globals", "theme:dark", "--color-scheme", "light", "--color-scheme", "dark",
         "--workers", "2", "-f", "json"],
        cwd=project,
        env={**os.environ, "TMPDIR": str(temp), "NO_COLOR": "1"},
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
        start_new_session=True,
        # As from a terminal: a shell starts background jobs (a CI step run with &) with
        # SIGINT ignored, and a program that finds it ignored keeps ignoring it.
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL),
    )  # fmt: skip
    # Mid-run: both browsers are up (their folders are in the run's TMPDIR).
    deadline = time.monotonic() + 60
    while len(list(temp.glob("alpha-audit-chromium-*"))) < 2:
        assert run.poll() is None and time.monotonic() < deadline, run.stderr.read()
        time.sleep(0.05)
    time.sleep(1.0)
    assert _processes_naming(temp)  # the browsers run in the folder the run was given
    run.send_signal(sig)
    assert run.wait(timeout=30) == -sig  # it died of the signal, after cleaning up
    deadline = time.monotonic() + 10
    while (_processes_naming(temp) or list(temp.iterdir())) and time.monotonic() < deadline:
        time.sleep(0.1)
    assert _processes_naming(temp) == []
    assert list(temp.iterdir()) == []  # no profile, no org.chromium.Chromium.* folder


def test_a_killed_run_is_cleaned_up_by_the_reaper(project, tmp_path):
    temp = tmp_path / "run-tmp"
    temp.mkdir()
    exe = Path(sys.executable).with_name("alpha-audit")
    run = subprocess.Popen(
        [str(exe), "render", "storybook-static", "--workers", "1"],
        cwd=project,
        env={**os.environ, "TMPDIR": str(temp)},
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
        start_new_session=True,
    )
    deadline = time.monotonic() + 60
    while not list(temp.glob("alpha-audit-chromium-*")):
        assert run.poll() is None and time.monotonic() < deadline
        time.sleep(0.05)
    time.sleep(1.0)
    run.kill()  # SIGKILL: no handler runs; the reaper sees its pipe close
    run.wait(timeout=10)
    deadline = time.monotonic() + 15
    while (_processes_naming(temp) or list(temp.iterdir())) and time.monotonic() < deadline:
        time.sleep(0.1)
    assert _processes_naming(temp) == []
    assert list(temp.iterdir()) == []


@pytest.mark.parametrize(
    ("story_id", "said"),
    [("a\x1b]52;c;SGVsbG8=\x07", "U+001B"), ("x\n::add-mask::y", "U+000A"), ("e\u202ev", "U+202E")],
)
def test_a_story_id_holding_a_control_or_bidi_character_is_refused(tmp_path, story_id, said):
    import json

    from alpha_audit.errors import InputError
    from alpha_audit.pages.sources import StorybookSource, targets
    from alpha_audit.safe_text import first_unsafe

    build = tmp_path / "storybook-static"
    build.mkdir()
    (build / "iframe.html").write_text("<html></html>")
    entries = {
        "ok--one": {"type": "story", "id": "ok--one", "title": "Ok", "name": "One"},
        "evil": {"type": "story", "id": story_id, "title": "Evil", "name": "Two"},
    }
    (build / "index.json").write_text(json.dumps({"v": 5, "entries": entries}))
    with pytest.raises(InputError, match=rf"story id '.*' has the .* U\+{said[2:]}") as info:
        targets([StorybookSource(build)])
    assert "index.json" in str(info.value) and first_unsafe(str(info.value)) is None


_PR_SET_CHILD_SUBREAPER = 36  # prctl(2): orphaned descendants are re-parented to the caller


def _children() -> list[tuple[int, str]]:
    """Live children of this process (``/proc``), with their command lines."""
    found = []
    for entry in os.scandir("/proc"):
        if not entry.name.isdigit():
            continue
        try:
            with open(f"/proc/{entry.name}/stat", "rb") as fh:
                fields = fh.read().rsplit(b")", 1)[1].split()
            with open(f"/proc/{entry.name}/cmdline", "rb") as fh:
                command = fh.read().replace(b"\0", b" ").decode(errors="replace")
        except OSError:
            continue
        if int(fields[1]) == os.getpid() and fields[0] != b"Z":
            found.append((int(entry.name), command[:120]))
    return found


def _reap() -> None:
    with contextlib.suppress(ChildProcessError):
        while os.waitpid(-1, os.WNOHANG)[0]:
            pass


@pytest.fixture
def subreaper():
    """This process as a child subreaper for the test: every process the run starts, at
    any depth and in any session (each engine runs in a session of its own), is
    re-parented here when its parent goes, so the process tree says what survived."""
    import ctypes

    libc = ctypes.CDLL(None, use_errno=True)
    if libc.prctl(_PR_SET_CHILD_SUBREAPER, 1, 0, 0, 0) != 0:
        pytest.skip("prctl(PR_SET_CHILD_SUBREAPER) is not available")
    try:
        yield
    finally:
        libc.prctl(_PR_SET_CHILD_SUBREAPER, 0, 0, 0, 0)
        _reap()


@pytest.mark.parametrize("engine", sorted(ENGINES))
def test_sigterm_mid_run_leaves_no_process_of_any_engine_and_no_profile(
    project, tmp_path, subreaper, engine
):
    if ENGINES[engine].find() is None:
        pytest.skip(f"{engine} is not installed")
    temp = tmp_path / "run-tmp"
    temp.mkdir()
    exe = Path(sys.executable).with_name("alpha-audit")
    before = {pid for pid, _ in _children()}
    run = subprocess.Popen(
        [str(exe), "render", "storybook-static", "--engine", engine, "--workers", "2",
         "-f", "json"],
        cwd=project,
        env={**os.environ, "TMPDIR": str(temp), "NO_COLOR": "1"},
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
        start_new_session=True,
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL),
    )  # fmt: skip
    # Mid-run: both browsers are up, each with its programs (a browser and its content
    # processes; WebKitWebDriver, MiniBrowser and Xvfb; Chromium and its helpers).
    deadline = time.monotonic() + 90
    while len(list(temp.glob(f"alpha-audit-{engine}-*"))) < 2 or len(_processes_naming(temp)) < 4:
        assert run.poll() is None and time.monotonic() < deadline, run.stderr.read()
        time.sleep(0.05)
    time.sleep(1.0)
    run.send_signal(signal.SIGTERM)
    assert run.wait(timeout=30) == -signal.SIGTERM  # it died of the signal, after cleaning up
    deadline = time.monotonic() + 15
    left = [c for c in _children() if c[0] not in before]
    while (left or list(temp.iterdir())) and time.monotonic() < deadline:
        _reap()
        time.sleep(0.1)
        left = [c for c in _children() if c[0] not in before]
    assert left == []  # nothing the run started, at any depth, is alive
    assert _processes_naming(temp) == []
    assert list(temp.iterdir()) == []  # no profile, no org.chromium.Chromium.* folder
