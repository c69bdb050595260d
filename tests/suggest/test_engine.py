"""``suggest``: the exact largest safe alpha, judged by independent implementations.

Two judges that share nothing with :mod:`alpha_audit.suggest.events`:

* ``broken_at`` -- a straightforward vectorised evaluation of the gate rules at
  many coefficients at once (composite, quantise, compare pairwise);
* ``gate_fails_at`` -- the reference semantics itself: :func:`audit` plus
  :func:`gate.evaluate`, keeping findings that involve a moved icon.
"""

from __future__ import annotations

import numpy as np
import pytest

from alpha_audit.color import (
    contrast_from_luminance,
    delta_e_2000,
    relative_luminance,
    srgb_decode,
    to_8bit,
)
from alpha_audit.errors import UsageError
from alpha_audit.gate import evaluate
from alpha_audit.model import Canvas, Icon, IconSet, Theme
from alpha_audit.policy import Exemption, Policy
from alpha_audit.rows import audit
from alpha_audit.rules import Rule
from alpha_audit.suggest import largest_safe_alpha, suggest

RULE_SETS = [
    frozenset({Rule.LOSS, Rule.NEWLY_FAILING, Rule.NEW_COLLISION}),
    frozenset({Rule.COLLISION}),
    frozenset({Rule.LOSS}),
    frozenset({Rule.NEWLY_FAILING, Rule.NEW_COLLISION}),
]


def broken_at(
    theme: Theme, iconset: IconSet, policy: Policy, moving: np.ndarray, alphas: np.ndarray
) -> np.ndarray:
    """For each coefficient, whether a rule breaks with a finding involving a moved icon."""
    src = iconset.sources  # (n, 3)
    bg = theme.backgrounds  # (m, 3)
    coef = np.where(moving[np.newaxis, :], alphas[:, np.newaxis], iconset.alphas[np.newaxis, :])
    out = np.clip(
        bg[None, None] + coef[:, :, None, None] * (src[None, :, None] - bg[None, None]), 0, 1
    )  # (N, n, m, 3)
    # Judged as it ships: the 8-bit colours (the sources and canvases are 8-bit already).
    shown = srgb_decode(to_8bit(out) / 255.0)
    y_bg = relative_luminance(bg)
    c_ref = contrast_from_luminance(relative_luminance(src)[:, None], y_bg[None, :])
    c = contrast_from_luminance(relative_luminance(shown), y_bg)
    t = theme.threshold
    bad = np.zeros(alphas.shape, dtype=bool)
    mv = moving[None, :, None]
    if Rule.LOSS in policy.rules:
        # Gated above the visibility floor, beyond the allowance and the relative tolerance.
        margin = np.maximum(max(policy.max_loss, 1e-10), policy.loss_tolerance * c_ref)
        lost = (c - c_ref < -margin) & (c_ref >= policy.visibility_floor)
        bad |= (lost & mv).any(axis=(1, 2))
    if Rule.NEWLY_FAILING in policy.rules:
        bad |= ((c_ref >= t) & (c < t) & mv).any(axis=(1, 2))
    if Rule.BELOW_THRESHOLD in policy.rules:
        bad |= ((c < t) & mv).any(axis=(1, 2))
    if Rule.COLLISION in policy.rules or Rule.NEW_COLLISION in policy.rules:
        codes = to_8bit(out).astype(np.int64)
        packed = (codes[..., 0] << 16) | (codes[..., 1] << 8) | codes[..., 2]  # (N, n, m)
        same = packed[:, :, None, :] == packed[:, None, :, :]  # (N, n, n, m)
        distinct = (src[:, None, :] != src[None, :, :]).any(axis=-1)  # hex sources: all new
        involved = moving[:, None] | moving[None, :]
        bad |= (same & (distinct & involved)[None, :, :, None]).any(axis=(1, 2, 3))
    return bad


def gate_fails_at(
    theme: Theme, iconset: IconSet, policy: Policy, moving: np.ndarray, a: float
) -> bool:
    """Reference semantics: audit() at these alphas, gate.evaluate(), moved icons only."""
    from dataclasses import replace

    icons = tuple(
        replace(icon, alpha=a) if moving[i] else icon for i, icon in enumerate(iconset.icons)
    )
    result = audit(theme, replace(iconset, icons=icons))
    moved = {icon.name for i, icon in enumerate(iconset.icons) if moving[i]}
    gate = evaluate([result], policy)
    return any(set(f.icons) & moved for f in gate.failures)


