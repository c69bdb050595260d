"""A page audit judged: the measured paints, the gate over their findings, and the fixes.

:func:`judge_pages` is ``alpha-audit render`` after the browsers are done: the
measured paints become findings (:mod:`alpha_audit.pages.findings`), the one
gate (:func:`alpha_audit.gate.judge`) decides the verdict against the policy
and the baseline, and each failing ``below-threshold`` finding gets its fix
once (:mod:`alpha_audit.fixes`' engines), so renderers only format a
:class:`PageReport`.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, replace

import numpy as np

from alpha_audit.color import hex_to_linear
from alpha_audit.findings import Finding, FindingKey
from alpha_audit.gate import Baseline, CanvasKey, GateResult, judge
from alpha_audit.model import IconSet
from alpha_audit.pages.findings import RENDER_DRIFT_TOLERANCE, paint_findings
from alpha_audit.pages.measured import RenderResult
from alpha_audit.policy import Policy
from alpha_audit.results import CheckReport, ColorFix, NearestColor, ReachAlpha, SafeAlpha
from alpha_audit.rules import RENDER_DEFAULT_RULES, RENDER_DEFAULT_WARNINGS, Rule

__all__ = ["RENDER_POLICY", "PageReport", "judge_pages"]

# render's gate without a config: below-threshold fails, render-drift is reported
# (rules.py: each rule's ``render`` level).
RENDER_POLICY = Policy(rules=RENDER_DEFAULT_RULES, warnings=RENDER_DEFAULT_WARNINGS)
MAX_PAGE_FIXES = 50  # fixes.MAX_FIXED_COLORS's budget: about 0.1 s per failing colour


@dataclass(frozen=True)
class PageReport:
    """What ``render`` produces: the measured paints, the gate over them, the fixes.

    Each failing finding names its fixes by index
    (:attr:`~alpha_audit.findings.Finding.fixes`), as in a ``check`` report.
    """

    result: RenderResult
    gate: GateResult
    fixes: tuple[ColorFix, ...] = ()
    fixes_left_out: int = 0

    def as_check(self) -> CheckReport:
        """The gate and fixes as a :class:`CheckReport` with no rows, for the CI formats."""
        return CheckReport((), self.gate, self.fixes, self.fixes_left_out)


def _fix(f: Finding, iconset: IconSet | None) -> ColorFix | None:
    """The fix of one failing ``below-threshold`` finding, from its worst paint's figures.

    Where the page draws what the manifest says (drift within the tolerance), the
    manifest's colour at its alpha and opacity on the measured backdrop: the smallest
    alpha from 1 reaching the threshold (the linear pipeline; CSS cannot draw an
    alpha above 1) and the nearest passing colour.  Where it draws another colour
    (a CSS override) or maps to no manifest icon, the nearest passing colour to the
    colour drawn: the manifest is not what needs changing.
    """
    from alpha_audit.fixes import nearest_passing_color, smallest_alpha_reaching

    n = f.numbers
    behind, drawn = n.get("background"), n.get("drawn")
    if not isinstance(behind, str) or not isinstance(drawn, str):
        return None
    by_name = {i.name: i for i in iconset.icons} if iconset is not None else {}
    icon = by_name.get(f.icons[0])
    drift = n.get("render_drift")
    faithful = icon is not None and isinstance(drift, float) and drift <= RENDER_DRIFT_TOLERANCE
    backdrop = hex_to_linear(behind)[np.newaxis]
    threshold = float(n["threshold"])
    policy = Policy(rules=frozenset({Rule.BELOW_THRESHOLD}))
    mode = f"{f.theme} backdrop"
    reach_alpha = reach_exact = None
    if icon is not None and faithful:
        alpha, opacity = float(n.get("alpha", 1.0)), float(n.get("opacity", 1.0))
        source, color = icon.linear, f"{icon.name} ({icon.color})"
        if n.get("pipeline") == "linear":
            reach_alpha, reach_exact = smallest_alpha_reaching(
                source, backdrop, threshold, opacities=opacity
            )
        nearest: NearestColor | None = nearest_passing_color(
            source, backdrop, [[alpha, opacity]], threshold, policy
        )
    else:
        source, color = tuple(hex_to_linear(drawn).tolist()), f"the drawn {drawn}"
        nearest = nearest_passing_color(source, backdrop, [1.0], threshold, policy)
    return ColorFix(
        theme=f.theme,
        iconset=f.iconset,
        color=color,
        source=drawn if not faithful else str(n.get("source", drawn)),
        canvas=behind,
        mode=mode,
        icons=f.icons,
        rules=(f.rule,),
        largest_safe=SafeAlpha(None, None, None),  # a page has no alpha range to keep
        reach=ReachAlpha(mode, (behind,), threshold, reach_alpha, reach_exact),
        nearest=nearest,
        manifest=iconset.path if faithful and iconset is not None else None,
        line=icon.color_line if faithful and icon is not None else None,
    )


def judge_pages(
    result: RenderResult,
    policy: Policy = RENDER_POLICY,
    iconset: IconSet | None = None,
    *,
    baseline: Baseline | Iterable[FindingKey | CanvasKey] | None = None,
    fixes: bool = True,
) -> PageReport:
    """The gate over ``result``'s measured paints, with a fix per failing contrast finding.

    ``iconset`` is the manifest the icons were mapped to (findings point at its
    lines).  Page states that could not be audited are counted as the gate's
    ``problems``; the verdict itself is the findings' (``render`` exits 2 for them).
    """
    found = paint_findings(result.paints, policy, iconset)
    gate = replace(judge([], policy, found, baseline), problems=len(result.problems), audited=None)
    if not fixes:
        return PageReport(result, gate)
    answers: list[ColorFix] = []
    index: dict[tuple[object, ...], int] = {}
    left_out = 0
    judged = []
    for f in gate.findings:
        if not (f.fails and f.rule is Rule.BELOW_THRESHOLD):
            judged.append(f)
            continue
        n = f.numbers
        question = (f.icons[0], n.get("drawn"), n.get("background"), n.get("render_drift"))
        if question not in index:
            if len(answers) >= MAX_PAGE_FIXES:
                left_out += 1
                judged.append(f)
                continue
            fix = _fix(f, iconset)
            if fix is None:
                judged.append(f)
                continue
            index[question] = len(answers)
            answers.append(fix)
        judged.append(replace(f, fixes=(index[question],)))
    gate = replace(gate, findings=tuple(judged))
    return PageReport(result, gate, tuple(answers), left_out)
