"""Every format a command writes has its file extensions, so ``-o`` never crashes on it.

``-f gitlab -o gl-code-quality-report.json`` (GitLab's own artifact name) raised
``KeyError: 'gitlab'`` (exit 3) because the extension table missed the format.
"""

from __future__ import annotations

import json
import os
from pathlib import Path

import pytest
from typer.testing import CliRunner

from alpha_audit.cli import app
from alpha_audit.errors import UsageError
from alpha_audit.render import SUFFIXES, CheckFormat, SuggestFormat
from alpha_audit.render.common import check_suffix

REPO = Path(__file__).resolve().parents[2]
INPUTS = [str(REPO / "themes" / "paper16.yaml"), str(REPO / "examples/vibrant/iconset.yaml")]


@pytest.mark.parametrize("fmt", [*CheckFormat, *SuggestFormat], ids=str)
def test_every_format_has_extensions_and_refuses_another_formats(fmt: str) -> None:
    assert SUFFIXES[fmt]
    for suffix in SUFFIXES[fmt]:
        check_suffix(fmt, Path(f"report{suffix}"))  # its own: accepted
    others = {s for f, ss in SUFFIXES.items() for s in ss} - set(SUFFIXES[fmt])
    for suffix in sorted(others):
        with pytest.raises(UsageError, match="another format"):
            check_suffix(fmt, Path(f"report{suffix}"))


def test_gitlab_report_to_its_usual_file_name(tmp_path: Path) -> None:
    old = Path.cwd()
    os.chdir(tmp_path)
    try:
        runner = CliRunner()
        args = ["check", *INPUTS, "-a", "1.3", "-f", "gitlab", "-o", "gl-code-quality-report.json"]
        result = runner.invoke(app, args)
        assert result.exit_code == 1, result.output  # the gate fails at 1.3
        issues = json.loads((tmp_path / "gl-code-quality-report.json").read_text())
        assert issues and len({i["fingerprint"] for i in issues}) == len(issues)
        wrong = runner.invoke(app, ["check", *INPUTS, "-f", "gitlab", "-o", "x.sarif"])
        assert wrong.exit_code == 2 and len(wrong.output.strip().splitlines()) == 1
        assert "x.sarif" in wrong.output and "gitlab reports are .json" in wrong.output
    finally:
        os.chdir(old)
