"""Every measured paint points at the line that sets its colour: checked by changing that line.

The truth is the browser's own: a declaration named as the one that sets an
icon's colour (or its backdrop's) is the one whose value, changed in a copy
of the file, changes the colour the engine computes for that icon and for no
icon that names another; every other declaration of the same property,
changed together, changes nothing.  That holds in Chromium (devtools'
matched styles) and, through the probe's own cascade walk, in Firefox and
WebKit, on the real Storybook build and static page (tests/pages/site) and on
a page of cascade cases written for it (tests/pages/cascade: layers,
``!important`` in layers and attributes, specificity, order, media, nesting,
``:is()``/``:where()``, ``inherit``, ``@import`` into a layer, a ``var()``
fallback, a presentation attribute, declarative shadow DOM, a user-agent
colour).  The engines must also agree on every place.
"""

from __future__ import annotations

import importlib.util
import json
import os
import re
import shutil
import subprocess
from collections.abc import Iterator
from dataclasses import dataclass, replace
from pathlib import Path
from urllib.parse import unquote

import jsonschema
import pytest
import tinycss2
from coloraide import Color

from alpha_audit.browser import Browser, LaunchOptions, engine_class
from alpha_audit.browser.server import PageServer
from alpha_audit.findings import Finding
from alpha_audit.gate import judge
from alpha_audit.pages.capture import _PROBE, FoundIcon, capture_page
from alpha_audit.pages.declarations import (
    PaintLocation,
    ServedFiles,
    finding_locations,
    paint_locations,
)
from alpha_audit.pages.sources import FolderSource, StorybookSource, Target, targets
from alpha_audit.pages.states import State
from alpha_audit.policy import Policy
from alpha_audit.render import sarif
from alpha_audit.render.common import RenderOptions
from alpha_audit.results import CheckReport
from alpha_audit.rules import Rule

HERE = Path(__file__).resolve().parent
REPO = HERE.parents[1]
ENGINES = ("chromium", "firefox", "webkit")
DARK = "&globals=theme:dark"
_PLAIN = State("plain", (), None)


def _installed(name: str) -> bool:
    return engine_class(name).find() is not None


class Browsers:
    """One browser per engine, started when first asked for, at device scale 1."""

    def __init__(self) -> None:
        self.opened: dict[str, Browser] = {}

    def __call__(self, engine: str) -> Browser:
        if engine not in self.opened:
            if not _installed(engine):
                pytest.skip(f"{engine} is not installed")
            self.opened[engine] = engine_class(engine)(options=LaunchOptions(scale=2))
        return self.opened[engine]


@pytest.fixture(scope="module")
def browsers() -> Iterator[Browsers]:
    found = Browsers()
    try:
        yield found
    finally:
        for b in found.opened.values():
            b.close()


