"""Source maps: the VLQ decoder against the format's definition and against esbuild's maps.

esbuild is the CSS minifier Vite runs (it is in the fixture Storybook's
node_modules); its map of the Storybook's own ``.storybook/theme.css`` is the
real thing to read.  Through it, a finding names the original file and line.
"""

from __future__ import annotations

import re
import shutil
import subprocess
from pathlib import Path

import pytest
import tinycss2
from hypothesis import given
from hypothesis import strategies as st

from alpha_audit.pages.cascade import Declaration, ServedPlace
from alpha_audit.pages.declarations import ServedFiles
from alpha_audit.pages.sourcemap import (
    SourceMap,
    SourceMapError,
    decode_vlq,
    inline_map,
    mapping_url,
    source_file,
)

_DIGITS = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/"


def _encode(value: int) -> str:
    """ECMA-426, 5.1, written from the definition: sign in bit 0, 5 bits a digit, bit 5 more."""
    v = (-value << 1) | 1 if value < 0 else value << 1
    out = ""
    while True:
        digit, v = v & 31, v >> 5
        out += _DIGITS[digit | (32 if v else 0)]
        if not v:
            return out


@given(st.lists(st.integers(-(2**40), 2**40), min_size=1, max_size=6))
def test_vlq_decodes_what_the_definition_encodes(values: list[int]) -> None:
    assert decode_vlq("".join(_encode(v) for v in values)) == values


@pytest.mark.parametrize(
    ("field", "values"),
    [
        ("A", [0]),
        ("C", [1]),
        ("D", [-1]),
        ("gB", [16]),  # the first value that needs a continuation digit
        ("AAAA", [0, 0, 0, 0]),
        ("AACA", [0, 0, 1, 0]),
        ("//////D", [-(2**31 - 1)]),  # 2**32 - 1 in seven digits, odd: negative
        ("%", None),
        ("g", None),  # a continuation digit with nothing after it
    ],
)
def test_vlq_fields(field: str, values: list[int] | None) -> None:
    if values is None:
        with pytest.raises(SourceMapError):
            decode_vlq(field)
    else:
        assert decode_vlq(field) == values


@pytest.mark.parametrize(
    "text",
    [
        "{",
        '{"version": 2, "sources": [], "mappings": ""}',
        '{"version": 3, "sections": []}',
        '{"version": 3, "sources": "a", "mappings": ""}',
        '{"version": 3, "sources": [], "mappings": "AA%A"}',
        '{"version": 3, "sources": [], "mappings": "AA"}',
    ],
)
def test_maps_we_cannot_read_are_refused(text: str) -> None:
    with pytest.raises(SourceMapError):
        SourceMap.parse(text)


def test_lookup_takes_the_segment_at_or_before_the_column() -> None:
    # Line 0: column 0 -> a.css 0:0, column 10 -> a.css 2:4; line 1 has no segment.
    mappings = f"AAAA,{_encode(10)}A{_encode(2)}{_encode(4)};"
    found = SourceMap.parse(f'{{"version":3,"sources":["a.css"],"mappings":"{mappings}"}}')
    assert found.original(0, 0) == ("a.css", 0, 0)
    assert found.original(0, 9) == ("a.css", 0, 0)
    assert found.original(0, 10) == ("a.css", 2, 4)
    assert found.original(0, 500) == ("a.css", 2, 4)
    assert found.original(1, 0) is None and found.original(7, 0) is None


def test_mapping_comments_and_inline_maps() -> None:
    assert mapping_url("a{}\n/*# sourceMappingURL=x.css.map */") == "x.css.map"
    assert mapping_url("a{}\n/*# sourceMappingURL=x.css.map */\na{}") is None  # not the last
    assert inline_map("data:application/json;base64,eyJ2ZXJzaW9uIjozfQ==") == '{"version":3}'
    assert inline_map("data:application/json;charset=utf-8,%7B%7D") == "{}"
    assert inline_map("data:text/plain;base64,e30=") is None
    assert inline_map("data:application/json;base64,%%%") is None


