"""Each gate rule stated once: the gate, suggest and the audit agree because they share it.

Independent judges: contrast rules re-derived from the paper's formula for every
cell of an audit; the gate's split of findings checked against their flags.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from alpha_audit.color import CONTRAST_TOLERANCE, pack_8bit
from alpha_audit.gate import evaluate
from alpha_audit.model import Canvas, Icon, IconProblem, IconSet, Theme
from alpha_audit.policy import (
    Exemption,
    Policy,
    Rule,
    contrast_breaks,
    contrast_floor,
)
from alpha_audit.rows import audit
from alpha_audit.rules import CONTRAST_RULES
from alpha_audit.suggest import largest_safe_alpha
from helpers import solid_paints

contrast = st.floats(1.0, 21.0)


@given(contrast, contrast, st.floats(1.0, 7.0), st.floats(0.0, 1.0))
def test_breaks_is_contrast_below_the_floor(ref: float, now: float, t: float, loss: float) -> None:
    policy = Policy(max_loss=loss)
    for rule in CONTRAST_RULES:
        floor = float(contrast_floor(rule, policy, ref, t))
        broken = bool(contrast_breaks(rule, policy, ref, now, t))
        if abs(now - floor) > 1e-9:  # off the boundary, the two statements agree exactly
            assert broken == (now < floor), rule


def test_each_contrast_rule_means_what_the_paper_says() -> None:
    ref = np.array([4.0, 4.0, 2.0, 3.0])
    now = np.array([3.5, 4.0 - 1e-12, 1.5, 2.999])
    p = Policy(max_loss=0.25)
    assert contrast_breaks(Rule.LOSS, p, ref, now, 3.0).tolist() == [True, False, True, False]
    assert contrast_breaks(Rule.BELOW_THRESHOLD, p, ref, now, 3.0).tolist() == [
        False,
        False,
        True,
        True,
    ]
    assert contrast_breaks(Rule.NEWLY_FAILING, p, ref, now, 3.0).tolist() == [
        False,
        False,
        False,
        True,
    ]
    # The float tolerance under the policy's allowance: a change of 1e-12 is no loss.
    assert Policy().loss_margin() == CONTRAST_TOLERANCE
    with pytest.raises(ValueError):
        contrast_breaks(Rule.COLLISION, p, ref, now, 3.0)


NO_WARNINGS: frozenset[Rule] = frozenset()


@pytest.mark.parametrize(
    ("rules", "warnings", "delta_e_ref", "expected"),
    [
        # Told apart at alpha 1: both failing, reported once as the wider rule.
        ({Rule.COLLISION, Rule.NEW_COLLISION}, NO_WARNINGS, 12.0, Rule.COLLISION),
        ({Rule.NEW_COLLISION}, NO_WARNINGS, 12.0, Rule.NEW_COLLISION),
        ({Rule.LOSS}, NO_WARNINGS, 12.0, None),
        # A failing rule before a reported one: collision at warn does not hide it.
        ({Rule.NEW_COLLISION}, {Rule.COLLISION}, 12.0, Rule.NEW_COLLISION),
        # Already one output at alpha 1: only collision objects.
        ({Rule.NEW_COLLISION}, {Rule.NEAR_DUPLICATE}, 0.0, None),
        ({Rule.COLLISION}, NO_WARNINGS, 0.0, Rule.COLLISION),
        # Closer than one JND at alpha 1: a near-duplicate, never a new collision.
        ({Rule.NEW_COLLISION}, {Rule.NEAR_DUPLICATE}, 0.5, Rule.NEAR_DUPLICATE),
        ({Rule.NEW_COLLISION}, NO_WARNINGS, 0.5, None),
        ({Rule.NEW_COLLISION}, NO_WARNINGS, 1.0, Rule.NEW_COLLISION),  # the limit is apart
    ],
)
def test_which_collision_rule_applies(
    rules: set[Rule], warnings: set[Rule], delta_e_ref: float, expected: Rule | None
) -> None:
    policy = Policy(rules=frozenset(rules), warnings=frozenset(warnings))
    assert policy.collision_rule(delta_e_ref) is expected


def test_pack_8bit_is_the_hex_code() -> None:
    codes = np.array([[[0, 0, 0], [255, 255, 255]], [[18, 52, 86], [1, 2, 3]]], dtype=np.uint8)
    packed = pack_8bit(codes)
    assert packed.shape == (2, 2)
    assert [f"#{int(v):06x}" for v in packed.ravel()] == [
        "#000000",
        "#ffffff",
        "#123456",
        "#010203",
    ]


def test_gate_and_suggest_draw_the_loss_line_in_the_same_place() -> None:
    """Just below suggest's answer the gate passes; at the first unsafe alpha it fails."""
    theme = Theme("t", (Canvas("yellow", "#ffff00"),))
    icons = IconSet("s", (Icon("dot", "dot.svg", "#0000d0", 1.0),))
    policy = Policy(rules=frozenset({Rule.LOSS}), max_loss=0.05)
    safe = largest_safe_alpha(audit(theme, icons), policy, precision=6)
    assert safe.limit is not None and safe.limit.rule is Rule.LOSS
    below = evaluate([audit(theme, icons.with_alpha(safe.alpha))], policy)
    above = evaluate([audit(theme, icons.with_alpha(safe.limit.at + 1e-6))], policy)
    assert below.passed and not above.passed


