"""Names from input files are shown literally: rich markup in them never crashes a report."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest
from typer.testing import CliRunner

from alpha_audit.cli import app

runner = CliRunner()


@pytest.fixture
def evil(tmp_path: Path, repo: Path) -> tuple[str, str]:
    (tmp_path / ".git").mkdir()
    svg = tmp_path / "svg"
    svg.mkdir()
    for name in ("[bold]x", "[red]y"):
        shutil.copy(repo / "examples/vibrant/svg/check.svg", svg / f"{name}.svg")
    theme = tmp_path / "theme.yaml"
    theme.write_text(
        'name: "[/evil]"\ncanvases:\n'
        '  - {name: "[/bold]", color: "#ffffff"}\n  - {name: "[red]x", color: "#000000"}\n'
    )
    manifest = tmp_path / "iconset.yaml"
    manifest.write_text(
        'name: "[/i]"\nicons: svg/*.svg\npalette: {"[/p]": "#ee7733", q: "#ee3377"}\nalpha: 1.4\n'
    )
    return str(theme), str(manifest)


@pytest.mark.parametrize("fmt", ["table", "json", "junit", "sarif", "markdown", "github"])
def test_check_reports_markup_names_literally(evil: tuple[str, str], fmt: str) -> None:
    result = runner.invoke(app, ["check", *evil, "-f", fmt])
    assert result.exit_code == 1, result.output  # the orange/magenta collision fails the gate
    assert result.exception is None or isinstance(result.exception, SystemExit)
    if fmt == "table":
        assert "[/bold]" in result.stdout and "[bold]x" in result.stdout


def test_suggest_and_reproduce_show_markup_names_literally(evil: tuple[str, str]) -> None:
    suggested = runner.invoke(app, ["suggest", *evil])
    assert suggested.exit_code == 0, suggested.output
    assert "[/bold]" in suggested.stdout and "[/i]" in suggested.stdout
    reproduced = runner.invoke(
        app, ["reproduce", "--quick", "--only", "palette", "--theme", evil[0]]
    )
    assert reproduced.exit_code == 0, reproduced.output
