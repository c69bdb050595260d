"""What a page says about its icons enters Python checked and bounded, in every engine.

The hostile-names page (``tests/hostile_names.py``: workflow commands after a newline,
ESC, BEL, RLO, a 30,000-character id) is audited: every icon is measured, each name
arrives as the page wrote it (escaping is the renderers' business) but never longer than
its bound, so a 20 KB page cannot make a report of tens of MB.  A probe answer of
another shape (a page in WebKitGTK, where the probe shares the page's world, replaced
what the probe calls) is a page problem, never a crash.
"""

from __future__ import annotations

import os
import shutil
from pathlib import Path

import pytest

from alpha_audit.browser import ENGINES, BrowserError
from alpha_audit.pages import FolderSource, RenderConfig, audit_pages
from alpha_audit.pages.capture import MAX_DOM_PATH, _found_icons
from alpha_audit.safe_text import MAX_NAME
from hostile_names import NAMES, PAGE, assert_inert

ICON = {
    "kind": "svg",
    "path": "svg#ok",
    "box": [1, 2, 24, 24],
    "keys": {"data": "ok", "sprite": None, "file": None, "geometry": "rect x=3"},
    "paints": [{"color": "rgb(1, 2, 3)", "opacity": 1, "kinds": ["fill"], "current": False}],
}


@pytest.fixture(params=list(ENGINES))
def engine(request: pytest.FixtureRequest) -> str:
    cls = ENGINES[request.param]
    if cls.find() is None:
        reason = f"{cls.LABEL} not installed: {cls.INSTALL_HINT}"
        if os.environ.get("CI"):
            pytest.fail(reason, pytrace=False)
        pytest.skip(reason)
    return str(request.param)


def test_every_hostile_name_arrives_bounded_in_every_engine(engine, tmp_path):
    (tmp_path / ".git").mkdir()
    shutil.copy(PAGE, tmp_path / PAGE.name)
    # A page that replaces what the probe measures with: WebKitGTK runs the probe in
    # the page's world, so there its answer has another shape; elsewhere it is isolated.
    (tmp_path / "tamper.html").write_text(
        "<!doctype html><body><svg width=24 height=24><rect width=24 height=24 fill=#333>"
        "</rect></svg><script>Element.prototype.getBoundingClientRect = () => "
        "({left: 'x', top: 0, width: 24, height: 24});</script>",
        encoding="utf-8",
    )
    config = RenderConfig((FolderSource(tmp_path),), root=tmp_path, engines=(engine,), workers=1)
    result = audit_pages(config)
    paths = [p.dom_path for p in result.paints if p.source == PAGE.name]
    assert len(paths) == len(NAMES)
    assert all(len(path) <= MAX_DOM_PATH for path in paths)
    assert paths[:-1] == [f"svg#{name}" for name in NAMES[:-1]]  # as the page wrote them
    long = paths[-1]
    assert len(long) == MAX_DOM_PATH and long.startswith("svg#gxxx") and "…" in long
    assert all(len(p.name) <= MAX_DOM_PATH + MAX_NAME for p in result.paints)
    problems = {p.source: p.message for p in result.run.problems}
    if ENGINES[engine].ISOLATED_SCRIPTS:
        assert problems == {}
    else:
        assert list(problems) == ["tamper.html"]
        assert "the icon probe returned malformed data" in problems["tamper.html"]


@pytest.mark.parametrize(
    ("change", "said"),
    [
        ({"kind": "frame"}, "icon kind"),
        ({"path": ["svg"]}, "DOM path"),
        ({"box": [1, 2, "x", 4]}, "not a finite number"),
        ({"box": [1, 2, None, 4]}, "not a finite number"),
        ({"box": [1, 2]}, "out of range"),
        ({"keys": []}, ""),
        ({"paints": [{"color": "red", "opacity": "1", "kinds": ["fill"], "current": False}]}, ""),
        ({"paints": [{"color": "red", "opacity": 1, "kinds": ["x"], "current": False}]}, ""),
        ({"paints": [{"color": "red", "opacity": 1, "kinds": ["fill"], "current": 1}]}, ""),
        ({"paints": [{"color": "r" * 300, "opacity": 1, "kinds": [], "current": False}]}, ""),
        ({"paints": "fill"}, ""),
    ],
)
def test_a_probe_answer_of_another_shape_is_a_browser_error(change, said):
    with pytest.raises(BrowserError, match=f"malformed data.*{said}"):
        _found_icons({"icons": [{**ICON, **change}]}, "WebKitGTK")
    with pytest.raises(BrowserError, match="malformed data"):
        _found_icons({"icons": "many"}, "WebKitGTK")


def test_long_keys_match_nothing_and_long_paths_keep_their_ends():
    long = "k" * (MAX_NAME + 1)
    raw = {**ICON, "path": "main#app > " + "div > " * 400 + "svg", "keys": {
        "data": long, "sprite": "s" * MAX_NAME, "file": long, "geometry": None}}  # fmt: skip
    (icon,) = _found_icons({"icons": [raw]}, "Chromium")
    assert icon.keys == {"data": None, "sprite": "s" * MAX_NAME, "file": None, "geometry": None}
    assert len(icon.dom_path) == MAX_DOM_PATH
    assert icon.dom_path.startswith("main#app > div") and icon.dom_path.endswith("div > svg")


def test_the_fixture_page_and_its_names_agree():
    text = Path(PAGE).read_text(encoding="utf-8")
    assert text.isascii()
    assert text.count('"x".repeat(30000)') == 1 and len(NAMES[-1]) == 30_001


def test_assert_inert_catches_each_raw_name_and_passes_escaped_ones():
    from alpha_audit.safe_text import safe_text, shorten

    for name in NAMES:
        with pytest.raises(AssertionError):
            assert_inert(f"| icon | {name} |\n")
        assert_inert(f"| icon | {safe_text(shorten(name, MAX_DOM_PATH))} |\n")
