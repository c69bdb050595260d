"""Commands and the config's tokens: table: --gamut everywhere, suggest says it reads YAML."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest
from typer.testing import CliRunner

from alpha_audit.cli import ExitStatus, app

REPO = Path(__file__).resolve().parents[2]
runner = CliRunner()


@pytest.fixture
def project(tmp_path, monkeypatch) -> Path:
    shutil.copytree(REPO / "examples/tokens", tmp_path / "p")
    (tmp_path / "p" / ".git").mkdir()
    monkeypatch.chdir(tmp_path / "p")
    return tmp_path / "p"


def test_suggest_on_a_tokens_config_says_what_it_reads(project) -> None:
    result = runner.invoke(app, ["suggest"])
    assert result.exit_code == ExitStatus.INPUT_ERROR
    assert "suggest reads YAML themes, not the config's tokens: table" in result.output


@pytest.mark.parametrize("command", ["check", "suggest", "preview", "export"])
def test_a_bad_gamut_is_one_usage_line_on_every_command(project, command) -> None:
    args = {"preview": ["preview", "t.yaml", "i.yaml", "-o", "out"]}.get(command, [command])
    result = runner.invoke(app, [*args, "--gamut", "squash"])
    assert result.exit_code == ExitStatus.INPUT_ERROR
    assert "--gamut 'squash' is not a policy; use one of: clip, map, error" in result.output


def test_check_gamut_flag_overrides_the_tokens_table(project) -> None:
    result = runner.invoke(app, ["check", "-f", "json", "--gamut", "clip", "--exit-zero"])
    assert result.exit_code == ExitStatus.OK, result.output
    doc = json.loads(result.stdout)
    assert doc["gamut"] and {row["policy"] for row in doc["gamut"]} == {"clip"}
    assert {row["file"] for row in doc["gamut"]} == {"base.tokens.json"}
    error = runner.invoke(app, ["check", "--gamut", "error"])
    assert error.exit_code == ExitStatus.INPUT_ERROR
    assert "base.tokens.json:" in error.output and "outside sRGB" in error.output
