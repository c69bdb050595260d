"""One set of words for a fix, whichever rule it answers.

On 3,470 simple-icons logos one "How to fix" list once mixed "#dd0700: alpha at
most 1" with "#ff000f: largest safe alpha 1.000" for the same kind of answer;
every fix is now computed once in the pipeline and worded by one function.
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

from alpha_audit.fixes import with_fixes
from alpha_audit.gate import evaluate
from alpha_audit.model import Canvas, Icon, IconSet, Theme
from alpha_audit.policy import Policy
from alpha_audit.render.common import finding_fix, fix_text
from alpha_audit.results import CheckReport, ColorFix, GroupFix
from alpha_audit.rows import audit
from alpha_audit.rules import Rule

# Blue at 1.6 loses contrast on mid grey (clipping in linear sRGB).
THEME = Theme("grey", (Canvas("mid", "#777777"),))
ICONS = IconSet(
    "set",
    tuple(Icon(f"b{k}", Path(f"b{k}.svg"), "#0000cc", 1.6, color_name="blue") for k in range(3)),
    palette={"blue": "#0000cc"},
)


def _fixed(iconset: IconSet, policy: Policy) -> CheckReport:
    result = audit(THEME, iconset)
    return with_fixes(CheckReport(audits=(result,), gate=evaluate([result], policy)))


def test_a_loss_names_the_colours_safe_span() -> None:
    report = _fixed(ICONS, Policy(rules=frozenset({Rule.LOSS})))
    finding = report.gate.failures[0]
    (fix,) = (report.fixes[k] for k in finding.fixes)
    assert isinstance(fix, ColorFix) and fix.color == "blue"
    text = finding_fix(finding, report)
    assert text == fix_text(fix) and text.startswith("blue: alpha 1")
    assert "largest safe alpha" not in text


def test_two_confused_roles_get_their_joint_answer() -> None:
    white = Theme("w", (Canvas("white", "#ffffff"),))
    icons = IconSet(
        "set",
        (
            Icon("alert", Path("a.svg"), "#bc4c00", 1.15, color_name="severe"),
            Icon("stop", Path("s.svg"), "#d1242f", 1.15, color_name="danger"),
        ),
        palette={"severe": "#bc4c00", "danger": "#d1242f"},
    )
    result = audit(white, icons)
    report = with_fixes(
        CheckReport(
            audits=(result,), gate=evaluate([result], Policy(rules=frozenset({Rule.CONFUSION})))
        )
    )
    finding = report.gate.failures[0]
    (fix,) = (report.fixes[k] for k in finding.fixes)
    # The group in palette order; the pair that limits it, the canvas and where, named.
    assert isinstance(fix, GroupFix) and fix.colors == ("severe", "danger")
    assert fix.safe.alpha is not None and 1.0 <= fix.safe.alpha < 1.15
    assert fix.safe.limit is not None and fix.safe.limit.roles == ("danger", "severe")
    assert finding_fix(finding, report).startswith("severe and danger together: alpha 1 to ")
    assert f"(limited by danger and severe on white at {fix.safe.limit.at:.6f})" in fix_text(fix)
    # The joint answer passes the gate; just above it fails.
    both = {"alert": fix.safe.alpha, "stop": fix.safe.alpha}
    from alpha_audit.rows import with_alphas

    policy = report.gate.policy
    assert evaluate([with_alphas(result, both)], policy).passed
    assert fix.safe.limit is not None
    above = {k: fix.safe.limit.at + 1e-6 for k in both}
    assert not evaluate([with_alphas(result, above)], policy).passed


def test_no_safe_alpha_says_not_even_1_only_when_1_itself_fails() -> None:
    """A colour held at 1 by others keeping their alpha is named so; alpha 1 may pass."""
    from alpha_audit.results import Limit, ReachAlpha, SafeAlpha

    limit = Limit(Rule.NEW_COLLISION, "white", ("a", "b"), 1.0, True)
    fix = ColorFix(
        theme="t",
        iconset="s",
        color="#ee7733",
        source="#ee7733",
        canvas="white",
        mode="light",
        icons=("a",),
        rules=(Rule.LOSS,),
        largest_safe=SafeAlpha(None, None, limit),
        reach=ReachAlpha("light", ("white",), 3.0, None, None),
        nearest=None,
        held=("#ff7f36",),
    )
    assert fix_text(fix) == (
        "#ee7733: no alpha from 1 is safe while #ff7f36 keeps its alpha; move the colours apart"
    )
    assert fix_text(replace(fix, held=())) == "#ee7733: not even alpha 1 passes; change the colour"
    together = replace(fix, largest_safe=SafeAlpha(1.05, 1.05, limit), together=("b", "c"))
    assert fix_text(together) == "#ee7733: alpha 1 to 1.05 together with b and c"


def test_a_fix_two_modes_share_is_said_once() -> None:
    """One fix per mode: blue at 1.6 loses contrast on a light and on a dark mid grey, and
    both modes' fixes read alike (the 3,470 simple-icons logos printed "#0500be: alpha 1 to
    1.001; #0500be: alpha 1 to 1.001")."""
    theme = Theme(
        "two", (Canvas("light-mid", "#777777", "light"), Canvas("dark-mid", "#787878", "dark"))
    )
    result = audit(theme, ICONS)
    report = with_fixes(
        CheckReport(audits=(result,), gate=evaluate([result], Policy(rules=frozenset({Rule.LOSS}))))
    )
    finding = report.gate.failures[0]
    texts = [fix_text(report.fixes[k]) for k in finding.fixes]
    assert len(texts) == 2 and texts[0] == texts[1]  # one per mode, the same words
    assert finding_fix(finding, report) == texts[0]
