"""``suggest`` honours the paint rules: judged by an independent evaluation.

The judge shares nothing with :mod:`alpha_audit.suggest`: it composites by
hand (the paper's formula, the coverage form for a paint at opacity ``o``),
judges what ships (8-bit colours, encoded and rounded by the spec's formula),
measures CIEDE2000 with colour-science directly and simulates CVD with
colour-science's Machado matrices, then applies each rule as docs/model.md
states it.  For seeded random small sets it sweeps every coefficient in
``[1, answer]`` on a fine grid (all safe), and checks the reported first
unsafe alpha is unsafe and lies within one rounding unit above the answer.
"""

from __future__ import annotations

import warnings
from dataclasses import replace
from pathlib import Path

import colour
import numpy as np
import pytest

from alpha_audit.color.coverage import CoverageStats
from alpha_audit.model import Canvas, Icon, IconSet, Theme
from alpha_audit.paints import (
    CURRENT_COLOR,
    IconPaints,
    Paint,
    PaintCoverage,
    PaintGroup,
    PaintSet,
    SvgPaints,
)
from alpha_audit.policy import Policy
from alpha_audit.rows import audit
from alpha_audit.rules import Rule
from alpha_audit.suggest import largest_safe_alpha

TOL_DE = 1e-9  # the CIEDE2000 tolerance (alpha_audit.color.DELTA_E_TOLERANCE), a float margin


def _linear(hexes: list[str]) -> np.ndarray:
    codes = np.array([[int(h[k : k + 2], 16) for k in (1, 3, 5)] for h in hexes]) / 255.0
    return np.where(codes <= 0.04045, codes / 12.92, ((codes + 0.055) / 1.055) ** 2.4)


# CSS Color 4, section 10.7 (lin_sRGB_to_XYZ) and its D65 white point: the
# product brief's CIELAB, written out from the spec, not taken from alpha_audit.
CSS_SRGB_TO_XYZ = np.array(
    [
        [506752 / 1228815, 87881 / 245763, 12673 / 70218],
        [87098 / 409605, 175762 / 245763, 12673 / 175545],
        [7918 / 409605, 87881 / 737289, 1001167 / 1053270],
    ]
)
CSS_D65 = np.array([0.3127, 0.3290])


def _ship(linear: np.ndarray) -> np.ndarray:
    """What an 8-bit screen shows: CSS Color 4 encode, x255, round half to even, decode."""
    v = np.clip(linear, 0.0, 1.0)
    encoded = np.where(v <= 0.0031308, 12.92 * v, 1.055 * v ** (1 / 2.4) - 0.055)
    codes = np.rint(encoded * 255.0) / 255.0
    return np.where(codes <= 0.04045, codes / 12.92, ((codes + 0.055) / 1.055) ** 2.4)


def _lab(linear: np.ndarray) -> np.ndarray:
    return colour.XYZ_to_Lab(linear @ CSS_SRGB_TO_XYZ.T, CSS_D65)


