"""Themes and manifests: valid files load, each kind of bad input gives one clear error."""

from __future__ import annotations

from pathlib import Path

import pytest

from alpha_audit import InputError, load_iconset, load_theme

SVG = (
    '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 24 24" fill="none" '
    'stroke="currentColor" stroke-width="2"><path d="M4 12h16"/></svg>'
)


def write(folder: Path, name: str, text: str) -> Path:
    path = folder / name
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text)
    return path


@pytest.fixture
def project(tmp_path: Path) -> Path:
    (tmp_path / ".git").mkdir()
    for name in ("alert", "bell", "check"):
        write(tmp_path, f"icons/svg/{name}.svg", SVG)
    return tmp_path


def test_theme_loads_with_modes_inferred(tmp_path: Path) -> None:
    path = write(
        tmp_path,
        "t.yaml",
        'name: T\ncanvases:\n  - {name: a, color: "#ffffff"}\n  - {name: b, color: "#0d1117"}\n',
    )
    theme = load_theme(path)
    assert [c.mode for c in theme.canvases] == ["light", "dark"]
    assert theme.threshold == 3.0
    assert theme.canvases[1].line == 4


def test_bundled_themes_load(repo: Path) -> None:
    paper = load_theme(repo / "themes/paper16.yaml")
    assert len(paper.canvases) == 16
    assert sorted(c.mode for c in paper.canvases).count("light") == 8
    assert {"#000000", "#ffffff"} <= {c.color for c in paper.canvases}
    for path in (repo / "themes").glob("*.yaml"):
        load_theme(path)


THEME_ERRORS = [
    ("canvases: []\n", r"t\.yaml:1: canvases: expected a non-empty list"),
    ("canvases:\n  - {name: a, color: #fff}\n", r"unquoted #hex starts a YAML comment"),
    (
        "canvases:\n  - {name: a, color: blurple}\n",
        r":2: canvases\[0\]\.color: 'blurple' is not a colour",
    ),
    (
        "canvases:\n  - {name: a, color: '#fff', mode: dim}\n",
        r"'dim' is not a mode; use light or dark",
    ),
    ("canvases:\n  - {name: a, colour: '#fff'}\n", r"unknown key 'colour'; did you mean 'color'\?"),
    (
        "canvases:\n  - {name: a, color: '#fff'}\n  - {name: a, color: '#000'}\n",
        r":3: canvases\[1\]\.name: duplicate canvas name 'a'",
    ),
    ("threshold: .nan\ncanvases:\n  - {color: '#fff'}\n", r"threshold: nan is out of range"),
    ("threshold: '3'\ncanvases:\n  - {color: '#fff'}\n", r"threshold: expected a contrast ratio"),
    ("threshold: yes\ncanvases:\n  - {color: '#fff'}\n", r"got True \(a boolean\)"),
    ("name: a\nname: b\ncanvases: []\n", r":2: name: duplicate key 'name' \(first set on line 1\)"),
    ("canvases: [\n", r"invalid YAML"),
    ("- 1\n- 2\n", r"expected a theme \(a mapping of keys\)"),
    ("canvases:\n  - {color: '#ffffff80'}\n", r"carries its own alpha"),
]


@pytest.mark.parametrize(("text", "message"), THEME_ERRORS)
def test_theme_errors(tmp_path: Path, text: str, message: str) -> None:
    path = write(tmp_path, "t.yaml", text)
    with pytest.raises(InputError, match=message) as info:
        load_theme(path)
    assert "\n" not in str(info.value)
    assert str(path) in str(info.value)


def test_missing_and_binary_theme_files(tmp_path: Path) -> None:
    with pytest.raises(InputError, match="file not found"):
        load_theme(tmp_path / "nope.yaml")
    (tmp_path / "bin.yaml").write_bytes(b"\xff\xfe\x00garbage")
    with pytest.raises(InputError, match="not UTF-8"):
        load_theme(tmp_path / "bin.yaml")


