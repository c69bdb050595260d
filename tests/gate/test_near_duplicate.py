"""Issue 28 item 2: collisions that alpha made, and near duplicates.

``new-collision`` gates only colours told apart at alpha 1 (CIEDE2000 between two of
them, as they ship at alpha 1, at least ``near-duplicate-delta-e``, default 1.0);
closer colours are listed once as ``near-duplicate``, never gated by default and never
a limit of ``suggest``.  Distances are checked against coloraide's CIEDE2000.
"""

from __future__ import annotations

import itertools

import numpy as np
import pytest
from coloraide import Color
from hypothesis import given, settings
from hypothesis import strategies as st

from alpha_audit.color import hex_to_linear, linear_to_lab
from alpha_audit.gate import evaluate
from alpha_audit.model import Canvas, Icon, IconSet, Theme
from alpha_audit.policy import NEAR_DUPLICATE_DELTA_E, Policy
from alpha_audit.rows import audit, widest_delta_e, widest_delta_e_many
from alpha_audit.rules import RULES, Level, Rule
from alpha_audit.suggest import suggest

LIGHT = Theme("light", (Canvas("white", "#ffffff"), Canvas("muted", "#f6f8fa")))
DARK = Theme("dark", (Canvas("ink", "#0d1117"),))


def _de(a: str | Color, b: str | Color) -> float:
    return float(Color(a).delta_e(Color(b), method="2000"))


def _brands(*colours: str, alpha: float = 1.1) -> IconSet:
    """Logos each in its own colour (no palette names: brand colours are no roles)."""
    return IconSet(
        "brands", tuple(Icon(f"b{k}", f"b{k}.svg", c, alpha) for k, c in enumerate(colours))
    )


def test_the_rule_is_reported_not_gated_by_default() -> None:
    spec = RULES[Rule.NEAR_DUPLICATE]
    assert spec.default is Level.WARN and NEAR_DUPLICATE_DELTA_E == 1.0
    assert Rule.NEAR_DUPLICATE not in Policy().rules and Rule.NEAR_DUPLICATE in Policy().reported


def test_two_brands_0_017_apart_are_one_near_duplicate_not_a_new_collision() -> None:
    # simple-icons: Bastyon #00a4ff and Warp #01a4ff; at 1.1 on white both ship #0097ff.
    result = audit(LIGHT, _brands("#00a4ff", "#01a4ff", "#7f00ff"))
    collisions = [c for c in result.collisions if c.sources == ("#00a4ff", "#01a4ff")]
    assert [(c.canvas, c.output) for c in collisions] == [
        ("white", "#0097ff"),
        ("muted", "#0098ff"),
    ]
    for c in collisions:
        assert c.new and c.delta_e_ref == pytest.approx(_de("#00a4ff", "#01a4ff"), abs=1e-6)
        assert c.delta_e_ref == pytest.approx(0.0169, abs=1e-4)
    gate = evaluate([result], Policy())
    assert gate.passed
    (near,) = [f for f in gate.warnings if f.rule is Rule.NEAR_DUPLICATE]
    assert near.canvases == ("white", "muted")  # listed once, over both canvases
    assert not near.fails and near.icons == ("b0", "b1")
    assert "already look the same at alpha 1 (CIEDE2000 0.0169 < 1)" in near.message
    assert not [f for f in (*gate.findings, *gate.warnings) if f.rule is Rule.NEW_COLLISION]


def test_the_distance_is_configurable_like_the_visibility_floor() -> None:
    result = audit(LIGHT, _brands("#00a4ff", "#01a4ff"))
    gate = evaluate([result], Policy(near_duplicate_delta_e=0.0))
    assert [f.rule for f in gate.failures] == [Rule.NEW_COLLISION]
    failing = Policy(warnings=frozenset(), rules=Policy().rules | {Rule.NEAR_DUPLICATE})
    assert [f.rule for f in evaluate([result], failing).failures] == [Rule.NEAR_DUPLICATE]
    with pytest.raises(Exception, match="CIEDE2000 difference between 0 and 200"):
        Policy(near_duplicate_delta_e=-1.0)


def test_suggest_is_not_limited_by_near_duplicates() -> None:
    result = audit(LIGHT, _brands("#00a4ff", "#01a4ff", alpha=1.0))
    assert suggest(result, Policy(), scopes=("set",)).overall.limit is None
    strict = suggest(result, Policy(near_duplicate_delta_e=0.0), scopes=("set",))
    limit = strict.overall.limit
    assert limit is not None and limit.rule is Rule.NEW_COLLISION and limit.at < 1.01


def test_one_colour_told_apart_makes_the_collision_new() -> None:
    # flag-icons on a dark canvas at 1.2: #000000 and #000001 are 0.43 apart, but #010002,
    # in the same output, is 1.03 from #000000: alpha made that collision.
    result = audit(DARK, _brands("#000000", "#000001", "#010002", alpha=1.2))
    (col,) = result.collisions
    assert col.output == "#000000" and col.sources == ("#000000", "#000001", "#010002")
    widest = max(_de(a, b) for a, b in itertools.combinations(col.sources, 2))
    assert col.delta_e_ref == pytest.approx(widest, abs=1e-6) and widest > 1.0
    assert [f.rule for f in evaluate([result], Policy()).failures] == [Rule.NEW_COLLISION]
    # The two nearest alone: a near duplicate.
    result = audit(DARK, _brands("#000000", "#000001", alpha=1.2))
    gate = evaluate([result], Policy())
    assert gate.passed and [f.rule for f in gate.warnings] == [Rule.NEAR_DUPLICATE]


def test_a_collision_already_at_alpha_1_is_not_new() -> None:
    # Two paints that already ship one code at alpha 1 (#000000 and a float just beside it).
    icons = IconSet("s", (Icon("a", "a.svg", "#000000", 1.2), Icon("b", "b.svg", "#000000", 1.3)))
    result = audit(DARK, icons)
    assert all(not c.new and c.delta_e_ref == 0.0 for c in result.collisions)


hexes = st.integers(0, 0xFFFFFF).map(lambda v: f"#{v:06x}")


@settings(max_examples=60, deadline=None)
@given(st.lists(hexes, min_size=1, max_size=7, unique=True))
def test_widest_is_the_largest_ciede2000_of_any_two(colours: list[str]) -> None:
    lab = linear_to_lab(np.array([hex_to_linear(c) for c in colours]))
    expected = max((_de(a, b) for a, b in itertools.combinations(colours, 2)), default=0.0)
    assert widest_delta_e(lab) == pytest.approx(expected, rel=1e-9, abs=1e-9)


def test_many_groups_at_once_are_each_groups_widest() -> None:
    rng = np.random.default_rng(3)
    # Small groups, and two of 400 colours (80,000 pairs each: more than one chunk).
    sizes = [0, 1, 2, 3, 5, 400, 2, 400, 7]
    labs = [linear_to_lab(rng.uniform(0.0, 1.0, (n, 3))) for n in sizes]
    many = widest_delta_e_many(labs)
    assert many.tolist() == [widest_delta_e_many([lab])[0] for lab in labs]
    for lab, value in zip(labs[:5], many[:5], strict=True):
        i, k = np.triu_indices(len(lab), 1)
        pairs = zip(i.tolist(), k.tolist(), strict=True)
        expected = max(
            (_de(Color("lab-d65", list(lab[x])), Color("lab-d65", list(lab[y]))) for x, y in pairs),
            default=0.0,
        )
        assert value == pytest.approx(expected, rel=1e-6, abs=1e-9)
