"""--no-cache: check, suggest and preview neither read nor write the render cache."""

from __future__ import annotations

from pathlib import Path

import pytest
from typer.testing import CliRunner

from alpha_audit.cli import app
from alpha_audit.load.render_cache import FILE_NAME

ROOT = Path(__file__).resolve().parents[2]
THEME, ICONSET = "paper16", str(ROOT / "examples/vibrant/iconset.yaml")
COMMANDS = {
    "check": ["check", THEME, ICONSET, "-f", "json", "--exit-zero"],
    "suggest": ["suggest", THEME, ICONSET],
    "preview": ["preview", THEME, ICONSET, "--html", "{tmp}/page.html"],
}


@pytest.mark.parametrize("command", COMMANDS)
def test_no_cache_leaves_the_cache_alone_and_changes_no_result(
    command: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("ALPHA_AUDIT_CACHE_DIR", str(tmp_path / "cache"))
    args = [a.replace("{tmp}", str(tmp_path)) for a in COMMANDS[command]]
    runner = CliRunner()
    without = runner.invoke(app, [*args, "--no-cache"])
    assert without.exit_code in (0, 1), without.output
    assert not (tmp_path / "cache").exists()
    (tmp_path / "page.html").unlink(missing_ok=True)
    cold = runner.invoke(app, args)
    assert (tmp_path / "cache" / FILE_NAME).exists()
    (tmp_path / "page.html").unlink(missing_ok=True)
    warm = runner.invoke(app, args)
    assert without.output == cold.output == warm.output
    assert without.exit_code == cold.exit_code == warm.exit_code
