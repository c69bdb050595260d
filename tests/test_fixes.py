"""Fixes, re-checked by an independent implementation.

The reference here is written from the specifications, not from our code:
CSS Color 4 sRGB transfer, WCAG 2.2 contrast, the paper's clipped extended
compositing, Ottosson's published Oklab matrices for OKLCH hue, and
colour-science's CIEDE2000 on CIELAB of the CSS Color 4 XYZ matrix.
"""

from __future__ import annotations

import json
import math
import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from alpha_audit.fixes import (
    nearest_passing_color,
    passes_everywhere,
    smallest_alpha_reaching,
    with_fixes,
)
from alpha_audit.gate import evaluate
from alpha_audit.model import Canvas, Icon, IconSet, Theme
from alpha_audit.policy import Policy
from alpha_audit.render.common import fix_to_dict
from alpha_audit.results import CheckReport
from alpha_audit.rows import audit
from alpha_audit.rules import Rule

with warnings.catch_warnings():
    warnings.simplefilter("ignore")
    import colour


# -- the independent reference ------------------------------------------------


def decode(v: np.ndarray) -> np.ndarray:
    v = np.asarray(v, dtype=float)
    return np.where(v <= 0.04045, v / 12.92, ((v + 0.055) / 1.055) ** 2.4)


def from_hex(text: str) -> np.ndarray:
    return decode(np.array([int(text[k : k + 2], 16) for k in (1, 3, 5)]) / 255.0)


def luminance(c: np.ndarray) -> np.ndarray:
    return c[..., 0] * 0.2126 + c[..., 1] * 0.7152 + c[..., 2] * 0.0722


def contrast(c1: np.ndarray, c2: np.ndarray) -> np.ndarray:
    y1, y2 = luminance(c1), luminance(c2)
    return (np.maximum(y1, y2) + 0.05) / (np.minimum(y1, y2) + 0.05)


def over(s: np.ndarray, b: np.ndarray, a: float | np.ndarray) -> np.ndarray:
    """The paper's composite, as it ships: 8-bit sRGB (CSS Color 4 encode, half to even)."""
    v = np.clip(b + np.asarray(a)[..., None] * (s - b), 0.0, 1.0)
    encoded = np.where(v <= 0.0031308, 12.92 * v, 1.055 * v ** (1 / 2.4) - 0.055)
    return decode(np.rint(encoded * 255.0) / 255.0)


# Ottosson, "A perceptual color space for image processing" (2020): linear sRGB -> LMS -> Oklab.
M1 = np.array(
    [
        [0.4122214708, 0.5363325363, 0.0514459929],
        [0.2119034982, 0.6806335040, 0.1073969566],
        [0.0883024619, 0.2817188376, 0.6299787005],
    ]
)
M2 = np.array(
    [
        [0.2104542553, 0.7936177850, -0.0040720468],
        [1.9779984951, -2.4285922050, 0.4505937099],
        [0.0259040371, 0.7827717662, -0.8086757660],
    ]
)


def oklch(lin: np.ndarray) -> np.ndarray:
    lab = np.cbrt(lin @ M1.T) @ M2.T
    return np.stack(
        [lab[..., 0], np.hypot(lab[..., 1], lab[..., 2]), np.arctan2(lab[..., 2], lab[..., 1])], -1
    )


def from_oklch(lch: np.ndarray) -> np.ndarray:
    lab = np.stack(
        [lch[..., 0], lch[..., 1] * np.cos(lch[..., 2]), lch[..., 1] * np.sin(lch[..., 2])], -1
    )
    return (lab @ np.linalg.inv(M2).T) ** 3 @ np.linalg.inv(M1).T


XYZ = np.array(
    [
        [506752 / 1228815, 87881 / 245763, 12673 / 70218],
        [87098 / 409605, 175762 / 245763, 12673 / 175545],
        [7918 / 409605, 87881 / 737289, 1001167 / 1053270],
    ]
)


def ciede2000(c1: np.ndarray, c2: np.ndarray) -> np.ndarray:
    white = np.array([0.3127, 0.3290])
    lab1 = colour.XYZ_to_Lab(np.asarray(c1) @ XYZ.T, white)
    lab2 = colour.XYZ_to_Lab(np.asarray(c2) @ XYZ.T, white)
    return np.asarray(colour.difference.delta_E_CIE2000(lab1, lab2))


