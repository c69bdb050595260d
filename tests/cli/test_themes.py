"""Bundled themes and example: ``alpha-audit themes``, names as arguments, from any folder."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest
from typer.testing import CliRunner

from alpha_audit.bundled import (
    bundled_iconset,
    bundled_iconsets,
    bundled_theme,
    bundled_themes,
    iconset_source,
    theme_source,
)
from alpha_audit.cli import ExitStatus, app
from alpha_audit.errors import UsageError
from alpha_audit.load.theme import load_theme

runner = CliRunner()
BUNDLED = ("github-primer", "material3", "paper16")


def test_the_three_themes_and_the_example_are_bundled(repo: Path) -> None:
    assert bundled_themes() == BUNDLED
    assert bundled_iconsets() == ("vibrant",)
    for name in BUNDLED:  # the same bytes as the repository's top-level files
        assert bundled_theme(name).read_bytes() == (repo / "themes" / f"{name}.yaml").read_bytes()
    manifest = repo / "examples/vibrant/iconset.yaml"
    assert bundled_iconset("vibrant").read_bytes() == manifest.read_bytes()


def test_unknown_names_list_the_bundled_ones() -> None:
    with pytest.raises(UsageError, match="no bundled theme 'nord'; bundled: github-primer, "):
        bundled_theme("nord")
    with pytest.raises(UsageError, match="bundled: vibrant"):
        bundled_iconset("nope")


def test_an_existing_path_wins_over_a_bundled_name(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(tmp_path)
    assert theme_source("paper16") == bundled_theme("paper16")
    Path("paper16").write_text("name: mine\n")
    assert theme_source("paper16") == Path("paper16")
    assert iconset_source("elsewhere.yaml") == Path("elsewhere.yaml")  # left for the loader


def test_themes_table_lists_every_theme_and_canvas() -> None:
    result = runner.invoke(app, ["themes"])
    assert result.exit_code == ExitStatus.OK, result.output
    for name in BUNDLED:
        assert name in result.stdout
        for canvas in load_theme(bundled_theme(name)).canvases:
            assert canvas.name in result.stdout and canvas.color in result.stdout


def test_themes_json() -> None:
    result = runner.invoke(app, ["themes", "-f", "json"])
    assert result.exit_code == ExitStatus.OK
    doc = json.loads(result.stdout)
    assert [t["name"] for t in doc["themes"]] == list(BUNDLED)
    primer = doc["themes"][0]
    assert primer["title"] == "GitHub Primer" and primer["threshold"] == 3.0
    assert primer["canvases"][0] == {"name": "light-default", "color": "#ffffff", "mode": "light"}
    assert len(doc["themes"][2]["canvases"]) == 16


def test_apply_refuses_to_rewrite_the_bundled_example() -> None:
    result = runner.invoke(app, ["suggest", "paper16", "vibrant", "--apply", "set"])
    assert result.exit_code == ExitStatus.INPUT_ERROR
    assert "bundled example" in result.output and "copy" in result.output


def _run(args: list[str], cwd: Path) -> subprocess.CompletedProcess[str]:
    env = {k: v for k, v in os.environ.items() if k not in ("NO_COLOR", "FORCE_COLOR")}
    return subprocess.run(
        [sys.executable, "-m", "alpha_audit", *args],
        cwd=cwd,
        capture_output=True,
        text=True,
        env=env,
        timeout=300,
    )


def test_bundled_names_resolve_from_an_empty_folder(tmp_path: Path) -> None:
    check = _run(["check", "github-primer", "vibrant", "-f", "json"], tmp_path)
    assert check.returncode == 0, check.stderr
    doc = json.loads(check.stdout)
    assert doc["summary"]["combinations"] == 12 * 8
    listing = _run(["themes"], tmp_path)
    assert listing.returncode == 0 and all(name in listing.stdout for name in BUNDLED)
    assert list(tmp_path.iterdir()) == []  # nothing written


def test_reproduce_finds_paper16_from_an_empty_folder(tmp_path: Path) -> None:
    run = _run(["reproduce", "--quick", "--only", "palette", "--format", "json"], tmp_path)
    assert run.returncode == 0, run.stderr
    doc = json.loads(run.stdout)
    assert doc["theme"]["name"] == load_theme(bundled_theme("paper16")).name


@pytest.mark.parametrize(
    "args",
    [
        ["suggest", "paper16", "vibrant", "-f", "json"],
        ["reproduce", "--theme", "material3", "--quick", "--only", "palette", "--format", "json"],
        ["check", "paper16", "vibrant", "--theme", "material3", "-f", "json"],
    ],
)
def test_every_command_taking_a_theme_accepts_bundled_names(args: list[str]) -> None:
    result = runner.invoke(app, args)
    assert result.exit_code == ExitStatus.OK, result.output
    assert json.loads(result.stdout)


def test_preview_accepts_bundled_names(tmp_path: Path) -> None:
    result = runner.invoke(app, ["preview", "github-primer", "vibrant", "-o", str(tmp_path)])
    assert result.exit_code == ExitStatus.OK, result.output
    assert sorted(p.suffix for p in tmp_path.iterdir()) == [".png"] * len(list(tmp_path.iterdir()))
    assert any(tmp_path.iterdir())


def test_no_color_means_no_escape_codes_even_on_a_terminal() -> None:
    """Like every report: NO_COLOR drops bold too (a forced terminal stands in for a TTY)."""
    import os
    import subprocess
    import sys

    env = {**os.environ, "FORCE_COLOR": "1", "NO_COLOR": "1", "COLUMNS": "100"}
    out = subprocess.run(
        [sys.executable, "-m", "alpha_audit", "themes"], capture_output=True, text=True, env=env
    ).stdout
    assert "paper16" in out and "\x1b" not in out