def _de(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return np.asarray(colour.delta_E(_lab(a), _lab(b), method="CIE 2000"))


def _machado(linear: np.ndarray, deficiency: str) -> np.ndarray:
    name = {"protanopia": "Protanomaly", "deuteranopia": "Deuteranomaly"}.get(
        deficiency, "Tritanomaly"
    )
    with warnings.catch_warnings():  # colour-science warns that tritan is approximate
        warnings.simplefilter("ignore")
        matrix = colour.matrix_cvd_Machado2009(name, 1.0)
    return np.clip(linear @ matrix.T, 0.0, 1.0)


def judge_unsafe(
    sources: np.ndarray,
    roles: list[str],
    opacity: np.ndarray,
    backgrounds: np.ndarray,
    policy: Policy,
    a: float | np.ndarray,
) -> np.ndarray:
    """The policy's rules (confusion, drift, cvd-confusion) at each coefficient, all moving."""
    alphas = np.atleast_1d(np.asarray(a, dtype=np.float64))
    s, bg = sources[:, None, None, :], backgrounds[None, :, None, :]  # (n, m, N, 3)
    k = alphas[None, None, :, None]
    o = opacity[:, None, None, None]
    pushed = np.clip(bg + k * (s - bg), 0, 1)
    shown = _ship(o * pushed + (1 - o) * bg)  # the coverage form, as it ships (8 bits)
    ref = _ship(o * s + (1 - o) * bg)
    pushed = _ship(pushed)
    out = np.zeros(alphas.shape, dtype=bool)
    if Rule.DRIFT in policy.rules:
        drift = _de(np.broadcast_to(ref, shown.shape), shown)  # (n, m, N)
        out |= (drift > policy.max_drift + TOL_DE).any(axis=(0, 1))
    views = []
    if Rule.CONFUSION in policy.rules:
        views.append(lambda c: c)
    if Rule.CVD_CONFUSION in policy.rules:
        views += [
            lambda c, d=d: _machado(c, d) for d in ("protanopia", "deuteranopia", "tritanopia")
        ]
    solid = np.broadcast_to(s, pushed.shape)  # roles are compared as solid colours
    for view in views:
        for i in range(len(roles)):
            for j in range(i + 1, len(roles)):
                if roles[i] == roles[j]:
                    continue
                d_ref = _de(view(solid[i]), view(solid[j]))  # (m, N)
                d_now = _de(view(pushed[i]), view(pushed[j]))
                level = policy.min_delta_e
                out |= ((d_ref >= level) & (d_now < level)).any(axis=0)
    return out


def _random_case(seed: int) -> tuple[Theme, IconSet, np.ndarray]:
    rng = np.random.default_rng(seed)
    n = int(rng.integers(3, 6))
    hexes = ["#" + "".join(f"{v:02x}" for v in rng.integers(0, 256, 3)) for _ in range(n)]
    canvases = tuple(
        Canvas(f"c{k}", "#" + "".join(f"{v:02x}" for v in rng.integers(0, 256, 3)))
        for k in range(2)
    )
    icons = tuple(
        Icon(f"i{k}", f"i{k}.svg", h, 1.0, color_name=f"r{k}") for k, h in enumerate(hexes)
    )
    return Theme("t", canvases), IconSet("s", icons), _linear(hexes)


POLICIES = [
    Policy(rules=frozenset({Rule.CONFUSION}), min_delta_e=20.0),
    Policy(rules=frozenset({Rule.DRIFT}), max_drift=8.0),
    Policy(rules=frozenset({Rule.CONFUSION, Rule.DRIFT}), min_delta_e=15.0, max_drift=15.0),
]


@pytest.mark.parametrize("seed", range(6))
@pytest.mark.parametrize("policy", POLICIES, ids=["confusion", "drift", "both"])
def test_answer_is_safe_and_just_above_is_not(seed: int, policy: Policy) -> None:
    theme, iconset, linear = _random_case(seed)
    roles = [i.color_name or i.color for i in iconset.icons]
    ones = np.ones(len(roles))
    safe = largest_safe_alpha(audit(theme, iconset), policy, precision=3)
    if safe.alpha is None:
        assert judge_unsafe(linear, roles, ones, theme.backgrounds, policy, 1.0)
        return
    # A fine sweep of [1, answer]: every coefficient keeps the policy.
    sweep = np.append(np.arange(1.0, safe.alpha, 2.5e-4), safe.alpha)
    assert not judge_unsafe(linear, roles, ones, theme.backgrounds, policy, sweep).any()
    if safe.limit is None:
        assert safe.alpha == 2.0
        return
    at = safe.limit.at
    assert safe.alpha < at <= safe.alpha + 1e-3 + 1e-9  # the limit is within one unit above
    # Unsafe just above the crossing (bisected to 1e-9), within one unit of the answer.
    above = min(at + 1e-7, safe.alpha + 1e-3)
    assert judge_unsafe(linear, roles, ones, theme.backgrounds, policy, above).all()
    assert safe.limit.grid == 1e-3  # bracketed rules say so


def test_cvd_confusion_against_colour_science_machado() -> None:
    theme = Theme("t", (Canvas("white", "#ffffff"),))
    # Red and green: apart for everyone at alpha 1, pushed towards each other for protans.
    hexes = ["#d1242f", "#1a7f37", "#0969da"]
    icons = tuple(
        Icon(f"i{k}", f"i{k}.svg", h, 1.0, color_name=f"r{k}") for k, h in enumerate(hexes)
    )
    policy = Policy(rules=frozenset({Rule.CVD_CONFUSION}), min_delta_e=10.0)
    safe = largest_safe_alpha(audit(theme, IconSet("s", icons)), policy, precision=3)
    linear, roles = _linear(hexes), [f"r{k}" for k in range(3)]
    judge = Policy(rules=frozenset({Rule.CVD_CONFUSION}), min_delta_e=10.0)
    ones = np.ones(3)
    assert safe.alpha is not None
    sweep = np.append(np.arange(1.0, safe.alpha, 2.5e-4), safe.alpha)
    assert not judge_unsafe(linear, roles, ones, theme.backgrounds, judge, sweep).any()
    assert safe.limit is not None and safe.limit.rule is Rule.CVD_CONFUSION
    above = min(safe.limit.at + 1e-7, safe.alpha + 1e-3)
    assert judge_unsafe(linear, roles, ones, theme.backgrounds, judge, above).all()
    assert not judge_unsafe(linear, roles, ones, theme.backgrounds, judge, 1.0).any()


def _painted(icons: list[Icon], opacity: float, q50: float) -> tuple[IconSet, PaintSet]:
    stats = CoverageStats(q50=q50, full_share=0.5, ink=10.0, pixels=20)
    out = {}
    for icon in icons:
        group = PaintGroup(
            CURRENT_COLOR, opacity, (Paint(CURRENT_COLOR, "fill", opacity, "<path>", 3),)
        )
        cov = (PaintCoverage(group, {24: stats}),)
        out[icon.name] = IconPaints(icon.name, Path(icon.file), SvgPaints(group.paints), cov)
    return IconSet("s", tuple(icons), sizes=(24,)), PaintSet(out, ())


@pytest.mark.parametrize("opacity", [1.0, 0.6, 0.3])
def test_drift_of_a_translucent_paint_uses_the_coverage_form(opacity: float) -> None:
    theme = Theme("t", (Canvas("white", "#ffffff"), Canvas("ink", "#0d1117")))
    icons = [Icon("a", "a.svg", "#64748b", 1.0), Icon("b", "b.svg", "#ee7733", 1.0)]
    iconset, paints = _painted(icons, opacity, 1.0)
    policy = Policy(rules=frozenset({Rule.DRIFT}), max_drift=6.0)
    safe = largest_safe_alpha(audit(theme, iconset, paints), policy, precision=4)
    linear = _linear([i.color for i in icons])
    o = np.full(2, opacity)
    assert safe.alpha is not None and safe.limit is not None
    sweep = np.append(np.arange(1.0, safe.alpha, 2.5e-4), safe.alpha)
    assert not judge_unsafe(linear, ["x", "x"], o, theme.backgrounds, policy, sweep).any()
    above = min(safe.limit.at + 1e-7, safe.alpha + 1e-4)
    assert judge_unsafe(linear, ["x", "x"], o, theme.backgrounds, policy, above).all()
    assert safe.limit.at <= safe.alpha + 1e-4 + 1e-9


def test_thin_strokes_is_exact_at_q50() -> None:
    # The paper's dark blue on yellow loses contrast as soon as a > 1; drawn at
    # half coverage (q50 0.5) its size contrast falls below a limit just under it.
    s, bg = _linear(["#0000d0"])[0], _linear(["#ffff00"])[0]
    weights = np.array([0.2126, 0.7152, 0.0722])  # WCAG 2.2 relative luminance

    def size_contrast(a: float) -> float:
        shown = _ship(0.5 * np.clip(bg + a * (s - bg), 0, 1) + 0.5 * bg)  # as it ships
        y, yb = shown @ weights, bg @ weights
        return float((max(y, yb) + 0.05) / (min(y, yb) + 0.05))

    limit = size_contrast(1.0) - 0.02  # it reaches 1.778 at a = 2
    theme = Theme("t", (Canvas("yellow", "#ffff00"),))
    iconset, paints = _painted([Icon("a", "a.svg", "#0000d0", 1.0)], 1.0, 0.5)
    policy = Policy(rules=frozenset({Rule.THIN_STROKES}), min_size_contrast=limit)
    safe = largest_safe_alpha(audit(theme, iconset, paints), policy, precision=6)
    assert safe.alpha is not None and safe.limit is not None
    assert safe.limit.rule is Rule.THIN_STROKES and safe.limit.grid is None  # exact
    assert size_contrast(safe.alpha) >= limit - 1e-10
    # What ships steps at an 8-bit code crossing: above it on one side, below on the other.
    assert size_contrast(safe.limit.at + 1e-9) < limit <= size_contrast(safe.limit.at - 1e-9)
    sweep = np.linspace(1.0, safe.alpha, 2001)
    assert min(size_contrast(a) for a in sweep) >= limit


def _confused(
    linear: np.ndarray,
    roles: list[str],
    bg: np.ndarray,
    alphas: np.ndarray,
    level: float,
    moving: int,
) -> np.ndarray:
    """The gate's confusion rule written out, for the pairs of icon ``moving``: roles apart
    with every icon at alpha 1, not at ``alphas``.  ``alphas`` is ``(n,)`` (one set of
    coefficients) or ``(steps, n)`` (a sweep, judged in one vectorised pass); the verdict
    has the leading shape."""
    alphas = np.asarray(alphas, dtype=np.float64)
    k = alphas[..., :, None, None]  # (..., n, 1, 1) against (n, m, 3)
    shown = np.clip(bg[None] + k * (linear[:, None, :] - bg[None]), 0, 1)  # (..., n, m, 3)
    out = np.zeros(alphas.shape[:-1], dtype=bool)
    for i in range(len(roles)):
        for j in range(i + 1, len(roles)):
            if roles[i] != roles[j] and moving in (i, j):
                d_ref = _de(*(np.broadcast_to(linear[x], bg.shape) for x in (i, j)))
                d_now = _de(shown[..., i, :, :], shown[..., j, :, :])  # (..., m)
                out |= ((d_ref >= level) & (d_now < level - TOL_DE)).any(axis=-1)
    return out


@pytest.mark.parametrize("seed", range(8))
def test_one_colour_moving_is_judged_against_every_role_at_alpha_1(seed: int) -> None:
    """The others held at their own alpha (not 1): a pair they already confuse at a = 1 counts.

    (The reference was once the others at their alpha, so a colour whose partner was
    pushed into it was told it was safe up to 2.)
    """
    rng = np.random.default_rng(100 + seed)
    theme, iconset, linear = _random_case(seed)
    held = rng.uniform(1.0, 1.6, len(iconset.icons))
    icons = tuple(replace(i, alpha=float(a)) for i, a in zip(iconset.icons, held, strict=True))
    iconset = IconSet("s", icons)
    roles = [i.color_name or i.color for i in iconset.icons]
    policy = Policy(rules=frozenset({Rule.CONFUSION}), min_delta_e=20.0)
    for k, icon in enumerate(iconset.icons):
        safe = largest_safe_alpha(audit(theme, iconset), policy, icons=[icon.name], precision=3)
        level = policy.min_delta_e
        if safe.alpha is None:
            alphas = held.copy()
            alphas[k] = 1.0
            assert _confused(linear, roles, theme.backgrounds, alphas, level + TOL_DE, k)
            continue
        sweep = np.append(np.arange(1.0, safe.alpha, 5e-3), safe.alpha)
        alphas = np.tile(held, (len(sweep), 1))
        alphas[:, k] = sweep
        confused = _confused(linear, roles, theme.backgrounds, alphas, level, k)
        assert not confused.any(), (k, sweep[confused])
