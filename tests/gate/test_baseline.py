"""Baselines: record today's findings, fail only on new ones, report the ones that went away."""

from __future__ import annotations

import json
import os
from pathlib import Path

import pytest
from typer.testing import CliRunner

from alpha_audit.baseline import parse_baseline
from alpha_audit.cli import app
from alpha_audit.errors import InputError
from alpha_audit.gate import baseline_document, evaluate
from alpha_audit.model import Canvas, Icon, IconSet, Theme
from alpha_audit.policy import Policy
from alpha_audit.rows import audit

# fill="currentColor": the manifest colour is audited (an unfilled rect is SVG's default black).
SVG = (
    '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 24 24">'
    '<rect width="9" height="9" fill="currentColor"/></svg>'
)


def _audit(*icons: tuple[str, str]):
    theme = Theme("t", (Canvas("sun", "#ffff00"), Canvas("paper", "#ffffff")))
    return audit(theme, IconSet("s", tuple(Icon(n, f"{n}.svg", c, 1.4) for n, c in icons)))


def test_round_trip_matches_by_icon_and_rule() -> None:
    before = evaluate([_audit(("deep", "#0000cf"))], Policy())
    assert not before.passed
    doc = baseline_document(before)
    assert doc["entries"] == [{"theme": "t", "iconset": "s", "rule": "loss", "icons": ["deep"]}]
    keys = parse_baseline(json.dumps(doc), Path("b.json"))
    # Same finding with other numbers (a different blue) is still the baselined one.
    after = evaluate([_audit(("deep", "#0000c0"), ("ok", "#ee7733"))], Policy(), baseline=keys)
    assert after.passed and [f.baselined for f in after.findings] == [True]
    # A new icon with a loss fails; the old entry is not stale.
    worse = evaluate([_audit(("deep", "#0000cf"), ("navy", "#000080"))], Policy(), baseline=keys)
    assert [f.icons for f in worse.failures] == [("navy",)] and not worse.stale
    fixed = evaluate([_audit(("deep", "#ee7733"))], Policy(), baseline=keys)
    assert fixed.passed and fixed.stale == (("t", "s", "loss", ("deep",)),)


def _legacy(*cells: tuple[str, str]) -> str:
    """A baseline/1 file (per-canvas entries, before findings were folded over canvases)."""
    entries = [
        {"theme": "t", "iconset": "s", "rule": r, "canvas": c, "icons": ["deep"]} for r, c in cells
    ]
    return json.dumps({"schema": "alpha-audit.baseline/1", "entries": entries})


def test_a_per_canvas_baseline_covers_a_folded_finding_only_on_every_canvas() -> None:
    result = _audit(("deep", "#0000cf"))  # loses contrast on sun only
    (finding,) = evaluate([result], Policy()).failures
    assert finding.canvases == ("sun",)
    both = parse_baseline(_legacy(("loss", "sun"), ("loss", "paper")), Path("b.json"))
    assert both.legacy
    gate = evaluate([result], Policy(), baseline=both)
    assert gate.passed and gate.stale == ()  # the paper entry still names this root cause
    other = parse_baseline(_legacy(("loss", "paper")), Path("b.json"))
    gate = evaluate([result], Policy(), baseline=other)
    assert not gate.passed  # sun was never accepted
    assert gate.stale == ()  # ... but the entry still names a finding that occurs
    gone = parse_baseline(_legacy(("newly-failing", "sun")), Path("b.json"))
    assert evaluate([result], Policy(), baseline=gone).stale == (
        ("t", "s", "newly-failing", ("deep",)),
    )


@pytest.mark.parametrize(
    "text",
    [
        "",
        "[]",
        '{"schema": "other"}',
        '{"schema": "alpha-audit.baseline/1", "entries": [1]}',
        '{"schema": "alpha-audit.baseline/1", "entries": [{"theme": "t"}]}',
        '{"schema": "alpha-audit.baseline/2", "entries": [{"theme": "t", "iconset": "s"}]}',
    ],
)
def test_bad_baseline(text: str) -> None:
    with pytest.raises(InputError, match="not an alpha-audit baseline"):
        parse_baseline(text, Path("b.json"))