def _gated(rules: set[Rule], exemptions: tuple[Exemption, ...] = (), baseline=None):
    theme = Theme("t", (Canvas("yellow", "#ffff00"),))
    icons = IconSet(
        "s",
        (Icon("dot", "dot.svg", "#0000d0", 1.4), Icon("ok", "ok.svg", "#000000", 1.4)),
    )
    broken = (IconProblem("gone", Path("gone.svg"), "not an SVG"),)
    result = audit(theme, icons, solid_paints(icons, broken))
    return evaluate(
        [result, result], Policy(frozenset(rules), exemptions=exemptions), baseline=baseline
    )


def test_unrenderable_icons_are_warnings_unless_the_rule_is_on() -> None:
    off = _gated({Rule.LOSS})
    assert [w.icons for w in off.warnings] == [("gone",)]  # once, not once per audit
    assert all(f.rule is not Rule.UNRENDERABLE for f in off.findings)
    assert off.policy.level(Rule.UNRENDERABLE).value == "warn"
    on = _gated({Rule.LOSS, Rule.UNRENDERABLE})
    assert on.warnings == () and on.policy.level(Rule.UNRENDERABLE).value == "fail"
    assert [f.icons for f in on.failures if f.rule is Rule.UNRENDERABLE] == [("gone",)]


def test_findings_split_once_into_failures_exempted_and_baselined() -> None:
    exempt = (Exemption("brand colour", icon="dot", rule=Rule.LOSS),)
    gate = _gated(
        {Rule.LOSS, Rule.UNRENDERABLE},
        exempt,
        baseline={("t", "s", "unrenderable", None, ("gone",))},
    )
    assert {f.icons for f in gate.exempted} == {("dot",)}
    assert {f.icons for f in gate.baselined} == {("gone",)}
    assert gate.failures == () and gate.passed
    split = [*gate.exempted, *gate.baselined, *gate.failures]
    assert len(split) == len(gate.findings) and all(f in gate.findings for f in split)


def test_two_colliding_colours_both_give_one_output_and_one_canvas_is_one_canvas() -> None:
    """Wording: 'both give' for two colours, '(1 canvas)' in the table's head."""
    from alpha_audit.render.common import RenderOptions
    from alpha_audit.render.table import render_report
    from alpha_audit.results import CheckReport

    icons = (Icon("a", Path("a.svg"), "#ee7733", 1.3), Icon("b", Path("b.svg"), "#ee3377", 1.3))
    result = audit(Theme("t", (Canvas("white", "#ffffff"),)), IconSet("s", icons))
    report = CheckReport(audits=(result,), gate=evaluate([result], Policy()))
    (collision,) = [f for f in report.gate.failures if f.rule.value == "new-collision"]
    assert "#ee3377, #ee7733 both give #" in collision.message
    assert "(1 canvas)" in render_report(report, RenderOptions(width=100))
