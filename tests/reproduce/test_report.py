"""Renderers: the report never hides a mismatch; JSON keys and schema."""

from __future__ import annotations

import json
from dataclasses import replace

import pytest

from alpha_audit.model import Canvas, Theme
from alpha_audit.reproduce import BroadGridResult
from alpha_audit.reproduce.paper import PAPER, matches_printed
from alpha_audit.reproduce.report import SCHEMA, alpha_key, reproduction_json, reproduction_markdown
from alpha_audit.reproduce.run import Reproduction, Settings

THEME = Theme("t", (Canvas("white", "#ffffff", "light"),))


def broad(alpha: float, increase: int) -> BroadGridResult:
    n = 17**3 * 33**3
    return BroadGridResult(
        alpha=alpha,
        source_levels=17,
        background_levels=33,
        combinations=n,
        increase=increase,
        decrease=n // 10,
        loss_le_0_25=n // 20,
        max_loss=0.5,
        worst_source=(0.0, 0.0, 0.8125),
        worst_background=(1.0, 1.0, 0.0),
        worst_contrast={1.0: 10.0, alpha: 9.5},
    )


def run_with(*results: BroadGridResult) -> Reproduction:
    return Reproduction(THEME, Settings.paper(), False, (1.1,), broad_grid=results)


def test_a_matching_value_is_marked_and_a_mismatch_is_not_hidden() -> None:
    n = 17**3 * 33**3
    exact = round(0.903672 * n)  # rounds to the printed 90.3672 %
    good = reproduction_markdown(run_with(broad(1.1, exact)))
    assert "| alpha 1.1: increase % | 90.3672 | 90.3672 | yes (Table 1) | **yes** |" in good
    bad = reproduction_markdown(run_with(broad(1.1, exact - 2000)))
    assert "| alpha 1.1: increase % | 90.3672 | 90.3661 | yes (Table 1) | **NO** |" in bad
    assert "| alpha 1.1: maximum loss | 0.4655 | 0.5000 | yes (Section 4.2) | **NO** |" in bad


def test_values_without_a_printed_counterpart_are_not_compared() -> None:
    text = reproduction_markdown(run_with(broad(1.3, 10)))
    assert "| alpha 1.3: increase % | — |" in text
    assert "no printed value" in text


def test_quick_grids_are_not_compared_with_the_paper() -> None:
    small = replace(broad(1.1, 10), source_levels=5, background_levels=9, combinations=5**3 * 9**3)
    text = reproduction_markdown(run_with(small))
    assert "**NO**" not in text and "**yes**" not in text


def test_json_document() -> None:
    doc = json.loads(reproduction_json(run_with(broad(1.1, 5), broad(1.4, 6))))
    assert doc["schema"] == SCHEMA == "alpha-audit.reproduce/1"
    assert set(doc["broad_grid"]) == {
        "source_levels", "background_levels", "combinations", "1.1", "1.4",
    }  # fmt: skip
    assert doc["broad_grid"]["1.4"]["increase"] == 6
    assert doc["broad_grid"]["1.1"]["worst"]["contrast"] == {"1.0": 10.0, "1.1": 9.5}
    ours = doc["broad_grid"]["1.1"]["increase_pct"]
    assert doc["paper"]["broad_grid"]["1.1"]["increase_pct"] == {
        "value": 90.3672, "decimals": 4, "where": "Table 1", "setup": "broad-grid",
        "ours": ours, "comparable": True, "why_not_comparable": None, "matches": False,
    }  # fmt: skip
    assert "full_gamut" not in doc
    # A printed value this run did not compute is listed, never compared.
    assert doc["paper"]["full_gamut"]["1.1"]["increase_pct"] | {"value": None} == {
        "value": None, "decimals": 4, "where": "abstract, Table 1", "setup": "full-gamut",
        "ours": None, "comparable": False, "why_not_comparable": "not computed", "matches": None,
    }  # fmt: skip


@pytest.mark.parametrize(
    ("value", "printed", "expected"),
    [
        (90.36716, PAPER["broad_grid"]["1.1"]["increase_pct"], True),
        (90.36726, PAPER["broad_grid"]["1.1"]["increase_pct"], False),
        (99.3449, PAPER["broad_grid"]["1.1"]["loss_le_0_25_pct"], True),
        (99.3349, PAPER["broad_grid"]["1.1"]["loss_le_0_25_pct"], False),
    ],
)
def test_matches_printed(value: float, printed, expected: bool) -> None:
    assert matches_printed(value, printed) is expected


def test_alpha_keys() -> None:
    assert [alpha_key(a) for a in (1, 1.1, 0.025, 2.0)] == ["1.0", "1.1", "0.025", "2.0"]
