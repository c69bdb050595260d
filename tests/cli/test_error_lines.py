"""Error lines name files relative to the project, however the file was found, and say
plainly what an empty path or a count of one means."""

from __future__ import annotations

from pathlib import Path

import pytest
from typer.testing import CliRunner

from alpha_audit.cli import app
from alpha_audit.errors import InputError
from alpha_audit.rows import check_combinations

runner = CliRunner()
BROKEN_THEME = "name: t\ncanvases: {}\n"
SET = "name: s\nicons: ['a.svg']\ncolor: '#333333'\n"
SVG = '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 4 4"><rect width="4" height="4"/></svg>'


@pytest.fixture
def project(tmp_path: Path) -> Path:
    """A project whose theme is broken, with a config naming it and a subfolder."""
    root = tmp_path / "design"
    (root / ".git").mkdir(parents=True)
    (root / "themes").mkdir()
    (root / "themes" / "t.yaml").write_text(BROKEN_THEME)
    (root / "s.yaml").write_text(SET)
    (root / "a.svg").write_text(SVG)
    (root / "sub").mkdir()
    return root


def _error(args: list[str]) -> str:
    result = runner.invoke(app, args)
    assert result.exit_code == 2, result.output
    (line,) = [line for line in result.stderr.splitlines() if "error:" in line]
    return line


@pytest.mark.parametrize(
    ("where", "how"),
    [(".", "config"), ("sub", "config given"), ("sub", "arguments"), (".", "absolute arguments")],
)
def test_a_file_is_named_relative_to_the_project(project, monkeypatch, where, how):
    (project / "alpha-audit.yaml").write_text("theme: themes/t.yaml\niconset: s.yaml\n")
    monkeypatch.chdir(project / where)
    up = "" if where == "." else "../"
    args = {
        "config": ["check"],
        "config given": ["check", "--config", str(project / "alpha-audit.yaml")],
        "arguments": ["check", f"{up}themes/t.yaml", f"{up}s.yaml"],
        "absolute arguments": ["check", str(project / "themes/t.yaml"), str(project / "s.yaml")],
    }[how]
    line = _error(args)
    assert line.startswith("alpha-audit: error: themes/t.yaml:2: canvases: "), line
    assert str(project) not in line


def test_a_file_outside_the_project_keeps_its_name(project, tmp_path, monkeypatch):
    outside = tmp_path / "elsewhere.yaml"
    outside.write_text(BROKEN_THEME)
    monkeypatch.chdir(project)
    line = _error(["check", str(outside), "s.yaml"])
    assert f"error: {outside}:2: canvases" in line


@pytest.mark.parametrize("option", ["--baseline", "--config", "-o"])
def test_an_empty_path_is_a_usage_error_naming_the_option(project, monkeypatch, option):
    monkeypatch.chdir(project)
    line = _error(["check", "themes/t.yaml", "s.yaml", "-f", "json", option, ""])
    assert "an empty path; give a file name" in line and option in line, line
    assert "is a directory" not in line


@pytest.mark.parametrize(
    ("rows", "canvases", "sizes", "said"),
    [
        (1, 1, 1, "1 paint x 1 canvas x 1 size is more than"),
        (2, 3, 1, "2 paints x 3 canvases x 1 size is more than"),
        (1_200, 1, 4, "1,200 paints x 1 canvas x 4 sizes is more than"),
    ],
)
def test_the_combinations_bound_counts_in_words_that_read_right(rows, canvases, sizes, said):
    with pytest.raises(InputError, match=said):
        check_combinations(rows, canvases, sizes, limit=0)
