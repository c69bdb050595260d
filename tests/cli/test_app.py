"""The root command: render workers start as soon as a rendering command is named."""

from __future__ import annotations

from pathlib import Path

import pytest
from typer.testing import CliRunner

from alpha_audit.cli import app
from alpha_audit.load import sandbox

ROOT = Path(__file__).resolve().parents[2]
runner = CliRunner()


@pytest.fixture
def started(monkeypatch: pytest.MonkeyPatch) -> list[int]:
    """Render processes started during the test (one entry each)."""
    made: list[int] = []
    real = sandbox._Worker.__init__

    def spy(self: sandbox._Worker, *args: object) -> None:
        made.append(1)
        real(self, *args)  # type: ignore[arg-type]  # the RenderLimits (and fork server) given

    monkeypatch.setattr(sandbox._Worker, "__init__", spy)
    return made


@pytest.mark.parametrize("command", ["check", "suggest"])
def test_help_starts_no_renderer(started: list[int], command: str) -> None:
    result = runner.invoke(app, [command, "--help"])
    assert result.exit_code == 0 and "Usage" in result.output
    assert started == []


def test_check_renders_with_the_workers_started_before_its_inputs(started: list[int]) -> None:
    """The workers started early are the ones that render: none is started a second time."""
    from alpha_audit.load.svg import RenderLimits

    args = ["check", "paper16", str(ROOT / "examples/vibrant/iconset.yaml"), "-f", "json"]
    result = runner.invoke(app, args)
    assert result.exit_code in (0, 1), result.output
    assert '"schema"' in result.output
    assert 1 <= len(started) <= RenderLimits().workers


def test_an_input_error_stops_the_workers_started_early(started: list[int]) -> None:
    result = runner.invoke(app, ["check", "no-such-theme.yaml", "no-such-set.yaml"])
    assert result.exit_code == 2
    assert started  # they had been started ...
    # ... and were stopped with the command: no render process is left running
    import subprocess

    ps = subprocess.run(["ps", "-eo", "ppid,args"], capture_output=True, text=True).stdout
    import os

    mine = [line for line in ps.splitlines() if line.split()[0] == str(os.getpid())]
    assert not any("_svg_worker.py" in line and "<defunct>" not in line for line in mine)


@pytest.mark.parametrize("command", [[], ["check"], ["suggest"], ["export"], ["reproduce"]])
def test_help_shows_flags_without_a_value_type(command: list[str]) -> None:
    """typer would print ``--force <bool>``, as if the flag took a value."""
    result = runner.invoke(app, [*command, "--help"], env={"COLUMNS": "120"})
    assert result.exit_code == 0
    assert "<bool>" not in result.output
    assert "--help" in result.output
