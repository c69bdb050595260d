"""Issue 28 item 1: confusion as a graph.

Roles that pull each other under the separation floor move together; their joint answer
names the pair and the canvas that limit it, and is true of what the gate says.  The
reference scenario is the issue's: Tailwind 4's eight -500 accents at alpha 1.2 on 25
GitHub Primer canvases, where orange and red, moved alone, are held by amber.
"""

from __future__ import annotations

import itertools
import os
import shutil
from pathlib import Path

import numpy as np
import pytest
from coloraide import Color
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from typer.testing import CliRunner

from alpha_audit.cli import app
from alpha_audit.figures import ConfusionFigures
from alpha_audit.fixes import with_fixes
from alpha_audit.gate import evaluate
from alpha_audit.model import Canvas, Icon, IconSet, Theme
from alpha_audit.policy import Policy
from alpha_audit.render.common import fix_text
from alpha_audit.results import CheckReport, GroupFix
from alpha_audit.rows import AuditResult, audit, with_alphas
from alpha_audit.rules import Rule
from alpha_audit.suggest import suggest
from alpha_audit.suggest.engine import connected
from helpers import spec_hex, spec_ship

# tailwindcss 4.3.5 theme.css, the -500 accents (oklch), fitted to sRGB as `gamut: map`
# does (coloraide minde-chroma in OKLCH, JND 0.02) and written as the 8-bit codes.
TAILWIND = {
    "red": "#fb2c36",
    "orange": "#ff6900",
    "amber": "#fd9a00",
    "yellow": "#efb100",
    "green": "#00c950",
    "blue": "#2b7fff",
    "violet": "#8e51ff",
    "pink": "#f6339a",
}
# @primer/primitives 11.10.0, dist/css/functional/themes/{light,dark}.css: the bgColor
# tokens default, muted, emphasis, neutral-emphasis, disabled, neutral-muted and the
# accent, success, attention, severe, danger, done and sponsors -muted ones; a translucent
# one composited over its theme's bgColor-default (encoded sRGB, rounded).
PRIMER = {
    "light-default": "#ffffff",
    "light-muted": "#f6f8fa",
    "light-emphasis": "#25292e",
    "light-neutral-emphasis": "#59636e",
    "light-disabled": "#eff2f5",
    "light-neutral-muted": "#f0f1f2",
    "light-accent-muted": "#ddf4ff",
    "light-success-muted": "#dafbe1",
    "light-attention-muted": "#fff8c5",
    "light-severe-muted": "#fff1e5",
    "light-danger-muted": "#ffebe9",
    "light-done-muted": "#fbefff",
    "light-sponsors-muted": "#ffeff7",
    "dark-default": "#0d1117",
    "dark-muted": "#151b23",
    "dark-emphasis": "#3d444d",
    "dark-neutral-emphasis": "#656c76",
    "dark-disabled": "#212830",
    "dark-neutral-muted": "#1f232a",
    "dark-accent-muted": "#111d2e",
    "dark-success-muted": "#12261e",
    "dark-attention-muted": "#272215",
    "dark-severe-muted": "#221a19",
    "dark-danger-muted": "#25181c",
    "dark-done-muted": "#252139",
}
THEME = Theme("primer-25", tuple(Canvas(name, color) for name, color in PRIMER.items()))
ICONS = IconSet(
    "tailwind",
    tuple(Icon(f"{c}{n}", f"{c}{n}.svg", v, 1.2, c) for c, v in TAILWIND.items() for n in (1, 2)),
    TAILWIND,
)


def _de(a: str, b: str) -> float:
    """CIEDE2000 by coloraide: an independent path from the audit's colour-science one."""
    return float(Color(a).delta_e(Color(b), method="2000"))


def _shipped_hex(source: str, canvas: str, alpha: float) -> str:
    """The 8-bit colour shown, from the spec formulas (helpers), as hex."""
    s, b = spec_hex(source), spec_hex(canvas)
    linear = spec_ship(b + alpha * (s - b))
    encoded = np.where(linear <= 0.0031308, 12.92 * linear, 1.055 * linear ** (1 / 2.4) - 0.055)
    return "#" + "".join(f"{code:02x}" for code in np.rint(encoded * 255).astype(int).tolist())


