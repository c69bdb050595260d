"""One set of words for a colour's largest safe alpha, whichever path computed it.

Beyond the colours :mod:`alpha_audit.fixes` answers, the table and the PR comment
fall back to :func:`~alpha_audit.render.markdown.safe_alpha_fixes`; on 3,470
simple-icons logos one "How to fix" list mixed "#dd0700: alpha at most 1" with
"#ff000f: largest safe alpha 1.000" for the same kind of answer.
"""

from __future__ import annotations

from pathlib import Path

from alpha_audit.audit import audit
from alpha_audit.fixes import describe_fix, fixes_for
from alpha_audit.gate import CheckReport, evaluate
from alpha_audit.model import Canvas, Icon, IconSet, Theme
from alpha_audit.policy import Policy, Rule
from alpha_audit.render.markdown import safe_alpha_fixes

# Blue at 1.6 loses contrast on mid grey (clipping in linear sRGB).
THEME = Theme("grey", (Canvas("mid", "#777777"),))
ICONS = IconSet(
    "set",
    tuple(Icon(f"b{k}", Path(f"b{k}.svg"), "#0000cc", 1.6, color_name="blue") for k in range(3)),
    palette={"blue": "#0000cc"},
)


def test_fallback_and_computed_fix_use_the_same_words() -> None:
    result = audit(THEME, ICONS)
    report = CheckReport(
        audits=(result,), gate=evaluate([result], Policy(rules=frozenset({Rule.LOSS})))
    )
    finding = report.gate.failures[0]
    fallback = safe_alpha_fixes(report)(finding)
    computed = [describe_fix(f) for f in fixes_for(report)]
    assert fallback is not None and fallback.startswith("blue: alpha 1")
    assert "largest safe alpha" not in fallback
    # The fallback's span is the computed fix's first option.
    assert all(text.startswith(fallback) for text in computed), (fallback, computed)
