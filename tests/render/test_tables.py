"""Every table at 60, 80 and 200 columns keeps every figure whole.

The figures expected in the text are worked out here from the JSON document of
the same run (per-canvas means and counts from its rows, contrast pairs, hex
codes), not read back from the table, so a cut figure (``#10b9…``, ``2.0…``)
or a vanished column fails.  Names (canvas, icon) may wrap; figures may not.
"""

from __future__ import annotations

import json
import re
from collections import defaultdict
from collections.abc import Iterable
from functools import cache
from pathlib import Path
from typing import Any

import pytest

from alpha_audit.gate import evaluate
from alpha_audit.load.iconset import load_iconset
from alpha_audit.load.theme import load_theme
from alpha_audit.model import Canvas, Icon, IconSet, Theme
from alpha_audit.pair import pair_report
from alpha_audit.policy import Policy
from alpha_audit.render import CheckFormat, PairFormat, SuggestFormat
from alpha_audit.render.common import RenderOptions, wrap_name
from alpha_audit.render.suggest import suggest_document
from alpha_audit.render.table import MAX_FINDINGS
from alpha_audit.results import CheckReport
from alpha_audit.rows import audit
from alpha_audit.suggest import suggest

ROOT = Path(__file__).resolve().parents[2]
WIDTHS = (60, 80, 200)


def _whole(token: str, text: str) -> bool:
    """``token`` appears with no digit, point or hex letter glued to either side."""
    return re.search(rf"(?<![\w.]){re.escape(token)}(?![\w.])", text) is not None


def _missing(tokens: Iterable[str], text: str) -> list[str]:
    return sorted({t for t in tokens if not _whole(t, text)})


@cache
def material3_report() -> CheckReport:
    """Material 3 (canvas names up to 31 characters) and the vibrant set at alpha 1.3."""
    theme = load_theme(ROOT / "themes" / "material3.yaml")
    iconset = load_iconset(ROOT / "examples" / "vibrant" / "iconset.yaml", root=ROOT)
    result = audit(theme, iconset, alpha=1.3)
    return CheckReport(audits=(result,), gate=evaluate([result], Policy()))


@cache
def loss_report() -> CheckReport:
    """A set with contrast losses (alpha above 1 on mid-grey canvases) and long names."""
    theme = Theme(
        "grey-long-names-theme",
        (
            Canvas("neutral-mid-grey-surface-container-highest", "#777777", "light"),
            Canvas("neutral-dark-grey-surface-container-lowest", "#444444", "dark"),
        ),
    )
    icons = (
        Icon("notification-bell-outline-filled", Path("a.svg"), "#7a7a7a", 1.6),
        Icon("arrow-right-circle-outline", Path("b.svg"), "#0000cc", 1.6),
        Icon("warning-triangle", Path("c.svg"), "#aa0000", 1.6),
    )
    result = audit(theme, IconSet("long", icons))
    return CheckReport(audits=(result,), gate=evaluate([result], Policy()))


def _check_tokens(report: CheckReport) -> set[str]:
    """Figures the check table shows, computed from the run's JSON document."""
    doc = json.loads(CheckFormat.JSON.renderer()(report, RenderOptions()))
    rows = doc["rows"]
    by_canvas: dict[str, list[dict[str, Any]]] = defaultdict(list)
    for row in rows:
        by_canvas[row["canvas"]].append(row)
    tokens = {c["color"] for c in doc["theme"]["canvases"]}
    for canvas_rows in by_canvas.values():
        gains = [r["gain"] for r in canvas_rows]
        tokens.add(f"{sum(gains) / len(gains):+.2f}")
        before = sum(r["passes_ref"] for r in canvas_rows)
        after = sum(r["passes"] for r in canvas_rows)
        tokens.add(f"{before}→{after}/{len(canvas_rows)}")
    for row in rows:  # each section lists a finding per (colour, canvas): below the cap here
        if row["loss"] or row["newly_passes"] or row["newly_fails"]:
            tokens.add(f"{row['contrast_ref']:.3f} → {row['contrast']:.3f}")
            tokens.add(row["source"])
        if row["loss"]:
            tokens.add(f"{row['gain']:+.4f}")
    # "Still below" lists the MAX_FINDINGS lowest (colour, canvas) groups.
    below = sorted({(r["contrast"], r["canvas"], r["source"]) for r in rows if not r["passes"]})
    tokens |= {f"{c:.3f}" for c, _, _ in below[:MAX_FINDINGS]}
    for c in doc["collisions"]:
        tokens |= {c["output"], *c["sources"]}
    for s in doc["separation"]:
        tokens.add(f"{s['set_min_delta_e_ref']:.1f}→{s['min_delta_e']:.1f}")
    summary = doc["summary"]
    tokens |= {f"{summary['mean_gain']:+.3f}", f"{summary['max_loss']:.4f}"}
    return tokens


@pytest.mark.parametrize("make", [material3_report, loss_report], ids=["material3", "losses"])
@pytest.mark.parametrize("width", WIDTHS)
def test_check_table_keeps_every_figure_whole(make: Any, width: int) -> None:
    report = make()
    text = CheckFormat.TABLE.renderer()(report, RenderOptions(width=width))
    assert max(map(len, text.splitlines())) <= width
    assert "…" not in text.split("Gate")[0].replace("… and", "")  # nothing cut with an ellipsis
    assert not _missing(_check_tokens(report), text)