def _involving(result: AuditResult, alphas: dict[str, float], icons: set[str], policy: Policy):  # type: ignore[no-untyped-def]
    """The gate's failing findings that involve ``icons``, with those ``alphas``."""
    gate = evaluate([with_alphas(result, alphas)], policy)
    return [f for f in gate.failures if set(f.icons) & icons]


def test_connected_joins_roles_through_any_pair() -> None:
    assert connected([("red", "orange"), ("amber", "yellow"), ("blue", "violet")]) == [
        ("orange", "red"),
        ("amber", "yellow"),
        ("blue", "violet"),
    ]
    assert connected([("a", "b"), ("c", "d"), ("b", "c"), ("e",)]) == [("a", "b", "c", "d")]
    assert connected([]) == []


def test_the_fix_of_orange_and_red_names_amber_and_the_pair_that_limits_it() -> None:
    result = audit(THEME, ICONS)
    policy = Policy()
    report = with_fixes(CheckReport(audits=(result,), gate=evaluate([result], policy)))
    confused = {
        ",".join(f.figures.roles): f for f in report.gate.failures if f.rule is Rule.CONFUSION
    }
    assert set(confused) == {"orange,red", "amber,yellow", "blue,violet"}
    # Orange and red alone are held by amber at 1.2: the group grows into amber and yellow,
    # and both confusions share its one fix.
    (k,) = confused["orange,red"].fixes
    assert confused["amber,yellow"].fixes == (k,)
    fix = report.fixes[k]
    assert isinstance(fix, GroupFix)
    assert fix.colors == ("red", "orange", "amber", "yellow")  # palette order
    assert fix.confused == ("red", "orange", "amber", "yellow")
    limit = fix.safe.limit
    assert fix.safe.alpha == 1.059 and limit is not None
    assert limit.roles == ("orange", "red") and limit.canvas == "light-default"
    assert fix_text(fix) == (
        "red, orange, amber and yellow together: alpha 1 to 1.059 (limited by orange and red "
        f"on light-default at {limit.at:.6f}), or move the colours apart"
    )
    assert "not even alpha 1" not in " ".join(fix_text(f) for f in report.fixes)
    # Independently (spec compositing, coloraide's CIEDE2000): orange and red on white are
    # 18.2 apart at alpha 1, at least 10 at the answer, and below 10 where the limit says.
    white = PRIMER["light-default"]
    orange, red = TAILWIND["orange"], TAILWIND["red"]
    assert _de(orange, red) == pytest.approx(18.23, abs=0.01)
    assert _de(_shipped_hex(orange, white, 1.059), _shipped_hex(red, white, 1.059)) >= 10
    assert _de(_shipped_hex(orange, white, limit.at), _shipped_hex(red, white, limit.at)) < 10
    # Why amber: orange at 1 is within the floor of amber held at 1.2 (both at 1: 15.7).
    amber = TAILWIND["amber"]
    assert _de(_shipped_hex(orange, white, 1.0), _shipped_hex(amber, white, 1.2)) < 10
    assert _de(orange, TAILWIND["amber"]) > 15
    # The gate agrees: the group at the answer, no confusion of its roles; at the limit, one.
    rule = Policy(rules=frozenset({Rule.CONFUSION}))
    group = {i.name for i in ICONS.icons if i.color_name in fix.colors}
    assert not _involving(result, dict.fromkeys(group, 1.059), group, rule)
    found = _involving(result, dict.fromkeys(group, limit.at), group, rule)
    assert [f.figures.roles for f in found] == [("orange", "red")]
    assert "light-default" in found[0].canvases


def test_a_confusion_names_every_icon_of_both_roles() -> None:
    result = audit(THEME, ICONS)
    gate = evaluate([result], Policy())
    confused = [f for f in gate.failures if isinstance(f.figures, ConfusionFigures)]
    (finding,) = [f for f in confused if f.figures.roles == ("orange", "red")]
    assert finding.icons == ("orange1", "orange2", "red1", "red2")


