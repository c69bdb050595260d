"""``alpha-audit reproduce`` through typer's CliRunner, on a tiny app registering the command."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
import typer
from PIL import Image
from typer.testing import CliRunner

from alpha_audit.cli.reproduce import reproduce_command
from alpha_audit.errors import InputError, UsageError
from alpha_audit.reproduce.report import SCHEMA

app = typer.Typer()
app.command("reproduce")(reproduce_command)


@app.command("noop")
def _noop() -> None:  # a second command keeps "reproduce" a subcommand, as in the real CLI
    """Nothing."""


runner = CliRunner()


def invoke(*args: str):
    return runner.invoke(app, ["reproduce", *args], catch_exceptions=True)


def test_broad_grid_json_prints_the_papers_figures() -> None:
    """The issue's bar: ``reproduce --only broad-grid --format json`` on the full grid."""
    result = invoke("--only", "broad-grid", "--format", "json")
    assert result.exit_code == 0, result.output
    doc = json.loads(result.stdout)
    assert doc["schema"] == SCHEMA
    grid = doc["broad_grid"]
    assert (grid["source_levels"], grid["background_levels"]) == (17, 33)
    for alpha, (inc, dec, loss, small, worst) in {
        "1.1": (90.3672, 9.3318, 0.4655, 99.34, 9.8118),
        "1.4": (86.7022, 12.9968, 1.6394, 81.53, 8.6379),
    }.items():
        r = grid[alpha]
        assert round(r["increase_pct"], 4) == inc
        assert round(r["decrease_pct"], 4) == dec
        assert round(r["max_loss"], 4) == loss
        assert round(r["loss_le_0_25_pct"], 2) == small
        assert r["worst"]["source"] == [0.0, 0.0, 0.8125]
        assert r["worst"]["background"] == [1.0, 1.0, 0.0]
        assert round(r["worst"]["contrast"]["1.0"], 4) == 10.2773
        assert round(r["worst"]["contrast"][alpha], 4) == worst
    assert "full_gamut" not in doc and "sweep" not in doc and "palette" not in doc


def test_quick_run_writes_every_output(tmp_path: Path) -> None:
    out = tmp_path / "out"
    result = invoke("--quick", "--out", str(out))
    assert result.exit_code == 0, result.output
    assert "Broad grid" in result.stdout and "Palette separation" in result.stdout
    doc = json.loads((out / "results.json").read_text())
    assert doc["schema"] == SCHEMA and doc["quick"] is True
    assert set(doc) >= {"broad_grid", "full_gamut", "sweep", "palette", "paper", "theme"}
    fg = doc["full_gamut"]["1.1"]
    assert len(fg["canvases"]) == 16
    assert fg["all"]["combinations"] == 16 * 33**3
    assert (
        fg["all"]["increase"] + fg["all"]["decrease"] + fg["all"]["unchanged"]
        == (fg["all"]["combinations"])
    )
    assert len(doc["sweep"]["alphas"]) == 21
    assert doc["palette"]["combinations"] == 336
    report = (out / "report.md").read_text()
    assert "99.8145" in report  # the paper's value, shown beside ours
    # Quick grids are not the paper's: shown, never called a match or a mismatch ...
    assert "no: 33^3 sources, not 256^3 (abstract, Table 1) | n/a |" in report
    assert "no: a 5^3 x 9^3 grid, not 17^3 x 33^3 (Table 1) | n/a |" in report
    # ... but the palette pairs on the paper's canvases do not depend on the grids.
    assert "| alpha 1.1: smaller CIEDE2000 | 32 | 32 | yes (Section 4.3) | **yes** |" in report
    assert "**NO**" not in report
    for name in ("sweep-1-2.png", "sweep-0-2.png"):
        with Image.open(out / name) as image:
            assert image.format == "PNG" and image.size[0] > image.size[1] > 100


def test_markdown_on_stdout_and_only_repeatable(repo: Path) -> None:
    result = invoke(
        "--quick", "--only", "palette", "--only", "full-gamut", "--format", "markdown",
        "--theme", str(repo / "themes" / "paper16.yaml"), "--alpha", "1.2",
    )  # fmt: skip
    assert result.exit_code == 0, result.output
    assert result.stdout.startswith("# alpha-audit reproduce")
    assert "## Palette separation" in result.stdout and "## Full gamut" in result.stdout
    assert "## Broad grid" not in result.stdout
    assert "alpha 1.2: increase %" in result.stdout


def test_missing_theme_is_a_usage_error(tmp_path: Path) -> None:
    result = invoke("--theme", str(tmp_path / "nope.yaml"), "--quick")
    assert isinstance(result.exception, UsageError)
    assert "not found" in str(result.exception)


def test_bad_theme_is_an_input_error(tmp_path: Path) -> None:
    bad = tmp_path / "bad.yaml"
    bad.write_text("name: bad\ncanvases:\n  - {name: x, color: '#12'}\n")
    result = invoke("--theme", str(bad), "--quick", "--only", "palette")
    assert isinstance(result.exception, InputError)


def test_out_must_not_be_a_file(tmp_path: Path) -> None:
    target = tmp_path / "file"
    target.write_text("keep me")
    result = invoke("--quick", "--only", "palette", "--out", str(target))
    assert result.exit_code != 0
    assert target.read_text() == "keep me"


@pytest.mark.parametrize("bad", [["--only", "nonsense"], ["--format", "yaml"]])
def test_unknown_choices_exit_2(bad: list[str]) -> None:
    result = invoke("--quick", *bad)
    assert result.exit_code == 2


def test_table_prints_the_shared_worst_case_once() -> None:
    """Both alphas' largest loss is the paper's (0, 0, 0.8125) on yellow: one line, not two."""
    result = runner.invoke(
        app, ["reproduce", "--only", "broad-grid", "--alpha", "1.1", "--alpha", "1.4"],
        env={"COLUMNS": "200"},
    )  # fmt: skip
    assert result.exit_code == 0, result.output
    assert result.stdout.count("largest loss") == 1
    assert "alpha 1.1 and 1.4: largest loss (0,0,0.8125) on (1,1,0)" in result.stdout
    assert "9.8118 (a=1.1) > 8.6379 (a=1.4)" in result.stdout


def test_out_refuses_existing_files_unless_forced(tmp_path: Path) -> None:
    out = tmp_path / "out"
    out.mkdir()
    (out / "report.md").write_text("mine")
    result = invoke("--quick", "--only", "broad-grid", "--out", str(out))
    assert isinstance(result.exception, UsageError)  # exit 2 at the real CLI's boundary
    assert result.exception.path == out / "report.md"
    assert sorted(p.name for p in out.iterdir()) == ["report.md"]  # nothing else written
    assert (out / "report.md").read_text() == "mine"
    forced = invoke("--quick", "--only", "broad-grid", "--out", str(out), "--force")
    assert forced.exit_code == 0, forced.output
    assert (out / "report.md").read_text().startswith("# alpha-audit reproduce")


def test_out_replaces_a_symlink_instead_of_writing_through_it(tmp_path: Path) -> None:
    out, victim = tmp_path / "out", tmp_path / "victim.txt"
    out.mkdir()
    victim.write_text("outside the folder")
    (out / "results.json").symlink_to(victim)
    result = invoke("--quick", "--only", "broad-grid", "--out", str(out), "--force")
    assert result.exit_code == 0, result.output
    assert victim.read_text() == "outside the folder"
    assert not (out / "results.json").is_symlink()
    assert json.loads((out / "results.json").read_text())["schema"] == SCHEMA
