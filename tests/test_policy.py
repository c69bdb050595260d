"""Policy overrides and rule names."""

from __future__ import annotations

import pytest

from alpha_audit.errors import UsageError
from alpha_audit.policy import Policy
from alpha_audit.rules import DEFAULT_RULES, Rule


def test_overrides_replace_only_what_is_given() -> None:
    base = Policy(max_loss=0.1)
    assert base.with_overrides() == base
    changed = base.with_overrides(rules=["collision", "LOSS"], min_delta_e=5)
    assert changed.rules == {Rule.COLLISION, Rule.LOSS}
    assert (changed.max_loss, changed.min_delta_e) == (0.1, 5)
    assert Policy().rules == DEFAULT_RULES


def test_unknown_rule_lists_the_valid_ones() -> None:
    with pytest.raises(
        UsageError,
        match="unknown rule 'los'; did you mean 'loss'\\? use one of: loss, below-threshold",
    ):
        Policy().with_overrides(rules=["los"])


@pytest.mark.parametrize("field", ["max_loss", "min_delta_e"])
@pytest.mark.parametrize("value", [-1.0, float("nan"), float("inf")])
def test_limits_must_be_finite_and_non_negative(field: str, value: float) -> None:
    with pytest.raises(UsageError):
        Policy().with_overrides(**{field: value})


def test_a_loss_gates_only_above_the_visibility_floor_and_the_relative_tolerance() -> None:
    import numpy as np

    from alpha_audit.policy import contrast_breaks, contrast_floor, loss_reported

    policy = Policy(visibility_floor=1.5, loss_tolerance=1e-3)
    ref = np.array([1.2, 1.5, 4.0, 4.0, 4.0])
    now = np.array([1.0, 1.4, 4.0 - 2e-10, 4.0 - 0.003, 4.0 - 0.005])
    gated = contrast_breaks(Rule.LOSS, policy, ref, now, 3.0)
    assert gated.tolist() == [False, True, False, False, True]
    # Every loss is either gated or reported, never both.
    reported = loss_reported(policy, ref, now)
    assert reported.tolist() == [True, False, True, True, False]
    # The solved form suggest uses says the same: gated iff below the floor it gives.
    assert ((now < contrast_floor(Rule.LOSS, policy, ref, 3.0)) == gated).all()


@pytest.mark.parametrize(("field", "value"), [("visibility_floor", 0.9), ("loss_tolerance", 1.5)])
def test_loss_thresholds_have_ranges(field: str, value: float) -> None:
    with pytest.raises(UsageError, match="out of range"):
        Policy(**{field: value})