def test_a_role_at_two_alphas_names_only_the_icons_at_the_confused_one() -> None:
    alphas = {"orange1": 1.2, "orange2": 1.0, "red1": 1.2, "red2": 1.0}
    icons = IconSet(
        "s",
        tuple(Icon(n, f"{n}.svg", TAILWIND[n[:-1]], a, n[:-1]) for n, a in alphas.items()),
        {c: TAILWIND[c] for c in ("orange", "red")},
    )
    gate = evaluate([audit(THEME, icons)], Policy())
    (finding,) = [f for f in gate.failures if f.rule is Rule.CONFUSION]
    # Independently: which (orange, red) icon pairs come under 10 on some canvas.
    expected = {
        name
        for o, r in itertools.product(("orange1", "orange2"), ("red1", "red2"))
        if any(
            _de(
                _shipped_hex(TAILWIND["orange"], bg, alphas[o]),
                _shipped_hex(TAILWIND["red"], bg, alphas[r]),
            )
            < 10
            for bg in PRIMER.values()
        )
        for name in (o, r)
    }
    assert expected and expected != set(alphas)
    assert set(finding.icons) == expected


def test_suggest_groups_are_disjoint_and_closed() -> None:
    result = suggest(audit(THEME, ICONS), Policy(), scopes=("group",))
    groups = [g.colors for g in result.per_group]
    assert groups == [("red", "orange", "amber", "yellow"), ("blue", "violet")]
    for g in result.per_group:
        limit = g.safe.limit
        assert limit is not None and set(limit.roles) <= set(g.colors)
        assert set(g.icons) == {i.name for i in ICONS.icons if i.color_name in g.colors}


# -- the property: a joint answer is true of what the gate says ------------------------


def _oklch_hex(lightness: float, chroma: float, hue: float) -> str:
    colour = Color("oklch", [lightness, chroma, hue]).convert("srgb").fit("srgb", method="clip")
    return colour.to_string(hex=True)


@st.composite
def cases(draw: st.DrawFn) -> tuple[Theme, IconSet]:
    """Palettes that can confuse: accents of one lightness and chroma, hues 12-35 degrees
    apart (as a design system's -500 row), at alphas from 1 to 1.6, on 1-3 near-grey
    canvases of any lightness."""
    unit = st.floats(0.0, 1.0)
    canvases = [
        _oklch_hex(0.1 + 0.9 * draw(unit), 0.05 * draw(unit), 360 * draw(unit))
        for _ in range(draw(st.integers(1, 3)))
    ]
    lightness, chroma, hue = 0.5 + 0.3 * draw(unit), 0.1 + 0.15 * draw(unit), 360 * draw(unit)
    palette: dict[str, str] = {}
    for k in range(draw(st.integers(2, 6))):
        hue += 0.0 if k == 0 else 12 + 23 * draw(unit)
        palette[f"r{k}"] = _oklch_hex(lightness + 0.1 * draw(unit) - 0.05, chroma, hue)
    icons = tuple(
        Icon(f"i{k}", f"i{k}.svg", c, round(1.0 + 0.6 * draw(unit), 3), name)
        for k, (name, c) in enumerate(palette.items())
    )
    theme = Theme("t", tuple(Canvas(f"c{k}", c) for k, c in enumerate(dict.fromkeys(canvases))))
    return theme, IconSet("s", icons, palette)


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(cases(), st.sampled_from(["confusion", "default"]))
def test_a_joint_answer_passes_the_gate_and_the_next_step_fails(
    case: tuple[Theme, IconSet], which: str
) -> None:
    """Whenever a joint answer ``a`` is reported, the gate (check's code: rows, findings,
    gate) passes with the group at ``a`` and the others at their alpha, and fails at the
    next step of the answer's precision -- or, where the unsafe window closes again inside
    that step, at the first unsafe alpha the answer names, which lies in the step.  No
    answer means alpha 1 itself fails for the group."""
    theme, iconset = case
    policy = Policy(rules=frozenset({Rule.CONFUSION})) if which == "confusion" else Policy()
    result = audit(theme, iconset)
    found = suggest(result, policy, scopes=("group",), precision=3)
    unit = 1e-3
    for g in found.per_group:
        group = {i.name for i in iconset.icons if i.color_name in g.colors}
        a, limit = g.safe.alpha, g.safe.limit
        if a is None:
            assert limit is not None
            everyone_at_1 = {i.name: 1.0 for i in iconset.icons}
            assert _involving(result, everyone_at_1, group, policy), g
            continue
        assert not _involving(result, dict.fromkeys(group, a), group, policy), g
        if limit is None:
            continue
        assert limit.roles == () or set(limit.roles) <= set(g.colors)  # a closed group
        assert a < limit.at <= a + unit + 1e-12 or (not limit.attained and limit.at == a)
        step = round(a + unit, 3)
        if not _involving(result, dict.fromkeys(group, step), group, policy):
            assert limit.attained and limit.at < step, g  # a window inside the step
            assert _involving(result, dict.fromkeys(group, limit.at), group, policy), g


