"""Every engine runs the same whatever the caller's folders: a 100-character TMPDIR, and a
home that must stay as it was.

Chromium's singleton socket lives under its TMPDIR, and a Unix socket path has 108
bytes (unix(7)); before the browsers got a short runtime folder of their own, a
TMPDIR of about 30 characters made Chromium die at start.  Chromium and Firefox also
wrote ``Crash Reports`` (and Firefox ``Downloads``) into the user's home on every run.
"""

from __future__ import annotations

import os
import shutil
import tempfile
from collections.abc import Iterator
from pathlib import Path

import pytest

from alpha_audit.browser import ENGINES
from alpha_audit.browser.interface import MAX_RUNTIME_BYTES

LONG = 100  # characters of the caller's TMPDIR


@pytest.fixture
def long_tmpdir(monkeypatch: pytest.MonkeyPatch) -> Iterator[Path]:
    """A TMPDIR of exactly :data:`LONG` characters, for this process and its children
    (made under /tmp: the suite's own TMPDIR may already be that long)."""
    base = Path(tempfile.mkdtemp(prefix="alpha-audit-long-", dir="/tmp"))
    folder = base / ("x" * (LONG - len(str(base)) - 1))
    folder.mkdir()
    assert len(str(folder)) == LONG
    monkeypatch.setenv("TMPDIR", str(folder))
    monkeypatch.setattr(tempfile, "tempdir", None)  # gettempdir() reads TMPDIR again
    try:
        yield folder
    finally:
        shutil.rmtree(base, ignore_errors=True)


@pytest.fixture
def fresh_home(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """An empty HOME, with no XDG folder elsewhere: anything an engine writes shows here."""
    home = tmp_path / "home"
    home.mkdir()
    monkeypatch.setenv("HOME", str(home))
    for name in ("XDG_CONFIG_HOME", "XDG_DATA_HOME", "XDG_CACHE_HOME", "XDG_STATE_HOME"):
        monkeypatch.delenv(name, raising=False)
    return home


def test_each_engine_starts_with_a_long_tmpdir_and_leaves_no_trace(engine, long_tmpdir, fresh_home):
    name, installation = engine
    with ENGINES[name](installation, timeout=60) as browser:
        runtime = browser.runtime
        assert browser.workdir.parent == long_tmpdir  # the profile stays where asked
        assert len(os.fsencode(runtime)) <= MAX_RUNTIME_BYTES
        browser.open_html("<!doctype html><p id=p>hello</p>")
        assert browser.evaluate("document.getElementById('p').textContent") == "hello"
        assert browser.screenshot().startswith(b"\x89PNG")
    assert list(long_tmpdir.iterdir()) == []  # no profile, no org.chromium.Chromium.*
    assert not runtime.exists()
    assert sorted(p.relative_to(fresh_home).as_posix() for p in fresh_home.rglob("*")) == []


def test_a_short_tmpdir_keeps_the_runtime_folder_inside_the_browsers_own(
    engine, tmp_path, monkeypatch
):
    name, installation = engine
    short = Path("/tmp") if len(str(tmp_path)) > 40 else tmp_path
    monkeypatch.setenv("TMPDIR", str(short))
    monkeypatch.setattr(tempfile, "tempdir", None)
    with ENGINES[name](installation, timeout=60) as browser:
        assert browser.runtime == browser.workdir / "tmp"
