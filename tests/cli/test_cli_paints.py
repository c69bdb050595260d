"""The issue's bars through the CLI: paints, opacity, size, pipelines, drift and confusion."""

from __future__ import annotations

import json
import os
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from alpha_audit.cli import app
from alpha_audit.color import contrast_ratio, hex_to_linear
from alpha_audit.load.paints import isolate_paints
from alpha_audit.load.svg import rasterize
from helpers import spec_contrast, spec_hex, spec_ship

runner = CliRunner()
NS = 'xmlns="http://www.w3.org/2000/svg"'
STROKED = (
    f'<svg {NS} viewBox="0 0 24 24" fill="none" stroke="currentColor" stroke-width="2" '
    'stroke-linecap="round"><circle cx="12" cy="12" r="10"/><path d="M12 8v4M12 16h.01"/></svg>'
)
SVGS = {
    "red": f'<svg {NS} viewBox="0 0 24 24" fill="none"><path d="M4 4L20 20" stroke="#ff0000" '
    'stroke-width="3"/></svg>',
    "disc": f'<svg {NS} viewBox="0 0 24 24"><circle cx="12" cy="12" r="10" opacity="0.3" '
    'fill="currentColor"/></svg>',
    "alert": STROKED,
}


@pytest.fixture
def project(tmp_path: Path) -> Path:
    (tmp_path / ".git").mkdir()
    (tmp_path / "svg").mkdir()
    for name, text in SVGS.items():
        (tmp_path / "svg" / f"{name}.svg").write_text(text)
    (tmp_path / "theme.yaml").write_text('canvases: [{name: white, color: "#ffffff"}]\n')
    (tmp_path / "set.yaml").write_text(
        'icons: "svg/*.svg"\ncolor: "#64748b"\nalpha: 1.2\nsizes: [16, 48]\n'
    )
    return tmp_path


def check(project: Path, *args: str) -> tuple[int, dict, str]:
    result = runner.invoke(
        app,
        ["check", str(project / "theme.yaml"), str(project / "set.yaml"), "-f", "json", *args],
    )
    doc = json.loads(result.stdout) if result.stdout.strip().startswith("{") else {}
    return result.exit_code, doc, result.output


def test_red_stroke_is_audited_as_red_with_a_fixed_colour_finding(project: Path) -> None:
    code, doc, _ = check(project, "--fail-on", "fixed-colour")
    assert code == 1
    (row,) = [r for r in doc["rows"] if r["icon"] == "red"]
    assert (row["paint"], row["source"], row["kinds"]) == ("#ff0000", "#ff0000", ["stroke"])
    red = hex_to_linear("#ff0000")
    assert row["contrast_ref"] == pytest.approx(float(contrast_ratio(red, np.ones(3))))
    (finding,) = doc["gate"]["failures"]
    assert finding["rule"] == "fixed-colour" and finding["icons"] == ["red"]
    assert finding["numbers"]["element"] == "<path> (line 1)"


def test_thirty_percent_disc_has_the_coverage_form_contrast(project: Path) -> None:
    _, doc, _ = check(project, "--exit-zero")
    (row,) = [r for r in doc["rows"] if r["icon"] == "disc"]
    assert row["opacity"] == pytest.approx(0.3)
    cs, cb = hex_to_linear("#64748b"), np.ones(3)
    shown = 0.3 * np.clip(cb + 1.2 * (cs - cb), 0, 1) + 0.7 * cb
    assert row["contrast_float"] == pytest.approx(spec_contrast(shown, cb), rel=1e-12)
    assert row["contrast"] == pytest.approx(spec_contrast(spec_ship(shown), cb), rel=1e-12)


def test_size_contrast_is_lower_at_16_and_matches_an_independent_q50(project: Path) -> None:
    _, doc, _ = check(project, "--exit-zero")
    (row,) = [r for r in doc["rows"] if r["icon"] == "alert"]
    for size in (16, 48):
        mask = rasterize(isolate_paints(STROKED.encode(), lambda p: True), size)
        q = np.sort(mask[mask > 0])
        q50 = q[np.argmax(np.cumsum(q) >= q.sum() / 2)]
        cs, cb = spec_hex("#64748b"), np.ones(3)
        shown = q50 * np.clip(cb + 1.2 * (cs - cb), 0, 1) + (1 - q50) * cb  # as it ships
        expected = spec_contrast(spec_ship(shown), cb)
        assert row["sizes"][str(size)]["contrast"] == pytest.approx(expected, abs=1e-12)
    assert row["sizes"]["16"]["contrast"] < row["sizes"]["48"]["contrast"] <= row["contrast"]


def test_slate_500_drifts_about_29_5(project: Path) -> None:
    _, doc, _ = check(project, "--exit-zero")
    (row,) = [r for r in doc["rows"] if r["icon"] == "alert"]
    assert row["output"] == "#00195d"
    assert row["drift"] == pytest.approx(29.5, abs=0.05)
    assert doc["summary"]["max_drift"] >= row["drift"]
    code, doc, _ = check(project, "--fail-on", "drift", "--max-drift", "25")
    assert code == 1 and {f["rule"] for f in doc["gate"]["failures"]} == {"drift"}