def random_case(seed: int) -> tuple[Theme, IconSet]:
    rng = np.random.default_rng(seed)
    k = int(rng.integers(2, 8))
    palette = {
        f"c{i}": "#" + "".join(f"{v:02x}" for v in rng.integers(0, 256, 3)) for i in range(k)
    }
    kinds = ["#000000", "#ffffff", "#0d1117", "#f6f8fa"]
    canvases = []
    for j in range(int(rng.integers(2, 7))):
        if rng.random() < 0.4:
            color = kinds[int(rng.integers(len(kinds)))]
        else:
            color = "#" + "".join(f"{v:02x}" for v in rng.integers(0, 256, 3))
        canvases.append(Canvas(f"bg{j}", color))
    names = list(palette)
    icons = tuple(
        Icon(
            f"i{i}",
            f"i{i}.svg",
            palette[names[i % k]],
            float(rng.choice([1.0, 1.1, 1.2])),
            names[i % k],
        )
        for i in range(k + int(rng.integers(0, 4)))
    )
    return Theme(f"t{seed}", tuple(canvases)), IconSet(f"s{seed}", icons, palette)


def judge(theme: Theme, iconset: IconSet, policy: Policy, moving: np.ndarray, safe) -> None:
    """a* safe on [1, a*] (dense), and something breaks within 1e-3 above it."""
    a_max = 2.0
    if safe.alpha is None:
        assert gate_fails_at(theme, iconset, policy, moving, 1.0)
        return
    grid = np.unique(np.concatenate([np.arange(1.0, safe.alpha, 1e-4), [safe.alpha]]))
    assert not broken_at(theme, iconset, policy, moving, grid).any()
    assert not gate_fails_at(theme, iconset, policy, moving, safe.alpha)
    if safe.alpha >= a_max:
        assert safe.limit is None
        return
    limit = safe.limit
    assert limit is not None and safe.alpha <= limit.at < safe.alpha + 1e-3
    above = np.concatenate(
        [
            [limit.at] if limit.attained else [],
            limit.at + np.array([1e-12, 1e-10, 1e-9]) * (not limit.attained),
            np.arange(safe.alpha + 1e-6, safe.alpha + 1e-3, 1e-6),
        ]
    )
    above = above[above > safe.alpha]
    assert broken_at(theme, iconset, policy, moving, above).any()
    first = above[np.argmax(broken_at(theme, iconset, policy, moving, above))]
    assert gate_fails_at(theme, iconset, policy, moving, float(first))


@pytest.mark.parametrize("seed", range(24))
def test_random_sets_agree_with_independent_judges(seed: int) -> None:
    theme, iconset = random_case(seed)
    policy = Policy(rules=RULE_SETS[seed % len(RULE_SETS)])
    result = suggest(audit(theme, iconset), policy)
    n = len(iconset.icons)
    judge(theme, iconset, policy, np.ones(n, dtype=bool), result.overall)
    color = result.per_color[seed % len(result.per_color)]
    moving = np.array([i.name in color.icons for i in iconset.icons])
    judge(theme, iconset, policy, moving, color.safe)
    one = result.per_icon[seed % n]
    judge(theme, iconset, policy, np.array([i.name == one.icon for i in iconset.icons]), one.safe)


@pytest.mark.parametrize("seed", range(100, 112))
def test_exact_answer_is_never_above_a_fine_sweep(seed: int) -> None:
    """The first unsafe point of a 1e-4 sweep is never below the exact one."""
    theme, iconset = random_case(seed)
    policy = Policy(rules=frozenset({Rule.COLLISION, Rule.LOSS, Rule.NEWLY_FAILING}))
    safe = suggest(audit(theme, iconset), policy).overall
    grid = np.arange(1.0, 2.0 + 5e-5, 1e-4)
    bad = broken_at(theme, iconset, policy, np.ones(len(iconset.icons), bool), grid)
    if safe.limit is None:
        assert not bad.any()
    else:
        assert not bad[grid < safe.limit.at].any()
        if bad.any():
            assert grid[np.argmax(bad)] >= safe.limit.at