def passes(c: np.ndarray, canvases: np.ndarray, alphas, threshold: float, loss: bool) -> np.ndarray:
    """(N,) whether each colour passes every canvas at every alpha."""
    ok = np.all((c >= 0) & (c <= 1), axis=-1)
    c = np.clip(c, 0, 1)
    for a in alphas:
        for b in canvases:
            now = contrast(over(c, b, np.full(c.shape[:-1], a)), b)
            ok &= now >= threshold
            if loss:  # against the same colour at alpha 1, as it ships
                ok &= now - contrast(over(c, b, np.ones(c.shape[:-1])), b) >= -1e-10
    return ok


# -- smallest alpha reaching the threshold -------------------------------------

hexes = st.integers(0, 0xFFFFFF).map(lambda n: f"#{n:06x}")
LIGHT = ["#ffffff", "#f6f8fa", "#fff8e1", "#e8eaed", "#dddddd"]
DARK = ["#000000", "#0d1117", "#1e1e2e", "#202124", "#3a3a3a"]


@settings(max_examples=60, deadline=None)
@given(
    canvases=st.lists(st.sampled_from([*LIGHT, *DARK, "#777777", "#3366cc"]), min_size=1),
    alphas=st.lists(st.sampled_from([1.0, 0.8, 1.25, 1.6]), min_size=1, max_size=3),
    seed=st.integers(0, 2**32 - 1),
)
def test_passes_everywhere_is_the_reference_on_every_canvas(
    canvases: list[str], alphas: list[float], seed: int
) -> None:
    """Colours dropped after a failing canvas (the hardest canvases are tried first) get
    the verdict of compositing each colour on every canvas in every style."""
    rng = np.random.default_rng(seed)
    colours = np.vstack([rng.uniform(-0.05, 1.05, (3000, 3)), rng.uniform(0, 0.02, (1000, 3))])
    bgs = np.array([from_hex(c) for c in canvases])
    only = Policy(rules=frozenset({Rule.BELOW_THRESHOLD}))
    expected = passes(colours, bgs, alphas, 3.0, loss=False).tolist()
    assert passes_everywhere(colours, bgs, alphas, 3.0, only).tolist() == expected
    few = colours[::40]  # too few to drop early: every canvas at once
    assert passes_everywhere(few, bgs, alphas, 3.0, only).tolist() == expected[::40]


@settings(max_examples=150)
@given(source=hexes, canvases=st.lists(st.sampled_from(LIGHT + DARK), min_size=1, max_size=4))
def test_smallest_alpha_reaching_3_to_1_is_tight(source: str, canvases: list[str]) -> None:
    s = from_hex(source)
    bgs = np.array([from_hex(c) for c in canvases])
    rounded, exact = smallest_alpha_reaching(s, bgs, 3.0, alpha_max=2.0, precision=3)
    grid = np.linspace(1.0, 2.0, 10_001)  # step 1e-4: ten points per unit of the 1e-3 answer
    reach = np.all(
        contrast(over(s, bgs[:, None, :], grid[None, :]), bgs[:, None, :]) >= 3.0, axis=0
    )
    if rounded is None:
        # Nothing on a fine grid reaches it either (up to a single-point touch).
        assert reach.sum() <= 1
        return
    assert exact is not None and 1.0 <= exact <= rounded <= exact + 1e-3 + 1e-12
    assert np.all(contrast(over(s, bgs, rounded), bgs) >= 3.0)
    if rounded - 1e-3 >= 1.0:
        assert not np.all(contrast(over(s, bgs, rounded - 1e-3), bgs) >= 3.0)
    # The exact infimum: a grid point just below it fails, the first passing grid point follows it.
    if exact > 1.0:
        below = grid[grid < exact - 1e-9]
        assert not reach[: below.size].any()
    first = grid[np.argmax(reach)] if reach.any() else None
    assert first is None or first >= exact - 1e-9


def test_smallest_alpha_reaching_known_value() -> None:
    # Linear grey 0.4 on white: Y(a) = 1 - 0.6 a; 3:1 needs Y <= 0.3, so a >= 7/6 in
    # float.  What ships is 8-bit: the first code at or below 0.3 is reached a little later.
    rounded, exact = smallest_alpha_reaching([0.4] * 3, [[1.0, 1.0, 1.0]], 3.0)
    white = np.ones((1, 3))
    assert exact is not None and 7 / 6 <= exact < 7 / 6 + 0.005
    assert contrast(over(np.full(3, 0.4), white, exact + 1e-9), white)[0] >= 3.0
    assert contrast(over(np.full(3, 0.4), white, exact - 1e-9), white)[0] < 3.0
    assert rounded == 1.170


def test_smallest_alpha_reaching_is_one_when_already_passing() -> None:
    assert smallest_alpha_reaching([0.0] * 3, [[1.0] * 3], 3.0) == (1.0, 1.0)


