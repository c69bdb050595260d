"""Issue 18: every number of a report comes from the same paint rows, under the chosen pipeline.

The checks recompute the report's figures from the JSON rows alone, and the
css pipeline's colours with an independent implementation (coloraide's CSS
Color 4 sRGB, colour-science's CIEDE2000), never with alpha-audit's own code.
"""

from __future__ import annotations

import json
import statistics
import warnings
from pathlib import Path

import numpy as np
import pytest
from coloraide import Color

from alpha_audit.fixes import with_fixes
from alpha_audit.gate import evaluate
from alpha_audit.load.config import ProjectConfig
from alpha_audit.model import Canvas, Icon, IconSet, Theme
from alpha_audit.pipeline import check_project
from alpha_audit.policy import Policy
from alpha_audit.render import CheckFormat, RenderOptions
from alpha_audit.render.table import render_report as table
from alpha_audit.results import CheckReport
from alpha_audit.rows import audit
from alpha_audit.rules import Rule

with warnings.catch_warnings():
    warnings.simplefilter("ignore")
    import colour

STROKE = '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 24 24" fill="none" stroke="{}"\n' + (
    ' stroke-width="3"><path d="M4 4 L20 20 M20 4 L4 20"/></svg>\n'
)


def _project(tmp_path: Path, manifest: str, theme: str, svgs: dict[str, str]) -> ProjectConfig:
    (tmp_path / ".git").mkdir()
    (tmp_path / "svg").mkdir()
    for name, text in svgs.items():
        (tmp_path / "svg" / f"{name}.svg").write_text(text)
    (tmp_path / "iconset.yaml").write_text(manifest)
    (tmp_path / "theme.yaml").write_text(theme)
    return ProjectConfig(themes=(tmp_path / "theme.yaml",), iconsets=(tmp_path / "iconset.yaml",))


WHITE = (
    "name: w\ncanvases:\n  - {name: white, color: '#ffffff'}\n  - {name: ink, color: '#0d1117'}\n"
)


def _json(report: CheckReport) -> dict:  # type: ignore[type-arg]
    return json.loads(CheckFormat.JSON.renderer()(report, RenderOptions()))  # type: ignore[no-any-return]


def _summary_from_rows(rows: list[dict]) -> dict:  # type: ignore[type-arg]
    gains = [r["contrast"] - r["contrast_ref"] for r in rows]
    losses = [g for g in gains if g < -1e-10]
    n = len(rows)
    return {
        "combinations": n,
        "increase_pct": 100 * sum(g > 1e-10 for g in gains) / n,
        "decrease_pct": 100 * len(losses) / n,
        "mean_gain": statistics.fmean(gains),
        "newly_pass": sum(r["newly_passes"] for r in rows),
        "newly_fail": sum(r["newly_fails"] for r in rows),
        "losses": len(losses),
        "max_loss": -min(losses) if losses else 0.0,
        "max_drift": max(r["drift"] for r in rows),
    }


def test_a_red_stroke_is_reported_as_red_everywhere(tmp_path: Path) -> None:
    """The issue's case: a red-stroked icon in a manifest whose colour is blue, alpha 1.2."""
    project = _project(
        tmp_path,
        "name: s\nicons: svg/*.svg\ncolor: '#0969da'\nalpha: 1.2\n",
        WHITE,
        {"stop": STROKE.format("#ff0000")},
    )
    report = check_project(project)
    doc = _json(report)
    (white, _ink) = doc["rows"]
    assert white["source"] == white["paint"] == "#ff0000"  # drawn red, not the manifest's blue
    summary = doc["summary"]
    for key, value in _summary_from_rows(doc["rows"]).items():
        assert summary[key] == pytest.approx(value, abs=1e-12), key
    # The contrast reported is red's (WCAG 2.2 with the pinned weights), not the blue's.
    red_y = 0.2126  # linear sRGB (1, 0, 0)
    assert white["contrast_ref"] == pytest.approx(1.05 / (red_y + 0.05), rel=1e-12)
    # The table shows the same red and the same mean gain; the hard-coded paint is a note.
    text = table(report, RenderOptions(width=120))
    assert "#0969da" not in text and "#ff0000" in text
    assert f"mean {summary['mean_gain']:+.3f}" in text
    assert any(w.rule is Rule.FIXED_COLOUR for w in report.gate.warnings)
    assert "fixed-colour" in text and "hard-coded" in text