def test_alias_bomb_is_refused(tmp_path: Path) -> None:
    lines = ["a0: &a0 [x, x, x, x, x, x, x, x, x, x]"]
    lines += [f"a{i}: &a{i} [{', '.join([f'*a{i - 1}'] * 10)}]" for i in range(1, 8)]
    path = write(tmp_path, "bomb.yaml", "\n".join(lines) + "\ncanvases: []\n")
    with pytest.raises(InputError, match="alias bomb"):
        load_theme(path)


def test_yaml12_floats_are_numbers(tmp_path: Path) -> None:
    path = write(tmp_path, "t.yaml", "threshold: 4.5e0\ncanvases:\n  - {color: '#fff'}\n")
    assert load_theme(path).threshold == 4.5


def test_manifest_glob_cycle_and_overrides(project: Path) -> None:
    path = write(
        project,
        "icons/iconset.yaml",
        "name: Demo\nicons: svg/*.svg\npalette: {orange: '#ee7733', blue: '#0077bb'}\n"
        "color: cycle\nalpha: 1.1\nsizes: [24, 16]\noverrides:\n  check: {alpha: 1.3}\n",
    )
    icons = load_iconset(path)
    assert [i.name for i in icons.icons] == ["alert", "bell", "check"]
    assert [i.color_name for i in icons.icons] == ["orange", "blue", "orange"]
    assert [i.alpha for i in icons.icons] == [1.1, 1.1, 1.3]
    assert icons.sizes == (16, 24)
    assert icons.icons[2].alpha_line == 8
    assert icons.root == project.resolve()


def test_manifest_list_form_explicit_entries_win(project: Path) -> None:
    path = write(
        project,
        "icons/iconset.yaml",
        "icons:\n  - svg/alert.svg\n"
        "  - {file: svg/bell.svg, name: ring, color: '#123456', alpha: 2}\n"
        "color: '#ee7733'\nalpha: 1.2\n",
    )
    icons = load_iconset(path).icons
    assert [(i.name, i.color, i.alpha) for i in icons] == [
        ("alert", "#ee7733", 1.2),
        ("ring", "#123456", 2.0),
    ]
    assert icons[1].color_line == 3


MANIFEST_ERRORS = [
    ("icons: svg/*.png\ncolor: red\n", r"icons: 'svg/\*\.png' matches no files"),
    ("icons: ../*.svg\ncolor: red\n", r"leaves the manifest's folder"),
    ("icons: [/etc/passwd]\ncolor: red\n", r"icons\[0\]: '/etc/passwd' is absolute"),
    ("icons: ['../../outside.svg']\ncolor: red\n", r"resolves outside the project root"),
    ("icons: svg/*.svg\ncolor: cycle\n", r"color: cycle needs a non-empty palette"),
    ("icons: svg/*.svg\ncolor: red\nalpha: .inf\n", r"alpha: inf is out of range"),
    ("icons: svg/*.svg\ncolor: red\nalpha: fast\n", r"alpha: expected a finite coefficient"),
    ("icons: svg/*.svg\ncolor: red\nsizes: [0]\n", r"sizes\[0\]: 0 \(a number\) is not a size"),
    (
        "icons: svg/*.svg\ncolor: red\noverrides: {alrt: {alpha: 2}}\n",
        r"no icon named 'alrt'; did you mean 'alert'\?",
    ),
    (
        "icons: svg/*.svg\npalette: {o: '#ee7733'}\ncolor: purple-ish\n",
        r"neither a palette name \(o\) nor a colour",
    ),
    ("icons: svg/*.svg\ncolor: red\nicon_size: 3\n", r"unknown key 'icon_size'"),
    (
        "icons: [svg/alert.svg, {file: svg/bell.svg, name: alert}]\ncolor: red\n",
        r"duplicate icon name 'alert'",
    ),
    ("icons: svg/*.svg\ncolor:\n", r"quote it"),
    ("icons: svg/*.svg\n", r"icon 'alert' has no colour"),
    (
        "icons: [svg/alert.svg, svg/nope.svg]\ncolor: red\n",
        r"icons\[1\]: 'svg/nope.svg' does not exist",
    ),
    (
        "icons: [{file: svg/nope.svg}]\ncolor: red\n",
        r"icons\[0\]\.file: 'svg/nope.svg' does not exist",
    ),
    ("icons: [svg]\ncolor: red\n", r"icons\[0\]: 'svg' is a folder, not a file"),
    ("icons: svg/*.svg\ncolor: red\noverrides: [a]\n", r"overrides"),
]


