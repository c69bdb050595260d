"""suggest judges losses as the gate does: invisible logos and sub-tolerance losses never decide."""

from __future__ import annotations

from alpha_audit.findings import findings_for
from alpha_audit.model import Canvas, Icon, IconSet, Theme
from alpha_audit.policy import Policy
from alpha_audit.rows import audit, with_alphas
from alpha_audit.rules import Level, Rule
from alpha_audit.suggest.engine import largest_safe_alpha

# A logo in (almost) the canvas's own lime: 1.009:1 at alpha 1, and its red
# channel clips at 1 above alpha 1, so its contrast drops a little further.
THEME = Theme("t", (Canvas("lime", "#f0ff00"), Canvas("white", "#ffffff")))
ICONS = IconSet("s", (Icon("logo", "l.svg", "#fffc00", 1.2), Icon("ink", "i.svg", "#333333", 1.2)))
LOSS = Policy(rules=frozenset({Rule.LOSS}))


def test_an_invisible_logos_loss_does_not_decide_the_answer() -> None:
    result = audit(THEME, ICONS)
    ref, now = result.contrast_ref[0, 0], result.contrast[0, 0]
    assert ref < LOSS.visibility_floor and now < ref  # invisible, and it loses
    assert largest_safe_alpha(result, LOSS).alpha == 2.0
    # Without the floor the same loss caps the answer where it starts as it ships: the
    # 8-bit colour of alpha 1 holds until a = 1.16514 (spec formula: first loss at 1.1655
    # on a 5e-4 grid).
    strict = Policy(rules=frozenset({Rule.LOSS}), visibility_floor=1.0)
    safe = largest_safe_alpha(result, strict)
    assert safe.alpha == 1.165 and safe.exact is not None and 1.1650 < safe.exact <= 1.1655
    # check says the same: reported, not gated.
    (found,) = findings_for(result, LOSS)
    assert found.level is Level.WARN and "reported, not gated" in found.message


def test_the_answer_is_where_the_loss_reaches_the_relative_tolerance() -> None:
    # Paper, Section 4: blue (0, 0, 0.8125) on yellow loses contrast from alpha 1 on.
    theme = Theme("t", (Canvas("yellow", "#ffff00"),))
    icons = IconSet("s", (Icon("dot", "dot.svg", "rgb(0 0 207.1875)", 1.0),))
    result = audit(theme, icons)
    policy = Policy(rules=frozenset({Rule.LOSS}), loss_tolerance=0.01)
    answer = largest_safe_alpha(result, policy).alpha
    assert answer is not None and answer > 1.0

    def relative_loss(alpha: float) -> float:
        at = with_alphas(result, {"dot": alpha})
        return float(1.0 - at.contrast[0, 0] / at.contrast_ref[0, 0])

    # Safe at the answer (within 1%), over 1% one rounding step above it.
    assert 0.0 < relative_loss(answer) <= 0.01 < relative_loss(answer + 0.001)
    assert [f for f in findings_for(with_alphas(result, {"dot": answer}), policy)
            if f.level is Level.FAIL] == []  # fmt: skip