# -- --apply colour: a manifest the gate passes, or nothing ---------------------------

VIBRANT = Path(__file__).parents[2] / "examples" / "vibrant" / "svg"


def _project(tmp_path: Path, manifest: str) -> Path:
    (tmp_path / ".git").mkdir()
    shutil.copytree(VIBRANT, tmp_path / "svg")
    (tmp_path / "iconset.yaml").write_text(manifest)
    canvases = "".join(f'  - {{name: {n}, color: "{c}"}}\n' for n, c in PRIMER.items())
    (tmp_path / "theme.yaml").write_text(f"name: primer-25\ncanvases:\n{canvases}")
    return tmp_path


def _run(args: list[str], cwd: Path):  # type: ignore[no-untyped-def]
    old = Path.cwd()
    os.chdir(cwd)
    try:
        return CliRunner().invoke(app, args, catch_exceptions=False)
    finally:
        os.chdir(old)


TAILWIND_MANIFEST = (
    "name: tailwind\nicons: svg/*.svg\ncolor: cycle\nalpha: 1.2\npalette:\n"
    + "".join(f'  {c}: "{v}"\n' for c, v in TAILWIND.items())
)


def test_apply_colour_writes_a_manifest_check_passes(tmp_path: Path) -> None:
    root = _project(tmp_path, TAILWIND_MANIFEST)
    assert _run(["check", "theme.yaml", "iconset.yaml"], root).exit_code == 1
    res = _run(["suggest", "theme.yaml", "iconset.yaml", "--apply", "colour"], root)
    assert res.exit_code == 0, res.output
    assert "the gate passes with what was written" in res.stderr
    assert _run(["check", "theme.yaml", "iconset.yaml"], root).exit_code == 0


def test_apply_writes_nothing_when_no_alpha_can_pass(tmp_path: Path) -> None:
    root = _project(tmp_path, TAILWIND_MANIFEST)
    (root / "svg" / "bell.svg").write_text(
        "<svg xmlns='http://www.w3.org/2000/svg' viewBox='0 0 24 24'>"
        "<path d='M2 2h20v20H2z' fill='#123456'/></svg>"
    )
    before = (root / "iconset.yaml").read_text()
    res = _run(
        ["suggest", "theme.yaml", "iconset.yaml", "--apply", "colour", "--fail-on", "fixed-colour"],
        root,
    )
    assert res.exit_code == 1, res.output
    assert (root / "iconset.yaml").read_text() == before
    assert "wrote nothing to iconset.yaml: the gate would still fail" in res.stderr
    assert "fixed-colour of bell" in res.stderr


def test_a_report_without_the_set_wide_question_claims_no_set_wide_answer() -> None:
    from alpha_audit.render.common import RenderOptions
    from alpha_audit.render.suggest import render_markdown, render_table

    result = suggest(audit(THEME, ICONS), Policy(), scopes=("group",))
    for text in (
        render_table(result, RenderOptions(width=200)),
        render_markdown(result, RenderOptions()),
    ):
        assert "No safe alpha" not in text and "nothing breaks up to" not in text
        assert "the set-wide answer not asked" in text
        assert "red, orange, amber and yellow" in text and "(orange and red" in text
