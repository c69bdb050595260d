"""Degenerate results: every renderer reports, and a gate over nothing does not pass."""

from __future__ import annotations

import os
from pathlib import Path

import pytest
from typer.testing import CliRunner

from alpha_audit.cli import app
from alpha_audit.gate import VACUOUS, evaluate
from alpha_audit.model import Canvas, Icon, IconProblem, IconSet, Theme
from alpha_audit.policy import Policy
from alpha_audit.rows import audit
from helpers import solid_paints

FORMATS = ["table", "json", "markdown", "github", "sarif", "junit"]
THEME = "name: t\ncanvases:\n  - {name: paper, color: '#ffffff'}\n"


def test_gate_over_zero_audited_icons_fails_and_says_why() -> None:
    theme = Theme("t", (Canvas("paper", "#ffffff"),))
    icons = IconSet("s", (Icon("a", Path("a.svg"), "#ee7733", 1.1),))
    result = audit(theme, icons, solid_paints(icons, (IconProblem("a", Path("a.svg"), "broken"),)))
    gate = evaluate([result], Policy())
    assert gate.failures == () and not gate.passed and gate.vacuous
    assert gate.counts() == {VACUOUS: 1}
    assert evaluate([audit(theme, icons)], Policy()).vacuous is False


@pytest.fixture
def broken_project(tmp_path: Path) -> Path:
    (tmp_path / ".git").mkdir()
    (tmp_path / "svg").mkdir()
    (tmp_path / "svg/a.svg").write_text("not svg")
    (tmp_path / "svg/b.svg").write_text('<svg xmlns="http://www.w3.org/2000/svg"/>')
    (tmp_path / "theme.yaml").write_text(THEME)
    (tmp_path / "iconset.yaml").write_text("name: s\nicons: svg/*.svg\ncolor: '#ee7733'\n")
    return tmp_path


@pytest.mark.parametrize("fmt", FORMATS)
def test_every_icon_unrenderable_is_a_report_and_a_failed_gate(
    broken_project: Path, fmt: str
) -> None:
    cwd = os.getcwd()
    os.chdir(broken_project)
    try:
        result = CliRunner().invoke(app, ["check", "theme.yaml", "iconset.yaml", "-f", fmt])
    finally:
        os.chdir(cwd)
    assert result.exit_code == 1, result.output
    assert ("Traceback" not in result.output and result.exception is None) or isinstance(
        result.exception, SystemExit
    )
    assert "nothing audited" in result.output
