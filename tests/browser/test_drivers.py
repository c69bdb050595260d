"""The driver interface in every engine: values, errors, timeouts and process cleanup."""

from __future__ import annotations

import io
import os
import time

import numpy as np
import pytest
from PIL import Image

from alpha_audit.browser import ENGINES, BrowserError, engine_class, installed_engines
from alpha_audit.browser.interface import json_expression
from alpha_audit.errors import UsageError

# (JS expression, the JSON value every engine must return)
VALUES = [
    ("1 + 1", 2),
    ("0.1 + 0.2", 0.30000000000000004),  # doubles survive the trip bit for bit
    ("'é\\u0000\"'", 'é\x00"'),
    ("[1, 'a', null, true]", [1, "a", None, True]),
    ("({a: {b: [2.5]}})", {"a": {"b": [2.5]}}),
    ("undefined", None),
    ("Promise.resolve(7)", 7),
    ("new Promise((r) => setTimeout(() => r('late'), 50))", "late"),
    ("document.getElementById('p').textContent", "hello"),
]


def _groups_gone(pids: list[int], within: float = 5.0) -> bool:
    """Whether no process is left in any of the process groups led by ``pids``."""
    deadline = time.monotonic() + within
    while time.monotonic() < deadline:
        alive = 0
        for pid in pids:
            try:
                os.killpg(pid, 0)
                alive += 1
            except ProcessLookupError:
                pass
        if not alive:
            return True
        time.sleep(0.05)
    return False


def test_json_expression_awaits_and_serialises():
    assert json_expression("x") == '(async () => JSON.stringify(await (x)) ?? "null")()'


def test_unknown_engine_names_the_valid_ones():
    with pytest.raises(UsageError, match="chromium, firefox, webkit"):
        engine_class("netscape")


def test_installed_engines_are_registered_and_found():
    found = installed_engines()
    assert set(found) <= set(ENGINES)
    for name, where in found.items():
        assert where.engine == name and where.binary.is_file()


def test_driver_values_errors_timeouts_and_cleanup(engine):
    name, installation = engine
    with ENGINES[name](installation, timeout=30) as browser:
        pids = list(browser.processes.pids)
        workdir = browser.workdir
        assert browser.version
        browser.open_html("<!doctype html><p id=p>hello</p>")
        got = [browser.evaluate(expression) for expression, _ in VALUES]
        assert got == [value for _, value in VALUES]
        with pytest.raises(BrowserError, match="script error"):
            browser.evaluate("no_such_name.x")
        with pytest.raises(BrowserError, match="script error"):
            browser.evaluate("Promise.reject(new Error('boom'))")
        started = time.monotonic()
        with pytest.raises(BrowserError):
            browser.evaluate("new Promise(() => {})", timeout=2)
        assert time.monotonic() - started < 15
        assert browser.evaluate("2 * 21") == 42  # still usable after a timeout
    assert _groups_gone(pids), f"{name} left processes behind"
    assert not workdir.exists()
    with pytest.raises(BrowserError, match="closed"):
        browser.evaluate("1")


def test_processes_end_when_the_block_raises(engine):
    name, installation = engine
    with pytest.raises(ZeroDivisionError), ENGINES[name](installation, timeout=30) as browser:
        pids = list(browser.processes.pids)
        1 / 0  # noqa: B018
    assert _groups_gone(pids), f"{name} left processes behind after an exception"


# Three flat boxes at known places, in sRGB codes; nothing antialiased.
SHOT_PAGE = """<!doctype html><style>html,body{margin:0;background:#102030}
div{position:absolute}</style>
<div style="left:10px;top:20px;width:30px;height:40px;background:#ff8000"></div>
<div style="right:0;bottom:0;width:5px;height:7px;background:#00ff7f"></div>
<div style="left:300px;top:0;width:1px;height:100%;background:#fefefe"></div>"""


def test_viewport_and_screenshot_show_the_page_pixel_for_pixel(engine):
    name, installation = engine
    with ENGINES[name](installation, timeout=30) as browser:
        browser.open_html(SHOT_PAGE)
        for width, height in ((640, 360), (801, 613)):  # MiniBrowser is never under ~450 px
            browser.set_viewport(width, height)
            assert browser.evaluate("[innerWidth, innerHeight, devicePixelRatio]") == [
                width,
                height,
                1,
            ]
            shot = np.asarray(Image.open(io.BytesIO(browser.screenshot())).convert("RGB"))
            expected = np.empty((height, width, 3), dtype=np.uint8)
            expected[:] = (0x10, 0x20, 0x30)
            expected[20:60, 10:40] = (0xFF, 0x80, 0x00)
            expected[:, 300] = (0xFE, 0xFE, 0xFE)
            expected[-7:, -5:] = (0x00, 0xFF, 0x7F)
            assert shot.shape == expected.shape
            assert np.array_equal(shot, expected), f"{name}: {np.argwhere(shot != expected)[:3]}"
        with pytest.raises(BrowserError, match="viewport 0 x 10"):
            browser.set_viewport(0, 10)


def _flaky_engine(failures: int):
    """A Browser whose first ``failures`` launches fail after starting a real process."""
    import sys
    from pathlib import Path
    from typing import ClassVar

    from alpha_audit.browser.interface import Browser, Installation

    class Flaky(Browser):
        NAME = LABEL = INSTALL_HINT = "flaky"
        starts: ClassVar[list[tuple[Path, int, float]]] = []

        @classmethod
        def find(cls):
            return Installation("flaky", Path(sys.executable))

        def _start(self):
            child = self.processes.start([sys.executable, "-c", "import time; time.sleep(60)"])
            Flaky.starts.append((self.workdir, child.pid, self.timeout))
            if len(Flaky.starts) <= failures:
                raise BrowserError("POST /session: timed out")

        def _navigate(self, *args):
            raise NotImplementedError

        def _evaluate_text(self, expression, timeout, isolated):
            raise NotImplementedError

        _set_viewport = _screenshot = _shutdown = _navigate

    return Flaky


def test_a_launch_that_fails_is_started_again_from_nothing():
    from alpha_audit.browser.interface import LAUNCH_TIMEOUT

    flaky = _flaky_engine(failures=1)
    with flaky(timeout=LAUNCH_TIMEOUT * 3) as browser:
        (first_dir, first_pid, first_wait), (second_dir, _, _) = flaky.starts
        assert first_dir != second_dir == browser.workdir
        assert not first_dir.exists() and _groups_gone([first_pid])  # nothing of it is left
        assert first_wait == LAUNCH_TIMEOUT  # a hanging launch is not waited on for long
        assert browser.timeout == LAUNCH_TIMEOUT * 3  # pages still get the whole timeout


def test_a_launch_that_keeps_failing_raises_its_error_after_the_last_attempt():
    from alpha_audit.browser.interface import LAUNCH_ATTEMPTS

    flaky = _flaky_engine(failures=LAUNCH_ATTEMPTS)
    with pytest.raises(BrowserError, match="POST /session: timed out"):
        flaky(timeout=5)
    assert len(flaky.starts) == LAUNCH_ATTEMPTS
    assert [w for w, _, _ in flaky.starts if w.exists()] == []
    assert [t for _, _, t in flaky.starts] == [5.0] * LAUNCH_ATTEMPTS
    assert _groups_gone([pid for _, pid, _ in flaky.starts])