@pytest.fixture(scope="module")
def root(site: Path, tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A project root: the Storybook build, its story sources, the page and the cascade cases."""
    out = tmp_path_factory.mktemp("declarations")
    (out / ".git").mkdir()
    shutil.copytree(site / "storybook-static", out / "storybook-static")
    shutil.copytree(site / "stories", out / "stories")
    shutil.copytree(site / "page", out / "page")
    shutil.copytree(HERE / "cascade", out / "cascade")
    return out


MOUNTS = ("storybook-static", "page", "cascade")


def _targets(root: Path) -> list[Target]:
    return targets(
        [
            StorybookSource(root / "storybook-static"),
            FolderSource(root / "page"),
            FolderSource(root / "cascade"),
        ]
    )


@dataclass(frozen=True)
class Seen:
    """One capture: the icons, and the places each paint and backdrop names."""

    icons: tuple[FoundIcon, ...]
    backdrops: tuple[str | None, ...]  # the backdrop element's computed background-color
    places: tuple[tuple[tuple[PaintLocation, ...], ...], ...]  # per icon, per paint
    files: ServedFiles


def _look(
    browser: Browser, root: Path, target: Target, suffix: str = "", *, sources: bool = True
) -> Seen:
    """Serve ``root`` afresh (a new origin: nothing cached) and capture ``target``."""
    with PageServer([root / m for m in MOUNTS], root) as server:
        assert target.mount is not None
        url = server.url(target.mount, target.path) + (suffix if target.storybook else "")
        capture = capture_page(
            browser,
            url,
            _PLAIN,
            storybook=target.storybook,
            viewport=(800, 600),
            scale=2,  # the product captures at 2 or more (scale 1 rasters a repaint differently)
            selector=None,
            attribute="data-icon",
            max_icon_size=64,
            sources=sources,
        )
        found = browser.evaluate(f"{_PROBE}.targets()", isolated=browser.ISOLATED_SCRIPTS)
        files = ServedFiles(server.local_file, root)
    assert isinstance(found, dict)
    backdrops = tuple(
        (i.get("backdrop") or {}).get("color") if isinstance(i, dict) else None
        for i in found["icons"]
    )
    places = tuple(
        tuple(
            paint_locations(icon, k if icon.paints else None, target, files)
            for k in range(max(1, len(icon.paints)))
        )
        for icon in capture.icons
    )
    return Seen(capture.icons, backdrops, places, files)


def _rgba(text: str | None) -> tuple[int, ...] | None:
    if text is None:
        return None
    c = Color(text).convert("srgb").fit("srgb", method="clip")
    return tuple(round(float(v) * 255) for v in (*c.coords(nans=False), c.alpha(nans=False)))


def _offset(text: str, line: int, column: int) -> int:
    starts = [0] + [m.end() for m in re.finditer("\n", text)]
    return starts[line - 1] + column - 1


def _rewrite(root: Path, out: Path, edits: dict[Path, list[tuple[int, int, str]]]) -> Path:
    """A copy of ``root`` (hard links) with each (start, end, text) edit made in its file."""
    shutil.rmtree(out, ignore_errors=True)
    shutil.copytree(root, out, copy_function=os.link)
    for file, changes in edits.items():
        text = file.read_text(encoding="utf-8")
        for start, end, new in sorted(changes, reverse=True):
            text = text[:start] + new + text[end:]
        copy = out / file.relative_to(root)
        copy.unlink()  # a new file: the link still names the original's content
        copy.write_text(text, encoding="utf-8")
    return out


def _span_edit(loc: PaintLocation, new: str) -> tuple[Path, tuple[int, int, str]]:
    assert loc.span is not None, loc
    text = loc.file.read_text(encoding="utf-8")
    start = _offset(text, loc.span.start_line, loc.span.start_column)
    end = _offset(text, loc.span.end_line, loc.span.end_column)
    assert text[start:end] == loc.span.text  # the span is exactly what the file holds
    return loc.file, (start, end, new)


def _sentinel(k: int) -> str:
    """Colours no fixture uses, one per declaration changed."""
    return f"#{(17 + 29 * k) % 256:02x}{(211 - 37 * k) % 256:02x}{(5 + 83 * k) % 256:02x}"


_VALUE = re.compile(r"[^:]*:\s*([^;}!]*?)\s*(?:!\s*important\s*)?[;}]")


def _named_in(css: str, name: str, nodes: list[object], found: list[tuple[int, int]]) -> None:
    starts = [0] + [m.end() for m in re.finditer("\n", css)]
    for node in nodes:
        kind = getattr(node, "type", "")
        if kind == "declaration" and getattr(node, "name", None) == name:
            at = starts[node.source_line - 1] + node.source_column - 1
            m = _VALUE.match(css, at)
            if m:
                found.append((m.start(1), m.end(1)))
        content = getattr(node, "content", None)
        if kind in ("qualified-rule", "at-rule") and content is not None:
            _named_in(
                css, name, tinycss2.parse_blocks_contents(content, skip_whitespace=True), found
            )


def _declarations_named(text: str, name: str) -> list[tuple[int, int]]:
    """(start, end) of the value of every declaration of ``name`` in CSS or HTML text.

    Independent of the code under test: tinycss2 over each style sheet (a
    page's ``<style>`` elements found by a regular expression), the value up
    to its ``;``, ``}`` or ``!important``.
    """
    blocks = (
        [(m.start(1), m.group(1)) for m in re.finditer(r"<style>(.*?)</style>", text, re.S)]
        if "<style" in text
        else [(0, text)]
    )
    out: list[tuple[int, int]] = []
    for base, css in blocks:
        found: list[tuple[int, int]] = []
        rules = tinycss2.parse_stylesheet(css, skip_whitespace=True, skip_comments=True)
        _named_in(css, name, rules, found)
        out += [(base + a, base + b) for a, b in found]
    return out


def _colours(seen: Seen) -> list[tuple[tuple[int, ...] | None, ...]]:
    return [
        (*(_rgba(p.get("color")) for p in icon.paints), _rgba(seen.backdrops[k]))
        for k, icon in enumerate(seen.icons)
    ]


def _check_by_changing(browser: Browser, root: Path, seen: Seen, target: Target, suffix: str,
                       tmp: Path) -> None:  # fmt: skip
    """The named declarations set the colours they are named for, and nothing else does.

    In one copy of the project every named declaration gets a colour of its
    own, and every other declaration of the same properties in those files
    (but those the traces pass through, and ``inherit``-like keywords)
    another: each icon must then show exactly its named declaration's colour,
    and an icon with none its old colour.  A declaration named wrongly, or a
    "loser" that in fact wins, shows as another colour.
    """
    named: dict[tuple[Path, int, int], PaintLocation] = {}
    expect: dict[tuple[int, int | None], tuple[Path, int, int]] = {}  # (icon, paint) -> key
    for k, per_paint in enumerate(seen.places):
        for paint, places in enumerate(per_paint):
            for loc in places:
                if loc.span is None or loc.what not in ("css-colour", "css-backdrop"):
                    continue
                if loc.what == "css-backdrop" and loc.property != "background-color":
                    continue  # a gradient's stop: its computed background-color stays transparent
                key = (loc.file, loc.span.start_line, loc.span.start_column)
                named[key] = loc
                expect[(k, paint if loc.what == "css-colour" else None)] = key
    assert any(p is not None for _, p in expect), f"no colour of {target.name} was traced"
    sentinel = {key: _sentinel(n) for n, key in enumerate(named)}
    edits: dict[Path, list[tuple[int, int, str]]] = {}
    for key, loc in named.items():
        file, edit = _span_edit(loc, sentinel[key])
        edits.setdefault(file, []).append(edit)
    hops = {
        (p.file, p.span.start_line, p.span.start_column)
        for icon in seen.icons
        if icon.sources is not None
        for t in (*icon.sources.paints, icon.sources.backdrop)
        if t is not None
        for d in t.hops
        if (p := seen.files.place(d)) is not None and p.span is not None
    }
    n = len(named)
    for file in {loc.file for loc in named.values()}:
        text = file.read_text(encoding="utf-8")
        names = {text[_offset(text, loc.line, loc.column) :].split(":")[0].strip()
                 for loc in named.values() if loc.file == file}  # fmt: skip
        for name in names:
            for start, end in _declarations_named(text, name):
                line = text.count("\n", 0, start) + 1
                column = start - (text.rfind("\n", 0, start) + 1) + 1
                value = text[start:end].strip().lower()
                if (file, line, column) in hops or value in ("inherit", "currentcolor", "unset"):
                    continue
                edits.setdefault(file, []).append((start, end, _sentinel(n)))
                n += 1
    assert n > len(named), f"{target.name}: no other declaration to change"
    changed = _look(browser, _rewrite(root, tmp / "changed", edits), target, suffix, sources=False)
    before, after = _colours(seen), _colours(changed)
    for k, icon in enumerate(changed.icons):
        for paint in [*range(len(icon.paints)), None]:
            key = expect.get((k, paint))
            column = len(icon.paints) if paint is None else paint
            wanted = _rgba(sentinel[key]) if key is not None else before[k][column]
            assert after[k][column] == wanted, (target.name, icon.dom_path, paint, named.get(key))


# The states each engine audits: the Storybook's stories in the dark theme and the two
# whose light theme differs in kind (a translucent chip, the failing alert), the page,
# and the cascade cases.  Chromium changes declarations in all of them, Firefox and
# WebKit in the three richest; every engine must name the same places as Chromium.
STATES = (
    ("icons--toolbar", DARK),
    ("icons--sprite", DARK),
    ("icons--images", DARK),
    ("icons--alert", DARK),
    ("icons--alert", ""),
    ("icons--chip", ""),
    ("icons--chip", DARK),
    ("page", ""),
    ("cascade", ""),
)
CHANGED_ELSEWHERE = {("icons--alert", DARK), ("icons--chip", ""), ("cascade", "")}


def _target(root: Path, name: str) -> Target:
    mount = {"page": 1, "cascade": 2}.get(name)
    return next(t for t in _targets(root) if (t.mount == mount if mount else t.name == name))


def _key(seen: Seen) -> list[list[list[tuple[object, ...]]]]:
    return [
        [
            [(p.file, p.line, p.column, p.what, p.span.text if p.span else None) for p in places]
            for places in per_paint
        ]
        for per_paint in seen.places
    ]


@pytest.fixture(scope="module")
def reference(browsers: Browsers, root: Path) -> dict[tuple[str, str], Seen]:
    """Chromium's captures (devtools' matched styles), filled as the tests go."""
    return {}


def _chromium(browsers: Browsers, root: Path, reference: dict[tuple[str, str], Seen],
              state: tuple[str, str]) -> Seen:  # fmt: skip
    if state not in reference:
        reference[state] = _look(browsers("chromium"), root, _target(root, state[0]), state[1])
    return reference[state]


@pytest.mark.parametrize("state", STATES, ids=lambda s: s[0] + ("-dark" if s[1] else ""))
def test_chromium_names_the_declaration_the_browser_applies(
    browsers: Browsers,
    root: Path,
    reference: dict[tuple[str, str], Seen],
    tmp_path: Path,
    state: tuple[str, str],
) -> None:
    seen = _chromium(browsers, root, reference, state)
    target = _target(root, state[0])
    _check_by_changing(browsers("chromium"), root, seen, target, state[1], tmp_path)


@pytest.mark.parametrize("engine", ["firefox", "webkit"])
def test_the_cascade_walk_names_the_declaration_the_browser_applies(
    browsers: Browsers,
    root: Path,
    reference: dict[tuple[str, str], Seen],
    tmp_path: Path,
    engine: str,
) -> None:
    """Firefox and WebKit walk the cascade themselves: the same places, and they hold."""
    browser = browsers(engine)
    for state in STATES:
        if state in (("icons--alert", ""), ("icons--chip", DARK)):
            continue  # the same rules as their other theme: Chromium covers both
        target = _target(root, state[0])
        seen = _look(browser, root, target, state[1])
        assert _key(seen) == _key(_chromium(browsers, root, reference, state)), (engine, state)
        if state in CHANGED_ELSEWHERE:
            _check_by_changing(browser, root, seen, target, state[1], tmp_path)


def test_the_walk_in_chromium_agrees_with_devtools(
    browsers: Browsers,
    root: Path,
    reference: dict[tuple[str, str], Seen],
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    chromium = browsers("chromium")
    monkeypatch.setattr(type(chromium), "matched_styles", lambda self, e, p: None)
    for state in (("icons--toolbar", DARK), ("cascade", "")):
        walked = _look(chromium, root, _target(root, state[0]), state[1])
        assert _key(walked) == _key(_chromium(browsers, root, reference, state)), state


def test_the_cascade_cases_point_where_expected(
    browsers: Browsers, root: Path, reference: dict[tuple[str, str], Seen]
) -> None:
    """Each case's declaration, read off the line it names (what the cases were written for)."""
    seen = _chromium(browsers, root, reference, ("cascade", ""))
    lines = {
        icon.keys["data"]: [
            (p.file.name, p.file.read_text().split("\n")[p.line - 1].strip())
            for p in places[0]
            if p.what == "css-colour"
        ]
        for icon, places in zip(seen.icons, seen.places, strict=True)
    }
    assert lines["layered"] == [("base.css", ".layered { color: #1b5e20; }")]  # later layer wins
    assert lines["important-layers"] == [("base.css", ".imp { color: #5b6b00 !important; }")]
    assert lines["specificity"] == [("base.css", "#spec { color: #00695c; }")]
    assert lines["order"] == [("base.css", ".o1 { color: #283593; }")]
    assert lines["important-rule"] == [("base.css", ".si { color: #2e7d32 !important; }")]
    assert lines["media"] == [("base.css", "@media (min-width: 1px) { .md { color: #0277bd; } }")]
    assert lines["nesting"] == [("base.css", "& svg { color: #37474f; }")]
    assert lines["where"] == [("base.css", "svg.wc { color: #455a64; }")]
    assert lines["is"] == [("base.css", ":is(#w2, .x) svg { color: #6d4c41; }")]
    assert lines["inherit"] == [("base.css", ".outer { --ic: #1565c0; }")]
    assert lines["stroke-var"] == [("base.css", ".fc { --fc: #558b2f; }")]
    assert lines["imported"] == [("tokens.css", "--imported: #7a3e9d;")]
    assert lines["fallback"] == [("base.css", ".fb { color: var(--undefined-here, #8e24aa); }")]
    assert lines["inherited-body"] == [("index.html", "body { margin: 8px; color: #212121; }")]
    assert lines["shadow"] == [("index.html", "svg { color: #5d4037; }")]
    for name, attribute in (
        ("style-attribute", 'style="color: #f9a825"'),
        ("important-attribute", 'style="color: #3949ab !important"'),
        ("presentation", 'stroke="#aa3300"'),
    ):
        ((file, line),) = lines[name]
        assert file == "index.html" and attribute in line, name
    assert lines["button"] == []  # the engine's own button colour: no line of the project