def _narrow_window_case() -> tuple[Theme, IconSet, float, float]:
    """Vibrant orange moving on GitHub's dark canvas passes through a fixed icon's colour.

    Its three channel codes equal ``#ff7f36`` only between two events of
    different channels, a window about 1.3e-4 wide with no 1e-3 grid point in
    it (the window is recomputed here from first principles).
    """

    theme = Theme("t", (Canvas("ink", "#0d1117"),))
    icons = (Icon("mover", "m.svg", "#ee7733", 1.0), Icon("fixed", "f.svg", "#ff7f36", 1.0))
    s = srgb_decode(np.array([0xEE, 0x77, 0x33]) / 255)
    b = srgb_decode(np.array([0x0D, 0x11, 0x17]) / 255)
    # Channel k holds code n for a between (decode((n -/+ 0.5)/255) - b)/(s - b);
    # red stays at 255 once it gets there.
    codes = np.array([0xFF, 0x7F, 0x36])
    enter = (srgb_decode((codes - 0.5) / 255) - b) / (s - b)
    leave = (srgb_decode((codes[1:] + 0.5) / 255) - b[1:]) / (s[1:] - b[1:])
    lo, hi = float(enter.max()), float(leave.min())
    assert 0 < hi - lo < 1e-3
    return theme, IconSet("s", icons), lo, hi


def test_a_1e3_sweep_misses_a_collision_window_that_the_exact_method_finds() -> None:
    theme, iconset, lo, hi = _narrow_window_case()
    policy = Policy(rules=frozenset({Rule.COLLISION}))
    moving = np.array([True, False])
    safe = largest_safe_alpha(audit(theme, iconset), policy, icons=["mover"])
    assert safe.limit is not None and safe.limit.rule is Rule.COLLISION
    assert safe.limit.at == pytest.approx(lo, abs=1e-12) and not safe.limit.attained
    assert safe.limit.icons == ("fixed", "mover")
    # A 1e-3 sweep steps over the window ...
    sweep = np.arange(1.0, 2.0 + 5e-4, 1e-3)
    assert not broken_at(theme, iconset, policy, moving, sweep).any()
    # ... but it is real: the reference audit finds the collision inside it.
    assert gate_fails_at(theme, iconset, policy, moving, 0.5 * (lo + hi))
    assert safe.alpha == np.floor(lo * 1000) / 1000
    # suggest() reports the same per icon.
    per_icon = {s.icon: s.safe for s in suggest(audit(theme, iconset), policy).per_icon}
    assert per_icon["mover"].limit == safe.limit


def test_paper_worst_case_loses_contrast_immediately() -> None:
    # Paper, Section 4: sRGB (0, 0, 0.8125) on (1, 1, 0); 0.8125 * 255 = 207.1875.
    theme = Theme("t", (Canvas("yellow", "#ffff00"),))
    iconset = IconSet("s", (Icon("dot", "dot.svg", "rgb(0 0 207.1875)", 1.0),))
    safe = largest_safe_alpha(audit(theme, iconset), Policy(rules=frozenset({Rule.LOSS})))
    # What ships (8 bits) first loses at the first code step above 1, a few thousandths on.
    assert safe.alpha is not None and 1.0 <= safe.alpha < 1.01 and safe.limit is not None
    assert safe.limit.rule is Rule.LOSS and safe.limit.at == pytest.approx(1.0, abs=1e-2)
    # Allowing the paper's (float) loss at 1.1 (10.2773 -> 9.8118) moves the limit to about
    # 1.1: what ships is the 8-bit colour, whose loss reaches it a little earlier (1.092).
    allowed = Policy(rules=frozenset({Rule.LOSS}), max_loss=10.277324 - 9.811806)
    answer = largest_safe_alpha(audit(theme, iconset), allowed).alpha
    assert answer is not None and 1.08 < answer <= 1.1