def test_sources_outside_the_root_are_not_named(tmp_path: Path) -> None:
    root = tmp_path / "project"
    (root / "src").mkdir(parents=True)
    (root / "build").mkdir()
    (root / "src" / "a.css").write_text("a{}")
    (tmp_path / "outside.css").write_text("a{}")
    (root / "src" / "link.css").symlink_to(tmp_path / "outside.css")
    map_file = root / "build" / "a.css.map"
    assert source_file("../src/a.css", map_file, root) == (root / "src" / "a.css").resolve()
    assert source_file("webpack://app/./src/a.css", map_file, root) == root / "src" / "a.css"
    assert source_file("../../outside.css", map_file, root) is None
    assert source_file("../src/link.css", map_file, root) is None
    assert source_file("../src/missing.css", map_file, root) is None
    assert source_file("https://example.com/a.css", map_file, root) is None


# ---------------------------------------------------------------- esbuild's maps
@pytest.fixture(scope="module")
def esbuilt(site: Path, tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, Path, Path]:
    """The Storybook's theme.css bundled and minified by esbuild, with its map beside it.

    Returns (project root, source file, built file) in a project laid out as a
    Storybook build with source maps would be.
    """
    esbuild = site / "node_modules" / ".bin" / "esbuild"
    if not esbuild.exists():
        pytest.skip("esbuild is not in the fixture Storybook's node_modules")
    root = tmp_path_factory.mktemp("mapped")
    (root / ".git").mkdir()
    (root / ".storybook").mkdir()
    source = root / ".storybook" / "theme.css"
    shutil.copy(site / ".storybook" / "theme.css", source)
    built = root / "storybook-static" / "assets" / "iframe.css"
    built.parent.mkdir(parents=True)
    subprocess.run(
        [str(esbuild), str(source), "--bundle", "--minify", "--sourcemap", f"--outfile={built}"],
        check=True,
        capture_output=True,
        timeout=60,
    )
    return root, source, built


def _declarations(css: str) -> list[tuple[str, int, int]]:
    """(name, line, column) of every declaration, 0-based, columns as UTF-16 (ASCII here)."""
    out = []
    for rule in tinycss2.parse_stylesheet(css, skip_whitespace=True, skip_comments=True):
        for node in tinycss2.parse_blocks_contents(rule.content, skip_whitespace=True):
            if node.type == "declaration":
                out.append((node.name, node.source_line - 1, node.source_column - 1))
    return out


def test_esbuild_map_leads_declarations_to_their_source_or_to_nothing(
    esbuilt: tuple[Path, Path, Path],
) -> None:
    """Each declaration esbuild maps exactly is named in the source; one it maps elsewhere
    (esbuild 0.28 maps the box shorthands it rewrites, ``margin:0``, ``padding:10px``, to
    line 1 column 1) is named in the served file, never on a wrong line of the source.
    Every colour, background and custom property maps exactly."""
    root, source, built = esbuilt
    text = built.read_text()
    assert mapping_url(text) == "iframe.css.map"
    found = SourceMap.parse((built.parent / "iframe.css.map").read_text())
    original = source.read_text().split("\n")
    files = ServedFiles(lambda url: built if url == "built" else None, root)
    generated = _declarations(text)
    exact = 0
    for name, line, column in generated:
        mapped = found.original(line, column)
        assert mapped is not None, name
        path, o_line, o_column = mapped
        assert source_file(path, built.parent / "iframe.css.map", root) == source.resolve()
        # esbuild adds -webkit-mask beside mask: its segment points at the mask it came from.
        holds = original[o_line][o_column:].startswith(name.removeprefix("-webkit-"))
        exact += holds
        place = files.place(_decl(name, "", "built", name, line, column))
        assert place is not None, name
        if holds and not name.startswith("-webkit-"):
            assert place.file == source.resolve() and place.line == o_line + 1, name
        elif not holds:
            assert place.file == built, name
        traced = name.startswith("--") or name in ("color", "background", "background-color")
        assert holds or not traced, name
    assert len(generated) > 20 and exact >= 0.8 * len(generated)


def _decl(prop: str, value: str, url: str, text: str, line: int, column: int) -> Declaration:
    place = ServedPlace(url, line=line, column=column, text=text)
    return Declaration(prop, prop, value, False, "rule", (1 << 30,), 0, place)


