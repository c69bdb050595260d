"""Containment before reading, listing or globbing: symlinks can never leave the root."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from alpha_audit.errors import InputError
from alpha_audit.load.iconset import load_iconset
from alpha_audit.load.paths import PathRefused, contain, glob_contained

SVG = (
    '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 24 24"><rect width="4" height="4"/></svg>'
)


@pytest.fixture
def root(tmp_path: Path) -> Path:
    project = tmp_path / "project"
    (project / ".git").mkdir(parents=True)
    (project / "svg").mkdir()
    (project / "svg/a.svg").write_text(SVG)
    outside = tmp_path / "outside"
    outside.mkdir()
    (outside / "secret.svg").write_text(SVG)
    return project.resolve()


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("", "empty"),
        (".", "empty"),
        ("file:///etc/passwd", "is a URL"),
        ("https://example.com/a.svg", "is a URL"),
        ("/etc/passwd", "absolute"),
        ("C:\\x.svg", "absolute"),
        ("svg/\x1b[2J.svg", "control or format character"),
        ("svg/a\u202e.svg", "control or format character"),
        ("../outside/secret.svg", "outside the project root"),
    ],
)
def test_refused_paths(root: Path, text: str, message: str) -> None:
    with pytest.raises(PathRefused, match=message) as info:
        contain(root, root, text)
    assert "\n" not in str(info.value) and "\x1b" not in str(info.value)


def test_symlink_leaving_the_root_is_refused(root: Path) -> None:
    os.symlink(root.parent / "outside/secret.svg", root / "svg/link.svg")
    with pytest.raises(PathRefused, match="outside the project root"):
        contain(root, root, "svg/link.svg")
    with pytest.raises(PathRefused, match="outside the project root"):
        glob_contained(root, root, "svg/*.svg", limit=10)


def test_symlink_loop_is_a_clean_refusal(root: Path) -> None:
    os.symlink(root / "svg/loop2.svg", root / "svg/loop1.svg")
    os.symlink(root / "svg/loop1.svg", root / "svg/loop2.svg")
    with pytest.raises(PathRefused, match=r"symlink loop|outside|cannot be resolved"):
        contain(root, root, "svg/loop1.svg")


def test_globs_never_enter_symlinked_directories(root: Path) -> None:
    os.symlink("/", root / "up")
    assert glob_contained(root, root, "up/**/*.svg", limit=10) == []
    assert glob_contained(root, root, "up/*", limit=10) == []
    assert glob_contained(root, root, "**/*.svg", limit=10) == [root / "svg/a.svg"]


def test_glob_limits(root: Path) -> None:
    for k in range(5):
        (root / f"svg/x{k}.svg").write_text(SVG)
    with pytest.raises(PathRefused, match="more than 3 files"):
        glob_contained(root, root, "svg/*.svg", limit=3)
    with pytest.raises(PathRefused, match="ends in"):
        glob_contained(root, root, "svg/**", limit=3)


def test_manifest_errors_name_the_file(root: Path) -> None:
    manifest = root / "iconset.yaml"
    manifest.write_text("icons:\n  - {file: 'file:///etc/passwd'}\ncolor: red\n")
    with pytest.raises(InputError, match=r"iconset\.yaml.*is a URL"):
        load_iconset(manifest)
    manifest.write_text("icons: ''\ncolor: red\n")
    with pytest.raises(InputError, match=r"iconset\.yaml.*empty"):
        load_iconset(manifest)


def test_theme_and_manifest_symlinks_leaving_the_root_are_refused_before_reading(
    root: Path,
) -> None:
    from alpha_audit.load.theme import load_theme

    secret = root.parent / "outside/theme.yaml"
    secret.write_text("name: secret\ncanvases:\n  - {name: a, color: '#ffffff'}\n")
    os.symlink(secret, root / "theme.yaml")
    with pytest.raises(InputError, match="symlink to a file outside the project root") as info:
        load_theme(root / "theme.yaml")
    assert "secret" not in str(info.value).replace("outside/theme.yaml", "")
    os.symlink(secret, root / "iconset.yaml")
    with pytest.raises(InputError, match="outside the project root"):
        load_iconset(root / "iconset.yaml")


def test_config_symlink_to_a_system_file_is_refused(root: Path) -> None:
    from alpha_audit.load.config import load_config

    os.symlink("/etc/passwd", root / "alpha-audit.yaml")
    with pytest.raises(InputError, match="outside the project root") as info:
        load_config(root / "alpha-audit.yaml")
    assert "root:" not in str(info.value)  # not a line of /etc/passwd


def test_config_discovery_does_not_climb_above_a_folder_without_git(tmp_path: Path) -> None:
    from alpha_audit.load.config import find_config

    (tmp_path / "alpha-audit.yaml").write_text("fail-on: [loss]\n")  # e.g. in /tmp or $HOME
    project = tmp_path / "tarball"
    project.mkdir()
    assert find_config(project) is None
    (tmp_path / ".git").mkdir()  # inside a repository the root's config is found
    assert find_config(project) == tmp_path / "alpha-audit.yaml"


def test_a_symlinked_manifest_keeps_its_own_folder_as_base(root: Path) -> None:
    (root / "sets").mkdir()
    (root / "sets/svg").mkdir()
    (root / "sets/svg/b.svg").write_text(SVG)
    (root / "real.yaml").write_text("icons: svg/*.svg\ncolor: red\n")
    os.symlink(root / "real.yaml", root / "sets/iconset.yaml")
    icons = load_iconset(root / "sets/iconset.yaml")
    assert [i.file for i in icons.icons] == [root / "sets/svg/b.svg"]


def test_glob_refuses_control_characters_in_folders_on_the_way(root: Path) -> None:
    (root / "svg/\x1b]52;c;x\x07").mkdir()
    (root / "svg/\x1b]52;c;x\x07/e.svg").write_text(SVG)
    with pytest.raises(PathRefused, match="control or format character") as info:
        glob_contained(root, root, "svg/*/*.svg", limit=10)
    assert "\x1b" not in str(info.value)


def test_a_name_outside_the_root_is_said_to_be_outside_not_a_symlink(root: Path) -> None:
    """``render ../sb`` from a project: no link is involved, and the message says so."""
    from alpha_audit.load.paths import contain_argument

    (root.parent / "sb").mkdir()
    with pytest.raises(PathRefused, match="is outside the project root") as info:
        contain_argument(root / ".." / "sb", root)
    assert "symlink" not in str(info.value)
    os.symlink(root.parent / "sb", root / "linked")
    with pytest.raises(PathRefused, match="leads through a symlink"):
        contain_argument(root / "linked", root)


def test_a_glob_over_folders_nested_deeper_than_pythons_stack_finds_the_file(
    root: Path,
) -> None:
    """Depth is bounded by the entries a glob visits, never by recursion: 1,500 folders
    deep (Python's recursion limit is 1,000) the icon at the bottom is found, in order."""
    import sys

    depth = 1500
    assert depth > sys.getrecursionlimit()
    deep = root / "deep"
    deep.mkdir()
    fd = os.open(deep, os.O_RDONLY)
    try:  # one folder at a time, relative to the last: no path is ever long
        for _ in range(depth):
            os.mkdir("d", dir_fd=fd)
            child = os.open("d", os.O_RDONLY, dir_fd=fd)
            os.close(fd)
            fd = child
        os.close(os.open("x.svg", os.O_CREAT | os.O_WRONLY, dir_fd=fd))
    finally:
        os.close(fd)
    (deep / "a.svg").write_text("<svg/>")
    try:
        found = glob_contained(root, deep, "**/*.svg", limit=10)
        assert [p.name for p in found] == ["a.svg", "x.svg"]
        assert len(found[1].relative_to(deep).parts) == depth + 1
    finally:
        _remove_deep(deep)


def _remove_deep(deep: Path) -> None:
    """Remove the chain of ``d`` folders bottom-up by descriptor (shutil.rmtree recurses)."""
    fds = [os.open(deep, os.O_RDONLY)]
    while True:
        try:
            fds.append(os.open("d", os.O_RDONLY, dir_fd=fds[-1]))
        except FileNotFoundError:
            break
    os.unlink("x.svg", dir_fd=fds[-1])
    for parent, child in zip(fds[-2::-1], fds[:0:-1], strict=True):
        os.close(child)
        os.rmdir("d", dir_fd=parent)
    os.close(fds[0])