def test_css_pipeline_gives_the_gamma_blend_and_refuses_alpha_above_one(project: Path) -> None:
    _, doc, _ = check(project, "--pipeline", "css", "--alpha", "0.6", "--exit-zero")
    assert doc["pipeline"] == "css"
    (row,) = [r for r in doc["rows"] if r["icon"] == "alert"]
    # codes: 255 + 0.6 (100 - 255) = 162, 255 + 0.6 (116 - 255) = 171.6, ... (139) = 185.4
    assert row["output"] == "#a2acb9"
    code, _, output = check(project, "--pipeline", "css", "--alpha", "1.2")
    assert code == 2
    assert "--alpha 1.2 cannot be drawn by pipeline css" in output
    code, _, output = check(project, "--pipeline", "css")  # the manifest's 1.2
    assert code == 2 and "set.yaml:3" in output and "pipeline css" in output


def test_pipeline_from_the_manifest_and_bad_names(project: Path) -> None:
    manifest = project / "set.yaml"
    manifest.write_text(manifest.read_text().replace("alpha: 1.2", "alpha: 0.6\npipeline: css"))
    _, doc, _ = check(project, "--exit-zero")
    assert doc["pipeline"] == "css"
    _, doc, _ = check(project, "--exit-zero", "--pipeline", "linear")
    assert doc["pipeline"] == "linear"
    manifest.write_text(manifest.read_text().replace("pipeline: css", "pipeline: webgl"))
    code, _, output = check(project)
    assert code == 2 and "set.yaml:4" in output and "use one of: linear, css" in output


def test_primer_severe_and_danger_confuse_at_1_15(tmp_path: Path, repo: Path) -> None:
    (tmp_path / ".git").mkdir()
    for name in ("alert", "stop"):
        (tmp_path / f"{name}.svg").write_text(STROKED)
    (tmp_path / "set.yaml").write_text(
        'icons: "*.svg"\npalette: {severe: "#bc4c00", danger: "#d1242f"}\nalpha: 1.15\n'
        "overrides: {alert: {color: severe}, stop: {color: danger}}\n"
    )
    args = ["check", str(repo / "themes/github-primer.yaml"), str(tmp_path / "set.yaml")]
    result = runner.invoke(app, [*args, "--fail-on", "confusion", "-f", "json"])
    assert result.exit_code == 1
    failures = json.loads(result.stdout)["gate"]["failures"]
    (confusion,) = failures  # one pair of roles: one root cause over the canvases
    assert {"light-default", "light-muted"} <= set(confusion["canvases"])
    assert confusion["numbers"]["roles"] == "danger,severe"
    assert confusion["icons"] == ["alert", "stop"]
    # Located at the palette entries of both roles (the manifest's line 2).
    assert [(p["line"], p["what"]) for p in confusion["locations"]][:1] == [(2, "colour")]


def test_lock_from_the_manifest(project: Path) -> None:
    manifest = project / "set.yaml"
    manifest.write_text(manifest.read_text() + "overrides: {alert: {lock: true}}\n")
    code, doc, _ = check(project, "--fail-on", "lock")
    assert code == 1
    assert {(f["rule"], tuple(f["icons"])) for f in doc["gate"]["failures"]} == {
        ("lock", ("alert",))
    }


def test_config_sets_pipeline_and_paint_limits(project: Path) -> None:
    (project / "alpha-audit.yaml").write_text(
        "theme: theme.yaml\niconset: set.yaml\npipeline: css\nalpha: 0.6\n"
        "fail-on: [drift, thin-strokes]\nmax-drift: 5\nmin-size-contrast: 1.2\n"
    )
    old = Path.cwd()
    os.chdir(project)
    try:
        result = runner.invoke(app, ["check", "-f", "json"])
        doc = json.loads(result.stdout)
        assert doc["pipeline"] == "css"
        policy = doc["gate"]["policy"]
        assert (policy["max_drift"], policy["min_size_contrast"]) == (5.0, 1.2)
        (project / "alpha-audit.yaml").write_text("theme: theme.yaml\npipeline: 3\n")
        bad = runner.invoke(app, ["check"])
        assert bad.exit_code == 2 and "alpha-audit.yaml:2" in bad.output
        assert "is not a pipeline" in bad.output
    finally:
        os.chdir(old)


def test_theme_pipeline_is_used_when_nothing_else_says(project: Path) -> None:
    (project / "theme.yaml").write_text(
        'pipeline: css\ncanvases: [{name: white, color: "#ffffff"}]\n'
    )
    code, doc, output = check(project, "--alpha", "0.5", "--exit-zero")
    assert code == 0 and doc["pipeline"] == "css", output


def test_pair_shows_linear_and_css_side_by_side() -> None:
    table = runner.invoke(app, ["pair", "#ee7733", "--on", "white", "-a", "0.6", "-a", "1.4"])
    assert table.exit_code == 0
    (line,) = [row for row in table.stdout.splitlines() if "#f5ad85" in row]
    assert "#f5bdad" in line and "1.645 → 1.875" in line  # both as shipped
    assert max(len(row) for row in table.stdout.splitlines()) <= 80
    doc = json.loads(
        runner.invoke(
            app, ["pair", "#ee7733", "--on", "white", "-a", "0.6", "-a", "1.4", "-f", "json"]
        ).stdout
    )
    assert [(r["output"], r["css_output"]) for r in doc["rows"]] == [
        ("#f5bdad", "#f5ad85"),
        ("#e70000", None),
    ]


def test_table_names_the_worst_drift(project: Path) -> None:
    result = runner.invoke(
        app, ["check", str(project / "theme.yaml"), str(project / "set.yaml"), "--exit-zero"]
    )
    text = " ".join(result.stdout.split())
    assert "colour drift up to 29.5 CIEDE2000" in text
