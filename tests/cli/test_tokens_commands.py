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


def test_check_says_on_stderr_which_rules_became_modes_and_which_canvases_are_layers(
    tmp_path, monkeypatch
) -> None:
    (tmp_path / ".git").mkdir()
    (tmp_path / "tokens.css").write_text(
        ":root { --bg: #ffffff; --chip: rgb(9 105 218 / 0.08); --fg: #0062ba; --gap: 4px }\n"
        "@media (prefers-color-scheme: dark) { :root { --bg: #0d1117; --fg: #4493f8 } }\n",
        encoding="utf-8",
    )
    (tmp_path / "icons").mkdir()
    shutil.copy(REPO / "examples/vibrant/svg/bell.svg", tmp_path / "icons")
    (tmp_path / "iconset.yaml").write_text("name: t\nicons: icons/*.svg\ncolor: fg\n")
    (tmp_path / "alpha-audit.yaml").write_text(
        "tokens: {file: tokens.css, canvases: [bg, chip], colors: [fg]}\niconset: iconset.yaml\n"
    )
    monkeypatch.chdir(tmp_path)
    result = runner.invoke(app, ["check", "-f", "json"])
    assert result.exit_code == ExitStatus.OK, result.output
    assert "mode dark from tokens.css: line 2 @media (prefers-color-scheme: dark) :root" in (
        result.stderr
    )
    assert "translucent canvases chip (0.08) audited as layers over bg" in result.stderr
    assert "mode dark" not in result.stdout  # the report stays machine-readable
    assert [a["theme"]["name"] for a in json.loads(result.stdout)["audits"]] == ["default", "dark"]