def test_cli_write_then_use_baseline(tmp_path: Path) -> None:
    (tmp_path / ".git").mkdir()
    (tmp_path / "a.svg").write_text(SVG)
    (tmp_path / "set.yaml").write_text('icons: "*.svg"\ncolor: "#0000cf"\nalpha: 1.4\n')
    (tmp_path / "theme.yaml").write_text('canvases: [{name: sun, color: "#ffff00"}]\n')
    old = Path.cwd()
    os.chdir(tmp_path)
    try:
        runner = CliRunner()
        args = ["check", "theme.yaml", "set.yaml"]
        assert runner.invoke(app, args).exit_code == 1
        wrote = runner.invoke(app, [*args, "--write-baseline", "baseline.json"])
        assert wrote.exit_code == 0 and "wrote baseline" in wrote.output
        assert runner.invoke(app, [*args, "--baseline", "baseline.json"]).exit_code == 0
        (tmp_path / "b.svg").write_text(SVG)  # a new icon, a new loss
        new = runner.invoke(app, [*args, "--baseline", "baseline.json", "-f", "json"])
        assert new.exit_code == 1
        failures = json.loads(new.stdout)["gate"]["failures"]
        assert [f["icons"] for f in failures] == [["b"]]
        missing = runner.invoke(app, [*args, "--baseline", "nope.json"])
        assert missing.exit_code == 2 and "--write-baseline" in missing.output
    finally:
        os.chdir(old)


@pytest.mark.parametrize("fmt", ["table", "markdown"])
def test_stale_count_is_grammatical(fmt: str) -> None:
    from alpha_audit.render import RenderOptions, render_check
    from alpha_audit.results import CheckReport

    result = _audit(("deep", "#ee7733"))
    one = (("t", "s", "loss", ("deep",)),)
    two = (*one, ("t", "s", "newly-failing", ("deep",)))
    texts = []
    for keys in (one, two):
        report = CheckReport((result,), evaluate([result], Policy(), baseline=keys))
        texts.append(render_check(report, fmt, RenderOptions(width=200)))
    assert "1 baseline entry no longer occurs" in texts[0]
    assert "entries" not in texts[0]
    assert "2 baseline entries no longer occur" in texts[1]


def test_write_baseline_works_when_the_config_names_it_and_calls_nothing_stale(
    tmp_path: Path,
) -> None:
    (tmp_path / ".git").mkdir()
    (tmp_path / "a.svg").write_text(SVG)
    (tmp_path / "set.yaml").write_text('icons: "*.svg"\ncolor: "#0000cf"\nalpha: 1.4\n')
    (tmp_path / "theme.yaml").write_text('canvases: [{name: sun, color: "#ffff00"}]\n')
    (tmp_path / "alpha-audit.yaml").write_text(
        "theme: theme.yaml\niconset: set.yaml\nbaseline: alpha-audit-baseline.json\n"
    )
    old = Path.cwd()
    os.chdir(tmp_path)
    try:
        runner = CliRunner()
        missing = runner.invoke(app, ["check"])
        assert missing.exit_code == 2 and "--write-baseline" in missing.output
        for extra in ([], ["--force"]):  # the first write, then writing it again over itself
            wrote = runner.invoke(
                app,
                ["check", "--write-baseline", "alpha-audit-baseline.json", *extra, "-f", "json"],
            )
            assert wrote.exit_code == 0, wrote.output
            gate = json.loads(wrote.stdout)["gate"]
            assert gate["passed"] and gate["stale_baseline"] == []
            assert [f["icons"] for f in gate["baselined"]] == [["a"]]
        assert runner.invoke(app, ["check"]).exit_code == 0
    finally:
        os.chdir(old)
