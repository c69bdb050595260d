"""Write docs/cli.md from the real ``--help`` of every command.

python tools/cli_reference.py          # rewrite docs/cli.md
python tools/cli_reference.py --check  # exit 1 if docs/cli.md is stale (the tests do this)
"""

from __future__ import annotations

import sys
from pathlib import Path

from typer.main import get_command
from typer.testing import CliRunner

from alpha_audit.cli import app

DOC = Path(__file__).resolve().parents[1] / "docs" / "cli.md"
ENV = {"COLUMNS": "100", "NO_COLOR": "1", "TERM": "dumb"}


def commands() -> list[str]:
    """Registered command names, in registration order."""
    return list(get_command(app).commands)  # type: ignore[attr-defined]


def help_text(args: list[str]) -> str:
    result = CliRunner().invoke(app, [*args, "--help"], env=ENV, prog_name="alpha-audit")
    if result.exit_code != 0:
        raise SystemExit(f"alpha-audit {' '.join(args)} --help failed: {result.output}")
    return "\n".join(line.rstrip() for line in result.stdout.strip().splitlines())


def reference() -> str:
    """The whole Markdown document."""
    parts = [
        "# Command-line reference",
        "",
        "Generated from `--help` by `tools/cli_reference.py`; a test fails when it is stale.",
        "",
        "```text",
        help_text([]),
        "```",
    ]
    for name in commands():
        parts += ["", f"## alpha-audit {name}", "", "```text", help_text([name]), "```"]
    return "\n".join(parts) + "\n"


if __name__ == "__main__":
    text = reference()
    if "--check" in sys.argv:
        sys.exit(0 if DOC.exists() and DOC.read_text() == text else 1)
    DOC.write_text(text)
    print(f"wrote {DOC}")
