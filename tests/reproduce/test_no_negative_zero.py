"""The sweep's mean change at alpha = 1 is zero up to float rounding: shown as 0, never -0.

``reproduce --quick`` printed "-0.0000 / 0.0000" on the alpha = 1 row, which
reads as a (tiny) loss where the paper's identity says there is none.
"""

from __future__ import annotations

import re

import typer
from typer.testing import CliRunner

from alpha_audit.cli.reproduce import reproduce_command

app = typer.Typer()
app.command("reproduce")(reproduce_command)


@app.command("noop")
def _noop() -> None:  # a second command keeps "reproduce" a subcommand
    """Nothing."""


def test_quick_sweep_and_report_show_no_negative_zero() -> None:
    runner = CliRunner()
    for fmt in ("table", "markdown"):
        result = runner.invoke(app, ["reproduce", "--quick", "--only", "sweep", "--format", fmt])
        assert result.exit_code == 0, result.output
        assert not re.search(r"-0\.0+(?!\d*[1-9])\b", result.stdout), result.stdout
