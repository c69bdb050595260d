"""The default gate holds ``confusion`` (issue 11): Primer's severe and danger at 1.15.

A small manifest in ``tmp_path``: Primer's fg accents (severe ``#bc4c00``,
danger ``#d1242f``, accent, success) cycling over bundled SVGs, on Primer's
light canvases ``#ffffff`` and ``#f6f8fa``.  ``check`` at 1.15 fails the
default gate naming the two roles; ``suggest`` answers below 1.15 and that
answer passes ``check`` while one rounding unit above it fails.
"""

from __future__ import annotations

import json
import shutil
from pathlib import Path

from typer.testing import CliRunner

from alpha_audit.cli import app

runner = CliRunner()
SVGS = ("alert", "bell", "check", "heart")


def _project(tmp_path: Path, repo: Path) -> tuple[str, str]:
    (tmp_path / "svg").mkdir()
    for name in SVGS:
        shutil.copy(repo / "examples" / "vibrant" / "svg" / f"{name}.svg", tmp_path / "svg")
    iconset = tmp_path / "primer-fg.yaml"
    iconset.write_text(
        "name: Primer fg accents\n"
        "icons: svg/*.svg\n"
        'palette: {severe: "#bc4c00", danger: "#d1242f", accent: "#0969da", '
        'success: "#1a7f37"}\n'
        "color: cycle\n"
        "alpha: 1.15\n"
        "sizes: [16, 24]\n"
    )
    theme = tmp_path / "primer-light.yaml"
    theme.write_text(
        "name: Primer light\n"
        "canvases:\n"
        '  - {name: light-default, color: "#ffffff"}\n'
        '  - {name: light-muted, color: "#f6f8fa"}\n'
    )
    (tmp_path / ".git").mkdir()  # the project root
    return str(theme), str(iconset)


def _check(theme: str, iconset: str, *extra: str) -> tuple[int, dict]:
    res = runner.invoke(app, ["check", theme, iconset, "-f", "json", *extra])
    return res.exit_code, json.loads(res.stdout)


def test_primer_accents_fail_the_default_gate_on_confusion(tmp_path: Path, repo: Path) -> None:
    theme, iconset = _project(tmp_path, repo)
    code, doc = _check(theme, iconset)
    assert code == 1
    findings = [f for f in doc["gate"]["failures"] if f["rule"] == "confusion"]
    # One root cause (the pair of roles), naming both canvases.
    (finding,) = findings
    assert set(finding["canvases"]) == {"light-default", "light-muted"}
    assert finding["canvas"] in finding["canvases"]
    for f in findings:
        assert f["numbers"]["roles"] == "danger,severe" and "danger and severe" in f["message"]
        assert f["numbers"]["delta_e_ref"] >= 10 > f["numbers"]["delta_e"]


def test_suggest_answers_the_largest_alpha_check_accepts(tmp_path: Path, repo: Path) -> None:
    theme, iconset = _project(tmp_path, repo)
    res = runner.invoke(app, ["suggest", theme, iconset, "-f", "json"])
    assert res.exit_code == 0, res.output
    doc = json.loads(res.stdout)
    answer, precision = doc["alpha"], doc["precision"]
    assert 1.0 <= answer < 1.15
    assert doc["limited_by"]["rule"] == "confusion"
    assert doc["limited_by"]["grid"] is not None  # bracketed, and the report says so
    assert _check(theme, iconset, "-a", f"{answer:.{precision}f}")[0] == 0
    above = round(answer + 10.0**-precision, precision)
    code, after = _check(theme, iconset, "-a", f"{above:.{precision}f}")
    assert code == 1
    assert {f["rule"] for f in after["gate"]["failures"]} == {"confusion"}
