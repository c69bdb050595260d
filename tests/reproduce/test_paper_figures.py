"""``alpha-audit reproduce`` with no ``--theme`` prints the paper's full-gamut and palette figures.

The expected values are the paper's, as printed (abstract, Table 1, Sections
4.2 and 4.3), not our own output: on the paper's sixteen canvases (the bundled
``paper16``) every one must come out to the printed digit, in the table on
stdout, in ``results.json`` and in ``report.md``.  One run at the paper's sizes
(all 256**3 sources, 65,536 random pairs) takes a few seconds.
"""

from __future__ import annotations

import json
import re
from typing import Any

import pytest
import typer
from typer.testing import CliRunner

from alpha_audit.cli.reproduce import reproduce_command

app = typer.Typer()
app.command("reproduce")(reproduce_command)


@app.command("noop")
def _noop() -> None:  # a second command keeps "reproduce" a subcommand, as in the real CLI
    """Nothing."""


# (alpha, table label, JSON section and key, the paper's printed value as printed)
FULL_GAMUT = [
    ("1.1", "increase %", "increase_pct", "99.8145"),  # abstract, Table 1
    ("1.1", "decrease %", "decrease_pct", "0.1853"),  # Table 1
    ("1.4", "increase %", "increase_pct", "99.6132"),  # Table 1
    ("1.4", "decrease %", "decrease_pct", "0.3867"),  # Table 1
    ("1.1", "mean change", "mean_change", "0.9783"),  # Section 4.2
    ("1.1", "newly 3:1, % of all", "newly_reach_pct", "4.8346"),  # abstract, 4.2
    ("1.1", "Difference, mean", "mean_difference_change", "-1.3050"),  # Section 4.2
    ("1.1", "Exclusion, mean", "mean_exclusion_change", "-1.3104"),  # Section 4.2
]
PALETTE = [  # Section 4.3
    ("1.1", "smaller CIEDE2000", "smaller", "32"),
    ("1.1", "collisions", "collisions", "0"),
    ("1.4", "smaller CIEDE2000", "smaller", "88"),
    ("1.4", "collisions", "collisions", "8"),
    ("1.1", "random collisions", "random_collisions", "617"),
    ("1.4", "random collisions", "random_collisions", "15,098"),
]


@pytest.fixture(scope="module")
def run(tmp_path_factory: pytest.TempPathFactory) -> tuple[str, dict[str, Any], str]:
    """One default run of the two experiments: (table on stdout, results.json, report.md)."""
    out = tmp_path_factory.mktemp("repro") / "out"
    result = CliRunner().invoke(
        app,
        ["reproduce", "--only", "full-gamut", "--only", "palette", "--out", str(out)],
        env={"COLUMNS": "80", "NO_COLOR": "1"},
    )
    assert result.exit_code == 0, result.output
    doc = json.loads((out / "results.json").read_text(encoding="utf-8"))
    return result.stdout, doc, (out / "report.md").read_text(encoding="utf-8")


def _table_row(stdout: str, alpha: str, label: str, printed: str) -> re.Match[str] | None:
    """The table line ``alpha  label  paper  ours  yes`` with both columns at the printed value."""
    value = re.escape(printed)
    pattern = rf"^\s*{re.escape(alpha)}\s+{re.escape(label)}\s+{value}\s+{value}\s+yes\s*$"
    return re.search(pattern, stdout, flags=re.MULTILINE)


@pytest.mark.parametrize(("alpha", "label", "key", "printed"), FULL_GAMUT + PALETTE)
def test_the_table_prints_the_papers_digits(run, alpha, label, key, printed) -> None:
    stdout, _, _ = run
    assert _table_row(stdout, alpha, label, printed), f"no matching row for {alpha} {label}"


@pytest.mark.parametrize(("alpha", "label", "key", "printed"), FULL_GAMUT)
def test_results_json_full_gamut(run, alpha, label, key, printed) -> None:
    _, doc, _ = run
    assert doc["theme"]["name"] == "paper16" and len(doc["theme"]["canvases"]) == 16
    assert doc["full_gamut"]["levels"] == 256
    ours = doc["full_gamut"][alpha]["all"][key]
    assert f"{ours:.4f}" == printed
    paper = doc["paper"]["full_gamut"][alpha][key]
    assert paper["comparable"] is True and paper["matches"] is True
    assert paper["why_not_comparable"] is None and paper["ours"] == ours


@pytest.mark.parametrize(("alpha", "label", "key", "printed"), PALETTE)
def test_results_json_palette(run, alpha, label, key, printed) -> None:
    _, doc, _ = run
    palette = doc["palette"]
    assert (palette["combinations"], palette["random"]["combinations"]) == (336, 1_048_576)
    assert (palette["random"]["pairs"], palette["random"]["seed"]) == (65536, 20260913)
    ours = (
        palette["random"]["collisions"][alpha]
        if key == "random_collisions"
        else palette[alpha][key]
    )
    assert f"{ours:,}" == printed
    assert doc["paper"]["palette"][alpha][key]["matches"] is True


def test_every_printed_figure_is_comparable_and_matches(run) -> None:
    stdout, doc, report = run
    figures = [v for group in doc["paper"]["full_gamut"].values() for v in group.values()]
    figures += [v for group in doc["paper"]["palette"].values() for v in group.values()]
    assert len(figures) == 16
    assert all(v["comparable"] and v["matches"] for v in figures)
    assert "16 of the 16 printed figures comparable in this run match every printed digit" in (
        " ".join(stdout.split())
    )
    assert report.count("| **yes** |") == 16 and "**NO**" not in report
    for _, _, _, printed in FULL_GAMUT:
        value = re.escape(printed)
        assert re.search(rf"\| {value} \| {value} \| yes \([^)]*\) \| \*\*yes\*\* \|", report)
