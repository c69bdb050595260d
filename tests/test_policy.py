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
