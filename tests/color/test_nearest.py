"""The pruned closest pair equals the brute-force one: same pair, same distance."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from alpha_audit.color import delta_e_2000_lab, linear_to_lab
from alpha_audit.color.nearest import (
    S_L_MAX,
    closest_pair,
    closest_pair_brute_force,
    closest_pair_delta_e_2000,
    delta_e_2000_lightness_key,
    iter_pairs,
    lightness_weight_max,
)

# 8-bit sRGB codes, few distinct values so that exact ties (dE = 0) happen.
codes = st.lists(st.tuples(*[st.sampled_from([0, 1, 128, 200, 255])] * 3), min_size=2, max_size=40)


def _lab(rgb: list[tuple[int, int, int]]) -> np.ndarray:
    encoded = np.array(rgb, dtype=np.float64) / 255
    linear = np.where(encoded <= 0.04045, encoded / 12.92, ((encoded + 0.055) / 1.055) ** 2.4)
    return linear_to_lab(linear)


def test_s_l_max_is_sharma_eq_15_at_the_ends_of_the_lightness_scale() -> None:
    # Independent evaluation of S_L = 1 + 0.015 (L - 50)^2 / sqrt(20 + (L - 50)^2).
    assert pytest.approx(1 + 0.015 * 2500 / math.sqrt(2520), abs=0) == S_L_MAX
    assert 1.747 < S_L_MAX < 1.7471
    assert lightness_weight_max([0.0, 100.0]) == S_L_MAX


@settings(max_examples=60, deadline=None)
@given(st.lists(st.tuples(*[st.integers(0, 255)] * 3), min_size=2, max_size=30))
def test_lightness_key_is_a_lower_bound_of_ciede2000(rgb: list[tuple[int, int, int]]) -> None:
    lab = _lab(rgb)
    key = delta_e_2000_lightness_key(lab)
    for first, second in iter_pairs(len(rgb)):
        de = delta_e_2000_lab(lab[first], lab[second])
        assert np.all(de >= np.abs(key[first] - key[second]) - 1e-12)


@settings(max_examples=80, deadline=None)
@given(codes, st.integers(1, 3), st.sampled_from([1, 3, 64]))
def test_pruned_equals_brute_force(
    rgb: list[tuple[int, int, int]], groups: int, chunk: int
) -> None:
    lab = _lab(rgb)
    labels = np.arange(len(rgb)) % groups if groups > 1 else None

    def distance(i: np.ndarray, j: np.ndarray) -> np.ndarray:
        return delta_e_2000_lab(lab[i], lab[j])

    expected = closest_pair_brute_force(distance, len(rgb), labels)
    assert closest_pair_delta_e_2000(lab, labels, chunk=chunk) == expected


def test_no_pair_with_different_labels_is_none() -> None:
    lab = _lab([(1, 2, 3), (200, 0, 0)])
    assert closest_pair_delta_e_2000(lab, [7, 7]) is None
    assert closest_pair_delta_e_2000(lab[:1]) is None


def test_ties_go_to_the_first_pair_like_argmin_over_triu() -> None:
    # Four equal colours: every pair is at 0; argmin over triu_indices picks (0, 1).
    lab = _lab([(10, 20, 30)] * 4)
    assert closest_pair_delta_e_2000(lab) == closest_pair_brute_force(
        lambda i, j: delta_e_2000_lab(lab[i], lab[j]), 4
    )
    assert (closest_pair_delta_e_2000(lab).first, closest_pair_delta_e_2000(lab).second) == (0, 1)


def test_pruning_skips_almost_every_pair_on_spread_colours() -> None:
    rng = np.random.default_rng(0)
    lab = _lab([tuple(c) for c in rng.integers(0, 256, (2000, 3))])
    calls = []

    def distance(i: np.ndarray, j: np.ndarray) -> np.ndarray:
        calls.append(i.size)
        return delta_e_2000_lab(lab[i], lab[j])

    closest_pair(delta_e_2000_lightness_key(lab), distance)
    assert sum(calls) < 0.02 * 2000 * 1999 / 2


def test_iter_pairs_covers_triu_once_in_order() -> None:
    chunks = list(iter_pairs(7, chunk=5))
    first = np.concatenate([a for a, _ in chunks])
    second = np.concatenate([b for _, b in chunks])
    expected = np.triu_indices(7, k=1)
    assert first.tolist() == expected[0].tolist() and second.tolist() == expected[1].tolist()


def test_audit_separation_is_the_same_pruned_or_brute_force(monkeypatch) -> None:
    import importlib

    audit_module = importlib.import_module("alpha_audit.rows")
    from alpha_audit.model import Canvas, Icon, IconSet, Theme

    rng = np.random.default_rng(3)
    colors = [f"#{c:06x}" for c in rng.integers(0, 1 << 24, 60)] + ["#ee7733", "#ee7734"]
    icons = IconSet("s", tuple(Icon(f"i{k}", f"i{k}.svg", c, 1.1) for k, c in enumerate(colors)))
    theme = Theme("t", tuple(Canvas(f"c{k}", c) for k, c in enumerate(["#ffffff", "#0d1117"])))
    brute = audit_module.audit(theme, icons).separations
    monkeypatch.setattr(audit_module, "DECREASES_BUDGET", 0)
    pruned = audit_module.audit(theme, icons).separations
    assert [s.decreases for s in pruned] == [None, None]
    strip = [(s.canvas, s.delta_e, s.delta_e_ref, s.icons, s.sources, s.pairs) for s in brute]
    assert [
        (s.canvas, s.delta_e, s.delta_e_ref, s.icons, s.sources, s.pairs) for s in pruned
    ] == strip
    assert all(isinstance(s.decreases, int) for s in brute)


@settings(max_examples=40, deadline=None)
@given(codes, st.sampled_from([0.5, 5.0, 20.0]))
def test_pairs_below_lists_exactly_the_brute_force_pairs(rgb, level: float) -> None:
    from alpha_audit.color.nearest import pairs_below

    lab = _lab(rgb)
    labels = np.arange(len(rgb)) % 2

    def distance(i: np.ndarray, j: np.ndarray) -> np.ndarray:
        return delta_e_2000_lab(lab[i], lab[j])

    first, second, values = pairs_below(delta_e_2000_lightness_key(lab), distance, level, labels)
    expected = [
        (int(a), int(b))
        for f, s in iter_pairs(len(rgb), labels)
        for a, b, d in zip(f, s, distance(f, s), strict=True)
        if d < level
    ]
    assert list(zip(first.tolist(), second.tolist(), strict=True)) == expected
    assert np.all(values < level)