def test_the_loss_fixture_has_what_it_claims() -> None:
    rows = list(loss_report().audits[0].rows())
    assert any(r.loss for r in rows) and any(not r.passes for r in rows)


def test_at_80_columns_every_check_column_stays() -> None:
    text = CheckFormat.TABLE.renderer()(material3_report(), RenderOptions(width=80))
    header = next(line for line in text.splitlines() if line.split()[:2] == ["canvas", "bg"])
    assert header.split() == ["canvas", "bg", "gain", "≥3:1", "new", "loss", "coll", "min", "ΔE"]
    # The canvas names keep their line at 80 columns; the icon lists beside them wrap first.
    findings = text.split("Newly reach")[1]
    assert "dark-surface-container-highest " in findings


@pytest.mark.parametrize("width", WIDTHS)
def test_suggest_table_keeps_every_alpha_whole(width: int) -> None:
    theme = load_theme(ROOT / "themes" / "material3.yaml")
    iconset = load_iconset(ROOT / "examples" / "vibrant" / "iconset.yaml", root=ROOT)
    result = suggest(audit(theme, iconset), Policy())
    doc = suggest_document(result)
    p = doc["precision"]
    tokens = {f"{c['alpha']:.{p}f}" for c in doc["per_canvas"] if c["alpha"] is not None}
    for entry in (*doc["per_color"], *doc["per_icon"], *doc["per_canvas"]):
        if entry.get("alpha") is not None:
            tokens.add(f"{entry['alpha']:.{p}f}")
        limit = entry["limited_by"]
        if limit is not None:
            tokens.add(f"{limit['at']:.6f}")
    tokens |= {c["source"] for c in doc["per_color"]}
    text = SuggestFormat.TABLE.renderer()(result, RenderOptions(width=width))
    assert max(map(len, text.splitlines())) <= width
    assert not _missing(tokens, text)


@pytest.mark.parametrize("width", WIDTHS)
def test_pair_table_keeps_every_figure_whole(width: int) -> None:
    report = pair_report("#ee7733", ["#ffffff", "#0d1117", "#10b981"], [1.0, 1.4, 2.5])
    doc = json.loads(PairFormat.JSON.renderer()(report, RenderOptions()))
    tokens = set()
    for r in doc["rows"]:
        tokens |= {r["background"], r["output"], f"{r['alpha']:g}", f"{r['gain']:+.3f}"}
        tokens |= {f"{r['contrast_ref']:.3f} → {r['contrast']:.3f}"}
        tokens.add(f"{r['delta_e_from_source']:.2f}")
    text = PairFormat.TABLE.renderer()(report, RenderOptions(width=width))
    assert "clipped" in text  # the last column stays
    assert not _missing(tokens, text)


@pytest.mark.parametrize("width", WIDTHS)
def test_themes_table_keeps_every_hex_whole(width: int) -> None:
    from alpha_audit.load.theme import load_bundled_themes
    from alpha_audit.render.common import to_text
    from alpha_audit.render.themes import _table

    themes = load_bundled_themes()
    text = to_text(_table(themes), RenderOptions(width=width))
    tokens = {c.color for _, theme in themes for c in theme.canvases}
    assert not _missing(tokens, text)


@pytest.mark.parametrize(
    ("text", "width", "lines"),
    [
        ("surface-container-lowest", 19, ["surface-container-", "lowest"]),
        ("surface-container-lowest", 80, ["surface-container-lowest"]),
        ("a b c", 3, ["a b", "c"]),
        ("abcdefgh", 3, ["abc", "def", "gh"]),  # one long word folds, nothing dropped
        ("", 5, [""]),
    ],
)
def test_wrap_name_breaks_after_separators_and_drops_nothing(
    text: str, width: int, lines: list[str]
) -> None:
    out = wrap_name(text, width)
    assert out == lines
    assert all(len(line) <= width for line in out)
    assert "".join(out).replace(" ", "") == text.replace(" ", "")


@cache
def reproduction() -> Any:
    from alpha_audit.reproduce.run import Experiment, reproduce

    theme = load_theme(ROOT / "themes" / "material3.yaml")
    experiments = [Experiment.FULL_GAMUT, Experiment.SWEEP, Experiment.PALETTE]
    return reproduce(theme, only=experiments, quick=True)


@pytest.mark.parametrize("width", WIDTHS)
def test_reproduce_tables_keep_every_figure_whole(width: int) -> None:
    from alpha_audit.reproduce.formats import ReproduceFormat

    run = reproduction()
    tokens: set[str] = set()
    for fg in run.full_gamut:
        for c in (fg.total, fg.group("light"), fg.group("dark")):
            tokens |= {
                f"{v:.4f}"
                for v in (c.increase_pct, c.decrease_pct, c.unchanged_pct, c.mean_change,
                          c.newly_reach_pct, c.mean_difference_change, c.mean_exclusion_change)
            }  # fmt: skip
    pal = run.palette
    tokens |= {f"{n:,} of {pal.random_combinations:,}" for n in pal.random_collisions.values()}
    tokens |= {str(n) for n in (*pal.smaller.values(), *pal.collisions.values())}
    text = ReproduceFormat.TABLE.renderer()(run, RenderOptions(width=width))
    assert max(map(len, text.splitlines())) <= width
    assert not _missing(tokens, text)