def test_smallest_alpha_reaching_none_when_unreachable() -> None:
    # An icon the colour of its canvas never moves; one far from white stops at black.
    assert smallest_alpha_reaching([0.5] * 3, [[0.5] * 3], 3.0) == (None, None)
    rounded, _ = smallest_alpha_reaching([0.9] * 3, [[1.0] * 3], 15.0)
    assert rounded is None


# -- nearest passing colour ---------------------------------------------------

CASES = [
    ("#ee7733", ["#ffffff", "#0d1117"], [1.0], Policy()),
    ("#66aaff", ["#ffffff", "#f6f8fa"], [1.0, 1.2], Policy()),
    ("#ffcc00", ["#ffffff"], [1.1], Policy(rules=frozenset({Rule.BELOW_THRESHOLD}))),
    ("#777777", ["#0d1117", "#3a3a3a"], [1.0], Policy()),
    ("#7733aa", ["#0d1117", "#1e1e2e"], [1.3], Policy()),
    ("#22bb66", ["#0d1117", "#ffffff", "#e8eaed"], [1.0], Policy()),
]


@pytest.mark.parametrize(("source", "canvases", "alphas", "policy"), CASES)
def test_nearest_passing_color_passes_and_none_is_much_closer(
    source: str, canvases: list[str], alphas: list[float], policy: Policy
) -> None:
    s = from_hex(source)
    bgs = np.array([from_hex(c) for c in canvases])
    loss = Rule.LOSS in policy.rules
    assert not passes(s[None], bgs, alphas, 3.0, loss)[0]  # a real fix is needed
    fix = nearest_passing_color(s, bgs, alphas, 3.0, policy)
    assert fix is not None
    found = from_hex(fix.color)
    assert passes(found[None], bgs, alphas, 3.0, loss)[0]
    assert fix.delta_e == pytest.approx(float(ciede2000(found, s)), abs=1e-9)
    # Hue kept (8-bit rounding aside).
    _, c0, h0 = oklch(s)
    _, c1, h1 = oklch(found)
    if c0 > 0.02 and c1 > 0.02:
        assert abs((h1 - h0 + math.pi) % (2 * math.pi) - math.pi) < math.radians(3)
    # Sample the source's hue: globally, and densely around the answer.
    rng = np.random.default_rng(7)
    lc = np.column_stack([rng.uniform(0, 1, 60_000), rng.uniform(0, 0.4, 60_000)])
    _, c_fix, _ = oklch(found)
    l_fix = oklch(found)[0]
    local = np.column_stack(
        [l_fix + rng.normal(0, 0.02, 60_000), np.abs(c_fix + rng.normal(0, 0.02, 60_000))]
    )
    lc = np.vstack([lc, local])
    samples = from_oklch(np.column_stack([lc, np.full(len(lc), h0)]))
    ok = passes(samples, bgs, alphas, 3.0, loss)
    assert ok.any()
    closest = float(ciede2000(samples[ok], s).min())
    assert closest >= fix.delta_e - 0.5


def test_nearest_passing_color_is_the_source_when_it_passes() -> None:
    fix = nearest_passing_color(from_hex("#000000"), [[1.0, 1.0, 1.0]], [1.0], 3.0)
    assert fix is not None and fix.color == "#000000" and fix.delta_e == 0.0


def test_nearest_passing_color_grey_stays_grey() -> None:
    fix = nearest_passing_color([0.4] * 3, [[1.0, 1.0, 1.0]], [1.0], 3.0)
    assert fix is not None
    assert len(set(fix.color[1:3] + fix.color[3:5] + fix.color[5:7])) <= 2  # #rrrrrr
    assert fix.color[1:3] == fix.color[3:5] == fix.color[5:7]


def test_nearest_passing_color_none_when_impossible() -> None:
    # 21:1 on white and black at once: no colour at all.
    assert nearest_passing_color(from_hex("#ee7733"), [[1.0] * 3, [0.0] * 3], [1.0], 21.0) is None


# -- fixes for a report --------------------------------------------------------


def fixes_for(report: CheckReport, **options: float) -> tuple:  # type: ignore[type-arg]
    """The fixes the pipeline attaches (:func:`with_fixes`)."""
    return with_fixes(report, **options).fixes  # type: ignore[arg-type]


def _report(policy: Policy) -> CheckReport:
    theme = Theme(
        "t",
        (Canvas("white", "#ffffff"), Canvas("paper", "#f6f8fa"), Canvas("ink", "#0d1117")),
    )
    icons = IconSet(
        "s",
        (
            Icon("a", "a.svg", "#ffcc00", 1.2, color_name="warn", color_line=3),
            Icon("b", "b.svg", "#ffcc00", 1.2, color_name="warn", color_line=3),
            Icon("c", "c.svg", "#000000", 1.0, color_name="ink"),
        ),
    )
    result = audit(theme, icons)
    return CheckReport(audits=(result,), gate=evaluate([result], policy))


