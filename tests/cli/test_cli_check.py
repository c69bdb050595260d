"""``check`` and ``pair`` through typer's runner: output, formats, exit codes, errors."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from typer.testing import CliRunner

from alpha_audit.cli import app
from helpers import spec_contrast, spec_hex

runner = CliRunner()


@pytest.fixture
def paths(repo: Path) -> tuple[str, str]:
    return str(repo / "themes/github-primer.yaml"), str(repo / "examples/vibrant/iconset.yaml")


def test_check_table_fits_80_columns(paths: tuple[str, str]) -> None:
    result = runner.invoke(app, ["check", *paths, "--alpha", "1.1"])
    assert result.exit_code == 0, result.output
    assert "light-default" in result.stdout and "dark-default" in result.stdout
    assert "Newly reach 3:1" in result.stdout
    assert max(len(line) for line in result.stdout.splitlines()) <= 80
    assert "\x1b[" not in result.stdout  # not a terminal: no ANSI codes


def test_check_json_matches_library(paths: tuple[str, str]) -> None:
    result = runner.invoke(app, ["check", *paths, "--alpha", "1.1", "--format", "json"])
    assert result.exit_code == 0
    doc = json.loads(result.stdout)
    assert doc["schema"] == "alpha-audit.check/4"
    assert len(doc["rows"]) == 12 * 8
    orange_on_white = next(
        r for r in doc["rows"] if r["source"] == "#ee7733" and r["background"] == "#ffffff"
    )
    assert orange_on_white["output"] == "#ec5a00"
    # Judged as it ships (8-bit against 8-bit); the unrounded figure beside it.
    assert orange_on_white["contrast"] == pytest.approx(
        spec_contrast(spec_hex("#ec5a00"), spec_hex("#ffffff")), rel=1e-12
    )
    assert orange_on_white["contrast_float"] == 3.4733853122940994
    assert {r["alpha"] for r in doc["rows"]} == {1.1}
    assert doc["summary"]["combinations"] == 96


def test_check_writes_output_but_never_over_a_file(tmp_path: Path, paths: tuple[str, str]) -> None:
    target = tmp_path / "report.json"
    first = runner.invoke(app, ["check", *paths, "-f", "json", "-o", str(target)])
    assert first.exit_code == 0 and json.loads(target.read_text())["schema"]
    target.write_text("mine")
    second = runner.invoke(app, ["check", *paths, "-f", "json", "-o", str(target)])
    assert second.exit_code == 2
    assert "already exists" in second.output and target.read_text() == "mine"
    third = runner.invoke(app, ["check", *paths, "-f", "json", "-o", str(target), "--force"])
    assert third.exit_code == 0 and target.read_text() != "mine"


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["check", "missing.yaml", "x.yaml"], "missing.yaml: file not found"),
        (
            ["check", "{theme}", "{icons}", "--alpha", "nan"],
            "--alpha nan is out of range; expected a finite coefficient between -100 and 100",
        ),
        (["check", "{theme}", "{icons}", "--format", "xml"], "xml"),
        (["pair", "blurple", "--on", "white"], "'blurple' is not a colour"),
    ],
)
def test_bad_input_exits_2_with_one_line(
    args: list[str], message: str, paths: tuple[str, str]
) -> None:
    args = [a.format(theme=paths[0], icons=paths[1]) for a in args]
    result = runner.invoke(app, args)
    assert result.exit_code == 2
    assert message in result.output
    assert "Traceback" not in result.output


def test_broken_svg_is_reported_not_fatal(tmp_path: Path, repo: Path) -> None:
    (tmp_path / ".git").mkdir()
    (tmp_path / "svg").mkdir()
    (tmp_path / "svg/good.svg").write_text(
        '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 24 24">'
        '<rect x="4" y="4" width="16" height="16"/></svg>'
    )
    (tmp_path / "svg/broken.svg").write_bytes(b"\x89PNG\r\n\x1a\n....")
    (tmp_path / "svg/empty.svg").write_text('<svg xmlns="http://www.w3.org/2000/svg"/>')
    manifest = tmp_path / "iconset.yaml"
    manifest.write_text("icons: svg/*.svg\ncolor: '#0077bb'\n")
    theme = str(repo / "themes/paper16.yaml")
    result = runner.invoke(app, ["check", theme, str(manifest), "-f", "json"])
    assert result.exit_code == 0, result.output
    doc = json.loads(result.stdout)
    assert {p["icon"] for p in doc["problems"]} == {"broken", "empty"}
    assert {r["icon"] for r in doc["rows"]} == {"good"}
    strict = runner.invoke(app, ["check", theme, str(manifest), "--strict-svg"])
    assert strict.exit_code == 2 and "PNG" in strict.output


def test_pair_json() -> None:
    result = runner.invoke(
        app,
        [
            "pair",
            "#ee7733",
            "--on",
            "white",
            "--on",
            "#0d1117",
            "-a",
            "1",
            "-a",
            "1.1",
            "-f",
            "json",
        ],
    )
    assert result.exit_code == 0
    rows = json.loads(result.stdout)["rows"]
    assert [(r["background"], r["alpha"]) for r in rows] == [
        ("#ffffff", 1.0),
        ("#ffffff", 1.1),
        ("#0d1117", 1.0),
        ("#0d1117", 1.1),
    ]
    assert rows[1]["output"] == "#ec5a00" and rows[1]["clipped"]
    assert rows[0]["gain"] == 0.0


def test_help_teaches() -> None:
    top = runner.invoke(app, ["--help"])
    assert top.exit_code == 0
    assert "Exit codes" in top.stdout and "check" in top.stdout and "pair" in top.stdout
    sub = runner.invoke(app, ["check", "--help"])
    assert "Example" in sub.stdout and "--alpha" in sub.stdout


def test_reports_get_ordinary_permissions(tmp_path: Path, paths: tuple[str, str]) -> None:
    import os

    target = tmp_path / "report.json"
    old = os.umask(0o022)
    try:
        assert runner.invoke(app, ["check", *paths, "-f", "json", "-o", str(target)]).exit_code == 0
    finally:
        os.umask(old)
    assert target.stat().st_mode & 0o777 == 0o644


def test_table_merges_icons_that_share_colour_and_alpha(paths: tuple[str, str]) -> None:
    # bell and plus are both cyan at 1.1 in the example: one line per canvas, both named.
    out = runner.invoke(app, ["check", *paths, "--alpha", "1.1"]).stdout
    cyan = [line for line in out.splitlines() if "cyan #33bbee" in line]
    assert cyan and all("bell, plus" in line for line in cyan)