@pytest.mark.parametrize(("pipeline", "alpha"), [("linear", 1.2), ("linear", 0.6), ("css", 0.6)])
def test_summary_and_table_come_from_the_json_rows(pipeline: str, alpha: float) -> None:
    theme = Theme(
        "t",
        (Canvas("white", "#ffffff"), Canvas("grey", "#777777"), Canvas("ink", "#0d1117")),
    )
    colours = ["#ee7733", "#cc3311", "#0077bb", "#33bbee", "#bbbbbb"]
    icons = IconSet(
        "s",
        tuple(Icon(f"i{k}", Path(f"i{k}.svg"), c, alpha) for k, c in enumerate(colours * 2)),
    )
    result = audit(theme, icons, pipeline=pipeline)  # type: ignore[arg-type]
    report = with_fixes(CheckReport((result,), evaluate([result], Policy())))
    doc = _json(report)
    rows = doc["rows"]
    assert {r["pipeline"] for r in rows} == {pipeline}
    for key, value in _summary_from_rows(rows).items():
        assert doc["summary"][key] == pytest.approx(value, abs=1e-12), key
    # Per canvas, as the table prints it: mean gain, passing before -> after, losses.
    text = table(report, RenderOptions(width=140))
    for c in theme.canvases:
        mine = [r for r in rows if r["canvas"] == c.name]
        gain = statistics.fmean(r["gain"] for r in mine)
        before, after = sum(r["passes_ref"] for r in mine), sum(r["passes"] for r in mine)
        line = next(ln for ln in text.splitlines() if ln.strip().startswith(c.name))
        assert f"{gain:+.2f}" in line and f"{before}→{after}/{len(mine)}" in line


def _de00(a: str, b: str) -> float:
    lab = [
        colour.XYZ_to_Lab(
            Color(h).convert("xyz-d65").coords(),
            colour.CCS_ILLUMINANTS["CIE 1931 2 Degree Standard Observer"]["D65"],
        )
        for h in (a, b)
    ]
    return float(colour.delta_E(lab[0] * 100 / 100, lab[1], method="CIE 2000"))


def test_css_separation_and_collisions_are_the_css_drawn_colours() -> None:
    """#ee7733 and #cc3311 at 0.6 on white: css draws #f5ad85 and #e08570 (CIEDE2000 12.24).

    The issue quoted 12.7 for the pair; colour-science and coloraide both give 12.2397.
    """
    theme = Theme("w", (Canvas("white", "#ffffff"),))
    icons = IconSet(
        "s",
        (
            Icon("o", Path("o.svg"), "#ee7733", 0.6, "orange"),
            Icon("r", Path("r.svg"), "#cc3311", 0.6, "red"),
        ),
        palette={"orange": "#ee7733", "red": "#cc3311"},
    )
    css, linear = audit(theme, icons, pipeline="css"), audit(theme, icons)
    outputs = {r.icon: r.output for r in css.rows()}
    # Independently: the browser's blend of encoded values at 0.6, rounded to 8 bits.
    for name, source in (("o", "#ee7733"), ("r", "#cc3311")):
        mixed = Color.mix(Color("#ffffff"), Color(source), 0.6, space="srgb").to_string(hex=True)
        assert outputs[name] == mixed
    assert outputs == {"o": "#f5ad85", "r": "#e08570"}
    (sep,) = css.separations
    assert sep.delta_e == pytest.approx(_de00("#f5ad85", "#e08570"), abs=1e-6)
    assert sep.delta_e == pytest.approx(12.24, abs=0.005)
    (lin,) = linear.separations
    assert lin.delta_e != pytest.approx(sep.delta_e, abs=0.1)  # the pipelines draw differently
    # Confusion judges the same drawn colours: under css the pair stays apart (12.7 > 10).
    policy = Policy(rules=frozenset({Rule.CONFUSION}))
    assert evaluate([css], policy).passed
    assert not evaluate([linear], policy).passed  # the linear pipeline pulls them to < 10
    assert np.all(css.output_codes[0, 0] != css.output_codes[1, 0])  # no collision either