def test_story_paints_fall_back_to_the_story_export(
    browsers: Browsers, root: Path, reference: dict[tuple[str, str], Seen]
) -> None:
    seen = _chromium(browsers, root, reference, ("icons--toolbar", DARK))
    last = seen.places[0][0][-1]
    assert last.what == "story" and last.file == root / "stories/icons.stories.js"
    assert last.file.read_text().split("\n")[last.line - 1].startswith("export const Toolbar")


# ------------------------------------------------------------------------- SARIF
@pytest.fixture(scope="module")
def sarif_schema() -> dict[str, object]:
    """The SARIF 2.1.0 schema (tools/sarif_schema.py: fetched once with npm, cached)."""
    spec = importlib.util.spec_from_file_location("sarif_schema", REPO / "tools/sarif_schema.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    try:
        schema: dict[str, object] = module.sarif_schema()
    except (RuntimeError, subprocess.CalledProcessError) as exc:
        if os.environ.get("CI"):
            pytest.fail(f"the SARIF schema could not be fetched: {exc}", pytrace=False)
        pytest.skip(f"the SARIF schema could not be fetched: {exc}")
    return schema


def test_sarif_without_an_iconset_has_a_line_for_every_result(
    browsers: Browsers,
    root: Path,
    reference: dict[tuple[str, str], Seen],
    sarif_schema: dict[str, object],
) -> None:
    """A finding per measured paint of every state, its locations from the paint alone (no
    manifest): the SARIF render/sarif.py writes validates against SARIF 2.1.0, and every
    result has a physical location with a line, in a file of the project that holds it."""
    found = []
    for state in STATES:
        seen = _chromium(browsers, root, reference, state)
        target = _target(root, state[0])
        for icon in seen.icons:
            for paint in range(max(1, len(icon.paints))):
                where = finding_locations(icon, paint if icon.paints else None, target, seen.files)
                found.append(
                    Finding(
                        rule=Rule.BELOW_THRESHOLD,
                        theme="theme:dark" if state[1] else "default",
                        iconset=target.name,
                        canvas=None,
                        icons=(icon.dom_path,),
                        message="below 3:1",
                        locations=where,
                    )
                )
    report = CheckReport((), judge((), Policy(), found))
    doc = json.loads(sarif.render_report(report, RenderOptions(base=root)))
    validator = jsonschema.Draft4Validator(sarif_schema)
    validator.validate(doc)
    broken = json.loads(json.dumps(doc))  # the check can fail: a region with no line
    del broken["runs"][0]["results"][0]["locations"][0]["physicalLocation"]["region"]["startLine"]
    assert not validator.is_valid(broken)
    results = doc["runs"][0]["results"]
    # Root causes sharing the declaration that sets their colour are one result (folded by
    # the line and column that cause them); every finding is in one.
    folded = [r["properties"].get("rootCauses", 1) for r in results]
    assert sum(folded) == len(found) > 30
    css = 0
    for result in results:
        (first,) = result["locations"]
        for place in (first, *result.get("relatedLocations", ())):
            physical = place["physicalLocation"]
            uri = physical["artifactLocation"]["uri"]
            assert not uri.startswith(("/", "..")) and (root / unquote(uri)).is_file(), uri
            assert physical["region"]["startLine"] >= 1
        css += first["physicalLocation"]["artifactLocation"]["uri"].endswith(".css")
    # Most paints are named by their CSS first (the rest: the cascade page's markup,
    # and the icons whose colour no project line sets).
    assert css >= len(results) // 2


def test_a_page_too_large_to_walk_is_still_captured(
    browsers: Browsers, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The walk is bounded (selector matches over all traced elements): a page beyond it has
    no sources, and its icons are captured as before."""
    project = tmp_path / "big"
    (project / ".git").mkdir(parents=True)
    (project / "page").mkdir()
    # 12,000 rules every <svg> is a candidate for, 60 icons: 720,000 matches to try.
    (project / "page" / "big.css").write_text(
        "".join(f"svg:not(.x{k}) {{ color: #{k % 4096:03x}; }}\n" for k in range(12000))
    )
    svg = ('<svg width="16" height="16" viewBox="0 0 16 16" fill="none" '
           'stroke="currentColor"><path d="M2 2h12v12H2z"/></svg>')  # fmt: skip
    (project / "page" / "index.html").write_text(
        '<!doctype html><link rel="stylesheet" href="big.css"><div>' + svg * 60 + "</div>"
    )
    target = replace(targets([FolderSource(project / "page")])[0], mount=MOUNTS.index("page"))
    chromium = browsers("chromium")
    monkeypatch.setattr(type(chromium), "matched_styles", lambda self, e, p: None)
    walked = _look(chromium, project, target)
    assert len(walked.icons) == 60 and all(i.sources is None for i in walked.icons)
    assert all(p.what == "page" for places in walked.places for p in places[0])