def test_black_and_white_canvases_never_lose_contrast() -> None:
    # Paper, Section 3: on black and white the contrast ratio cannot decrease.
    theme = Theme("t", (Canvas("black", "#000000"), Canvas("white", "#ffffff")))
    rng = np.random.default_rng(7)
    icons = tuple(
        Icon(f"i{k}", "x.svg", "#" + "".join(f"{v:02x}" for v in rng.integers(0, 256, 3)), 1.0)
        for k in range(40)
    )
    safe = largest_safe_alpha(
        audit(theme, IconSet("s", icons)), Policy(rules=frozenset({Rule.LOSS}))
    )
    assert safe.alpha == 2.0 and safe.limit is None


def test_rounding_is_down_and_an_unsafe_point_is_stepped_off() -> None:
    theme, iconset = random_case(3)
    for precision in (0, 1, 2, 4):
        safe = suggest(
            audit(theme, iconset), Policy(rules=RULE_SETS[1]), precision=precision
        ).overall
        if safe.alpha is not None and safe.limit is not None:
            assert safe.alpha <= safe.limit.at
            assert round(safe.alpha, precision) == safe.alpha


def test_exemptions_are_honoured() -> None:
    theme, iconset, lo, _ = _narrow_window_case()
    policy = Policy(
        rules=frozenset({Rule.COLLISION}),
        exemptions=(Exemption(reason="known", icon="fixed"),),
    )
    assert largest_safe_alpha(audit(theme, iconset), policy, icons=["mover"]).limit is None
    by_canvas = Policy(
        rules=frozenset({Rule.COLLISION}), exemptions=(Exemption(reason="x", canvas="paper"),)
    )
    limit = largest_safe_alpha(audit(theme, iconset), by_canvas, icons=["mover"]).limit
    assert limit is not None and limit.at == pytest.approx(lo, abs=1e-12)


def test_separation_is_bracketed_and_bisected() -> None:
    theme = Theme("t", (Canvas("paper", "#ffffff"), Canvas("ink", "#0d1117")))
    icons = (Icon("o", "o.svg", "#ee7733", 1.0), Icon("m", "m.svg", "#ee3377", 1.0))
    policy = Policy(rules=frozenset({Rule.SEPARATION}), min_delta_e=20.0)
    safe = largest_safe_alpha(audit(theme, IconSet("s", icons)), policy)
    assert safe.limit is not None and safe.limit.rule is Rule.SEPARATION
    at = safe.limit.at
    moving = np.ones(2, dtype=bool)
    assert gate_fails_at(theme, IconSet("s", icons), policy, moving, at)
    assert not gate_fails_at(theme, IconSet("s", icons), policy, moving, at - 2e-9)
    src = IconSet("s", icons).sources
    assert delta_e_2000(src[0], src[1]) > 20.0  # safe at alpha = 1


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"alpha_max": 0.5}, "alpha_max"),
        ({"alpha_max": float("nan")}, "alpha_max"),
        ({"precision": 12}, "precision"),
        ({"precision": -1}, "precision"),
    ],
)
def test_bad_arguments(kwargs: dict, message: str) -> None:
    theme, iconset = random_case(1)
    with pytest.raises(UsageError, match=message):
        suggest(audit(theme, iconset), Policy(), **kwargs)


def test_unknown_icon() -> None:
    theme, iconset = random_case(1)
    with pytest.raises(UsageError, match="no icon named 'nope'"):
        largest_safe_alpha(audit(theme, iconset), Policy(), icons=["nope"])


@pytest.mark.parametrize(
    "scopes", [("set",), ("colour",), ("icon",), ("colour", "icon"), ("set", "colour", "icon")]
)
def test_progress_counts_exactly_the_questions_asked(scopes: tuple[str, ...]) -> None:
    """Every tick is one question of the scopes asked, and there are as many as announced
    (the set-wide tick came even when ``set`` was not asked: one past the total)."""
    theme, iconset = random_case(3)
    totals: list[int] = []
    ticks: list[None] = []
    result = suggest(
        audit(theme, iconset),
        Policy(),
        scopes=scopes,
        progress=(totals.append, lambda: ticks.append(None)),
    )
    expected = ("set" in scopes) + len(result.per_color) + len(result.per_icon)
    assert totals == [expected] and len(ticks) == expected > 0
