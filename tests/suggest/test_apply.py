"""``suggest --apply``: only the alpha values change, everything else byte for byte."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest
from typer.testing import CliRunner

from alpha_audit.cli import app
from alpha_audit.errors import InputError
from alpha_audit.load.iconset import load_iconset
from alpha_audit.suggest.apply import apply_alpha, format_alpha, set_alpha

MANIFEST = """\
# Demo icons -- keep this comment
name: Demo
icons:
  - a.svg
  - {file: b.svg, alpha: 1.05}   # explicit
  - file: c.svg
    alpha: "1.3"
palette: {orange: "#ee7733", blue: "#0077bb"}
color: cycle
alpha:   1.1    # default
overrides:
  a: {color: blue, alpha: 1.2}
"""


def test_only_alpha_values_change() -> None:
    edited = set_alpha(MANIFEST, "1.226")
    # A comment after a value keeps its column: the longer value takes the gap's spaces.
    expected = (
        MANIFEST.replace("alpha: 1.05}   #", "alpha: 1.226}  #")
        .replace('alpha: "1.3"', "alpha: 1.226")
        .replace("alpha:   1.1    #", "alpha:   1.226  #")
        .replace("alpha: 1.2}", "alpha: 1.226}")
    )
    assert edited == expected


def test_missing_top_level_alpha_is_added_at_the_end() -> None:
    text = "name: x\nicons: svg/*.svg\ncolor: '#000000'  # no newline at end"
    assert set_alpha(text, "1.5") == text + "\nalpha: 1.5\n"


@pytest.mark.parametrize(("alpha", "precision", "text"), [(1.226, 3, "1.226"), (2.0, 3, "2.0")])
def test_format_alpha(alpha: float, precision: int, text: str) -> None:
    assert format_alpha(alpha, precision) == text


def test_apply_writes_and_reloads(tmp_path: Path) -> None:
    (tmp_path / "svg").mkdir()
    for name in "abc":
        (tmp_path / "svg" / f"{name}.svg").write_text("<svg/>")
    path = tmp_path / "iconset.yaml"
    path.write_bytes(b"# crlf\r\nname: x\r\nicons: svg/*.svg\r\ncolor: '#ee7733'\r\nalpha: 1.1\r\n")
    assert apply_alpha(path, 1.25, 3)
    assert path.read_bytes() == (
        b"# crlf\r\nname: x\r\nicons: svg/*.svg\r\ncolor: '#ee7733'\r\nalpha: 1.25\r\n"
    )
    assert {i.alpha for i in load_iconset(path, root=tmp_path).icons} == {1.25}
    assert not apply_alpha(path, 1.25, 3)


def test_unparseable_manifest_is_an_input_error() -> None:
    with pytest.raises(InputError, match="cannot edit"):
        set_alpha("- just\n- a list\n", "1.2")


def test_cli_apply_and_no_write_without_it(tmp_path: Path, repo: Path) -> None:
    example = repo / "examples" / "vibrant"
    target = tmp_path / "vibrant"
    target.mkdir()
    shutil.copytree(example / "svg", target / "svg")
    original = (example / "iconset.yaml").read_text()
    (target / "iconset.yaml").write_text(original)
    (tmp_path / ".git").mkdir()
    theme = str(repo / "themes" / "paper16.yaml")
    runner = CliRunner()
    res = runner.invoke(app, ["suggest", theme, str(target / "iconset.yaml"), "-f", "json"])
    assert res.exit_code == 0, res.output
    assert (target / "iconset.yaml").read_text() == original
    doc = json.loads(res.stdout)
    assert doc["schema"] == "alpha-audit.suggest/3" and doc["alpha"] == 1.193
    # The default policy holds confusion: orange and magenta (roles) blur on white first.
    assert doc["limited_by"]["rule"] == "confusion" and doc["limited_by"]["canvas"] == "white"
    assert doc["limited_by"]["grid"] == 1e-3  # bracketed, and said so
    assert len(doc["per_color"]) == 7 and len(doc["per_icon"]) == 12
    for fmt in ("table", "markdown"):
        res = runner.invoke(app, ["suggest", theme, str(target / "iconset.yaml"), "-f", fmt])
        assert res.exit_code == 0 and "1.193" in res.stdout
    res = runner.invoke(app, ["suggest", theme, str(target / "iconset.yaml"), "--apply", "set"])
    assert res.exit_code == 0, res.output
    edited = (target / "iconset.yaml").read_text()
    # The explicit `alert: {alpha: 1.18}` is kept; the comment stays in its column.
    assert edited == original.replace("alpha: 1.1   ", "alpha: 1.193 ")
    assert "kept the explicit alpha of 1 icon (alert)" in res.stderr


# --- robustness: the edited file means the same document with new alpha values ---------------


def test_line_endings_are_kept_as_they_are(tmp_path: Path) -> None:
    mixed = "name: x\r\nicons: [a.svg]\nalpha: 1.1\r\n"
    path = tmp_path / "m.yaml"
    path.write_bytes(mixed.encode())
    assert apply_alpha(path, 1.25, 3, root=tmp_path)
    assert path.read_bytes() == b"name: x\r\nicons: [a.svg]\nalpha: 1.25\r\n"


def test_an_appended_default_uses_the_files_line_ending() -> None:
    assert set_alpha("name: x\r\nicons: [a.svg]\r\n", "1.2") == (
        "name: x\r\nicons: [a.svg]\r\nalpha: 1.2\r\n"
    )


@pytest.mark.parametrize("mode", [0o600, 0o444, 0o640])
def test_the_file_mode_is_kept(tmp_path: Path, mode: int) -> None:
    path = tmp_path / "m.yaml"
    path.write_text("name: x\nicons: [a.svg]\nalpha: 1.1\n")
    path.chmod(mode)
    assert apply_alpha(path, 1.3, 3, root=tmp_path)
    assert path.stat().st_mode & 0o777 == mode
    assert "alpha: 1.3" in path.read_text()


def test_a_link_inside_the_project_edits_its_target_and_stays_a_link(tmp_path: Path) -> None:
    real = tmp_path / "real.yaml"
    real.write_text("name: x\nicons: [a.svg]\nalpha: 1.1\n")
    link = tmp_path / "iconset.yaml"
    link.symlink_to(real)
    assert apply_alpha(link, 1.3, 3, root=tmp_path)
    assert link.is_symlink() and "alpha: 1.3" in real.read_text()


def test_a_link_leaving_the_project_is_refused(tmp_path: Path) -> None:
    outside, project = tmp_path / "outside.yaml", tmp_path / "project"
    project.mkdir()
    outside.write_text("name: x\nicons: [a.svg]\nalpha: 1.1\n")
    (project / "iconset.yaml").symlink_to(outside)
    with pytest.raises(InputError, match="outside the project"):
        apply_alpha(project / "iconset.yaml", 1.3, 3, root=project)
    assert outside.read_text().endswith("alpha: 1.1\n")


@pytest.mark.parametrize(
    ("text", "words"),
    [
        ("name: x\nicons: [a.svg]\nalpha: &a 1.1\nother: *a\n", "anchor"),
        ("{name: x, icons: [a.svg]}\n", "not be valid YAML"),  # appended line breaks flow style
        ("name: x\nicons: [a.svg]\n...\n", "valid YAML"),  # after the end marker
        ("name: x\nicons: [a.svg]\nalpha: 1.1\nalpha: 1.3\n", "more than the alpha"),
        ("  name: x\n  icons: [a.svg]\n", "valid YAML"),  # indented top level
    ],
)
def test_edits_that_would_change_meaning_are_refused(text: str, words: str) -> None:
    with pytest.raises(InputError, match=words) as err:
        set_alpha(text, "1.2")
    assert "\n" not in str(err.value)  # one line


@pytest.mark.parametrize("kind", ["loop", "dangling"])
def test_a_broken_link_is_an_input_error(tmp_path: Path, kind: str) -> None:
    link = tmp_path / "iconset.yaml"
    link.symlink_to(link if kind == "loop" else tmp_path / "nowhere.yaml")
    with pytest.raises(InputError, match="leads to no file"):
        apply_alpha(link, 1.3, 3, root=tmp_path)