@pytest.mark.parametrize(("text", "message"), MANIFEST_ERRORS)
def test_manifest_errors(project: Path, text: str, message: str) -> None:
    path = write(project, "icons/iconset.yaml", text)
    with pytest.raises(InputError, match=message) as info:
        load_iconset(path)
    assert "\n" not in str(info.value) and "iconset.yaml" in str(info.value)


def test_file_names_with_terminal_escapes_are_refused(project: Path) -> None:
    write(project, "icons/svg/\x1b[2Jwipe.svg", SVG)
    path = write(project, "icons/iconset.yaml", "icons: svg/*.svg\ncolor: red\n")
    with pytest.raises(InputError, match="control or format character"):
        load_iconset(path)


def test_no_manifest_colour_when_every_icon_has_one(project: Path) -> None:
    path = write(
        project,
        "icons/iconset.yaml",
        "icons:\n"
        "  - {file: svg/alert.svg, color: '#ee7733'}\n"
        "  - {file: svg/bell.svg, color: red}\n",
    )
    assert [i.color for i in load_iconset(path).icons] == ["#ee7733", "#ff0000"]


def test_symlink_escaping_the_root_is_refused(
    project: Path, tmp_path_factory: pytest.TempPathFactory
) -> None:
    outside = tmp_path_factory.mktemp("outside") / "evil.svg"
    outside.write_text(SVG)
    (project / "icons/svg/evil.svg").symlink_to(outside)
    path = write(project, "icons/iconset.yaml", "icons: svg/*.svg\ncolor: red\n")
    with pytest.raises(InputError, match="outside the project root"):
        load_iconset(path)


def test_bundled_example_manifest(repo: Path) -> None:
    icons = load_iconset(repo / "examples/vibrant/iconset.yaml")
    assert len(icons.icons) == 12
    assert set(icons.palette.values()) == {
        "#ee7733",
        "#0077bb",
        "#33bbee",
        "#ee3377",
        "#cc3311",
        "#009988",
        "#bbbbbb",
    }


@pytest.mark.parametrize("empty", ["overrides:\n", "overrides: ~\n", "overrides:  # none yet\n"])
def test_empty_overrides_means_none(project: Path, empty: str) -> None:
    path = write(
        project, "icons/iconset.yaml", "icons: svg/*.svg\ncolor: red\nalpha: 1.1\n" + empty
    )
    assert {(i.color, i.alpha) for i in load_iconset(path).icons} == {("#ff0000", 1.1)}


def test_a_glob_may_name_icons_by_path_to_keep_variants_apart(tmp_path: Path) -> None:
    (tmp_path / ".git").mkdir()
    svg = '<svg xmlns="http://www.w3.org/2000/svg"/>'
    for style in ("filled", "outline"):
        write(tmp_path / "icons" / style, "x.svg", svg)
    write(tmp_path / "icons" / "filled", "y.svg", svg)
    by_stem = write(tmp_path / "icons", "stem.yaml", 'icons: "**/*.svg"\ncolor: red\n')
    with pytest.raises(InputError, match=r"duplicate icon name 'x'.*name: path"):
        load_iconset(by_stem)
    by_path = write(
        tmp_path / "icons",
        "path.yaml",
        'icons: {glob: "**/*.svg", name: path}\ncolor: red\noverrides: {outline/x: {alpha: 1.2}}\n',
    )
    icons = {i.name: i for i in load_iconset(by_path).icons}
    assert set(icons) == {"filled/x", "filled/y", "outline/x"}
    assert icons["outline/x"].alpha == 1.2 and icons["filled/x"].alpha == 1.0
    assert icons["outline/x"].file == (tmp_path / "icons" / "outline" / "x.svg").resolve()
    bad = write(
        tmp_path / "icons", "bad.yaml", 'icons: {glob: "**/*.svg", name: file}\ncolor: red\n'
    )
    with pytest.raises(InputError, match=r"icons\.name: expected one of stem, path"):
        load_iconset(bad)
