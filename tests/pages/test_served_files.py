"""From what an engine reports to a file and a line, without a browser: the hard cases."""

from __future__ import annotations

from pathlib import Path

import pytest

from alpha_audit.pages.cascade import Declaration, ServedPlace, Trace
from alpha_audit.pages.declarations import ServedFiles, story_line

LAST = (1 << 30,)


def _files(root: Path) -> ServedFiles:
    return ServedFiles(lambda url: (root / url).resolve() if url else None, root)


def _walked(prop: str, url: str, selector: str, rule: int, **more: object) -> Declaration:
    place = ServedPlace(url, rule=rule, selector=selector, **more)
    return Declaration(prop, prop, "", False, "rule", LAST, 0, place)


def _text_at(root: Path, file: str, line: int) -> str:
    return (root / file).read_text().split("\n")[line - 1].strip()


@pytest.fixture
def root(tmp_path: Path) -> Path:
    (tmp_path / ".git").mkdir()
    return tmp_path


def test_the_walks_rule_is_found_by_selector_as_the_cssom_writes_it(root: Path) -> None:
    (root / "a.css").write_text(
        ":-moz-only-here { color: red }\n"  # a rule Chromium drops: indices shift by one
        "html[data-theme=dark] {\n  --icon: #8b949e;\n}\n"
        ".card { .title { color: var(--icon) } }\n"
        ".x{color:red;color:blue}\n"
    )
    files = _files(root)
    # The CSSOM says html[data-theme="dark"], rule 0 (its first rule was dropped).
    place = files.place(_walked("--icon", "a.css", 'html[data-theme="dark"]', 0))
    assert place is not None and _text_at(root, "a.css", place.line) == "--icon: #8b949e;"
    assert place.span is not None and place.span.text == "#8b949e"
    nested = files.place(_walked("color", "a.css", "& .title", 2))
    assert nested is not None and nested.span is not None and nested.span.text == "var(--icon)"
    twice = files.place(_walked("color", "a.css", ".x", 3))  # the CSSOM keeps the later
    assert twice is not None and twice.span is not None and twice.span.text == "blue"
    assert files.place(_walked("color", "a.css", ".nowhere", 1)) is None


def test_a_style_element_is_found_in_a_crlf_page(root: Path) -> None:
    css = "\n  .a { color: #123456; }\n"
    (root / "p.html").write_bytes(
        f"<!doctype html>\r\n<style>{css.replace(chr(10), chr(13) + chr(10))}</style>".encode()
    )
    # The DOM's text has LF line ends (HTML parsing normalises them).
    place = _files(root).place(_walked("color", "p.html", ".a", 0, inline=True, sheet_text=css))
    assert place is not None and place.line == 3 and place.span is not None
    assert place.span.text == "#123456"


def test_script_written_styles_are_not_named(root: Path) -> None:
    (root / "p.html").write_text("<!doctype html><p>no style here</p>")
    files = _files(root)
    inline = _walked("color", "p.html", ".a", 0, inline=True, sheet_text=".a { color: red }")
    assert files.place(inline) is None
    constructed = _walked("color", "p.html", ".a", 0, inline=True)
    assert files.place(constructed) is None


def test_devtools_positions_must_hold_what_devtools_says(root: Path) -> None:
    (root / "a.css").write_text("a{}\n.b { color: red }\n")
    files = _files(root)

    def decl(line: int, column: int, text: str) -> Declaration:
        place = ServedPlace("a.css", line=line, column=column, text=text)
        return Declaration("color", "color", "red", False, "rule", LAST, 0, place)

    good = files.place(decl(1, 5, "color: red"))
    assert good is not None and (good.line, good.column) == (2, 6)
    assert files.place(decl(1, 4, "color: red")) is None  # one column off: not there
    assert files.place(decl(9, 0, "color: red")) is None


def test_files_outside_the_root_are_never_read(
    root: Path, tmp_path_factory: pytest.TempPathFactory
) -> None:
    outside = tmp_path_factory.mktemp("outside") / "a.css"
    outside.write_text(".a { color: red }")
    files = ServedFiles(lambda url: outside, root)
    assert files.place(_walked("color", "x", ".a", 0)) is None


def test_an_unmatched_walk_names_nothing(root: Path) -> None:
    """A trace whose plain chain ends in another colour than the engine computed is wrong."""
    (root / "a.css").write_text(":root { --c: #ff0000; }\n.a { color: var(--c) }\n")
    files = _files(root)
    hops = (
        Declaration("color", "color", "var(--c)", False, "rule", LAST, 0,
                    ServedPlace("a.css", rule=1, selector=".a")),
        Declaration("--c", "--c", "#ff0000", False, "rule", LAST, 0,
                    ServedPlace("a.css", rule=0, selector=":root")),
    )  # fmt: skip
    right = files.trace_locations(Trace("color", hops, "rgb(255, 0, 0)", True), "css-colour")
    assert [(p.what, p.line, p.custom_property) for p in right] == [
        ("css-colour", 1, "--c"),
        ("css-colour-use", 2, "--c"),
    ]
    assert files.trace_locations(Trace("color", hops, "rgb(0, 0, 255)", True), "css-colour") == []
    assert files.trace_locations(Trace("color", hops, None, False), "css-colour") == []


@pytest.mark.parametrize(
    ("text", "line"),
    [
        ("export default {};\n\nexport const Toolbar = {};\n", 3),
        ("export default {};\nexport function Toolbar() {}\n", 2),
        ("const Toolbar = {};\nexport { Other, Toolbar };\n", 2),
        ("export const ToolbarWide = {};\nexport const Toolbar = {};\n", 2),
        ("// no export of it\nconst Toolbar = 1;\n", 1),
    ],
)
def test_story_exports(root: Path, text: str, line: int) -> None:
    (root / "a.stories.ts").write_text(text)
    assert story_line(root / "a.stories.ts", "Toolbar", _files(root)) == line