def test_fixes_for_every_failing_color_and_canvas() -> None:
    report = _report(Policy(rules=frozenset({Rule.BELOW_THRESHOLD})))
    fixes = fixes_for(report, alpha_max=3.0)  # red cannot move on white: yellow needs a > 2
    failing = {(c, name) for f in report.gate.failures for c in f.canvases for name in f.icons}
    # Yellow fails on both light canvases (one fix for the light mode, computed on
    # the worst of them), black on the dark one.
    assert {(fx.color, fx.mode) for fx in fixes} == {("warn", "light"), ("ink", "dark")}
    assert next(fx for fx in fixes if fx.color == "warn").canvas in ("white", "paper")
    assert {("white", "a"), ("paper", "b"), ("ink", "c")} <= failing
    warn = next(fx for fx in fixes if fx.color == "warn")
    assert warn.icons == ("a", "b") and warn.line == 3 and warn.mode == "light"
    assert warn.reach.canvases == ("white", "paper")
    # Yellow on white needs a darker yellow; a > 1 moving away from white gets there.
    assert warn.reach.alpha is not None
    bgs = np.array([from_hex("#ffffff"), from_hex("#f6f8fa")])
    assert np.all(contrast(over(from_hex("#ffcc00"), bgs, warn.reach.alpha), bgs) >= 3.0)
    assert warn.nearest is not None
    all_bgs = np.array([from_hex(c) for c in ("#ffffff", "#f6f8fa", "#0d1117")])
    assert passes(from_hex(warn.nearest.color)[None], all_bgs, [1.2], 3.0, False)[0]
    ink = next(fx for fx in fixes if fx.color == "ink")
    assert ink.reach.alpha is None  # black on a dark canvas: no alpha helps
    # JSON-ready: strict JSON accepts it.
    import json

    json.dumps([fix_to_dict(fx) for fx in fixes], allow_nan=False)


def test_fixes_for_skips_exempted_findings() -> None:
    from alpha_audit.policy import Exemption

    policy = Policy(
        rules=frozenset({Rule.BELOW_THRESHOLD}),
        exemptions=(Exemption("dark canvas is decorative", canvas="ink"),),
    )
    assert all(fx.canvas != "ink" for fx in fixes_for(_report(policy)))


def test_fixes_for_passing_report_is_empty() -> None:
    assert fixes_for(_report(Policy(rules=frozenset()))) == ()


def test_json_report_carries_the_fixes() -> None:
    import json

    from alpha_audit.render import RenderOptions
    from alpha_audit.render.json import render_report

    report = with_fixes(_report(Policy(rules=frozenset({Rule.BELOW_THRESHOLD}))))
    doc = json.loads(render_report(report, RenderOptions()))
    fixes = doc["gate"]["fixes"]
    assert [(f["color"], f["canvas"]) for f in fixes] == [
        (fx.color, fx.canvas) for fx in fixes_for(report)
    ]
    warn = next(f for f in fixes if f["color"] == "warn")
    assert warn["nearest_color"]["color"].startswith("#")
    assert warn["smallest_alpha_reaching"]["mode"] == "light"
    # Each failure points at the fixes of its icons' colours on its canvas.
    colour = {"a": "warn", "b": "warn", "c": "ink"}
    for failure in doc["gate"]["failures"]:
        named = {(fixes[k]["color"], fixes[k]["canvas"]) for k in failure["fixes"]}
        assert named == {(colour[i], failure["canvas"]) for i in failure["icons"]}


def test_with_fixes_carries_them_and_renderers_use_them() -> None:
    from dataclasses import replace as dc_replace

    report = _report(Policy(rules=frozenset({Rule.BELOW_THRESHOLD})))
    assert report.fixes == ()
    carried = with_fixes(report)
    assert carried.fixes == fixes_for(report)
    assert all(f.fixes for f in carried.gate.failures)
    # What is carried is what renderers show: no fixes at all, none in the JSON.
    from alpha_audit.render import RenderOptions
    from alpha_audit.render.json import render_report

    doc = json.loads(render_report(dc_replace(carried, fixes=()), RenderOptions()))
    assert doc["gate"]["fixes"] == [] and all(f["fixes"] == [] for f in report_json(report))


def report_json(report: CheckReport) -> list[dict]:  # type: ignore[type-arg]
    from alpha_audit.render import RenderOptions
    from alpha_audit.render.json import render_report

    return json.loads(render_report(report, RenderOptions()))["gate"]["failures"]  # type: ignore[no-any-return]