def test_a_served_declaration_is_named_in_its_source(esbuilt: tuple[Path, Path, Path]) -> None:
    root, source, built = esbuilt
    text = built.read_text()
    files = ServedFiles(lambda url: built if url == "built" else None, root)
    for name in ("--danger", "--icon", "color"):
        for match in re.finditer(rf"(?<![\w-]){name}:([^;}}]+)", text):
            at = match.start()
            place = files.place(_decl(name, match.group(1), "built", name, 0, at))
            assert place is not None and place.file == source.resolve(), name
            line = source.read_text().split("\n")[place.line - 1]
            assert line.strip().startswith(f"{name}:"), (name, line)
            assert place.span is not None
            assert place.span.text.strip() == match.group(1).strip() or name == "--chip"


def test_without_a_usable_map_the_served_file_is_named(
    esbuilt: tuple[Path, Path, Path], tmp_path: Path
) -> None:
    root, _, built = esbuilt
    text = built.read_text()
    at = text.rindex("--danger:")  # the dark theme's
    for variant, body in (
        ("missing", text.replace("iframe.css.map", "gone.css.map")),
        ("outside", text.replace("iframe.css.map", "../../../../outside.map")),
        ("none", text[: text.rindex("/*#")]),
    ):
        served = built.with_name(f"{variant}.css")
        served.write_text(body)
        files = ServedFiles(lambda url, s=served: s if url == "served" else None, root)
        place = files.place(_decl("--danger", "#6e1a1f", "served", "--danger", 0, at))
        assert place is not None and place.file == served and place.line == 1, variant
        assert place.span is not None and place.span.text == "#6e1a1f"


@pytest.mark.parametrize("route", ["devtools", "walk"])
def test_a_storybook_built_with_css_maps_is_named_in_its_sources(
    site: Path,
    esbuilt: tuple[Path, Path, Path],
    tmp_path: Path,
    route: str,
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """The fixture Storybook with its CSS asset replaced by esbuild's (same name, map beside):
    the failing alert's colour is named in ``.storybook/theme.css``, from devtools' ranges and
    from the probe's walk (Chromium without its devtools answer, as Firefox and WebKit)."""
    from alpha_audit.browser import LaunchOptions, engine_class
    from alpha_audit.browser.server import PageServer
    from alpha_audit.pages.capture import capture_page
    from alpha_audit.pages.declarations import paint_locations
    from alpha_audit.pages.sources import StorybookSource, targets
    from alpha_audit.pages.states import State

    if route == "walk":
        monkeypatch.setattr(engine_class("chromium"), "matched_styles", lambda self, e, p: None)
    _, source, built = esbuilt
    root = tmp_path / "project"
    (root / ".git").mkdir(parents=True)
    shutil.copytree(source.parent, root / ".storybook")
    shutil.copytree(site / "storybook-static", root / "storybook-static")
    shutil.copytree(site / "stories", root / "stories")
    (asset,) = (root / "storybook-static" / "assets").glob("iframe-*.css")
    asset.write_text(built.read_text().replace("iframe.css.map", f"{asset.name}.map"))
    # The map's sources are relative to it: ../../.storybook/theme.css from assets/, the
    # same in this project as where esbuild wrote it.
    shutil.copy(built.parent / "iframe.css.map", asset.parent / f"{asset.name}.map")
    target = next(t for t in targets([StorybookSource(root / "storybook-static")])
                  if t.name == "icons--alert")  # fmt: skip
    with (
        PageServer([root / "storybook-static"], root) as server,
        engine_class("chromium")(options=LaunchOptions(scale=1)) as browser,
    ):
        capture = capture_page(
            browser,
            server.url(0, target.path) + "&globals=theme:dark",
            State("dark", (), None),
            storybook=True,
            viewport=(400, 300),
            scale=1,
            selector=None,
            attribute="data-icon",
            max_icon_size=64,
        )
        files = ServedFiles(server.local_file, root)
    (icon,) = capture.icons
    places = paint_locations(icon, 0, target, files)
    lines = source.read_text().split("\n")
    named = {p.what: (p.file, lines[p.line - 1].strip()) for p in places if p.what != "story"}
    theme = (root / ".storybook" / "theme.css").resolve()
    assert named["css-colour"] == (theme, "--danger: #6e1a1f;")
    assert named["css-colour-use"] == (theme, "color: var(--danger);")
    assert named["css-backdrop"] == (theme, "--surface: #0d1117;")
