"""What each gate rule is called, means and asks for, in the words every report uses.

One table per reader, each covering every :class:`~alpha_audit.policy.Rule`
(a test says so): SARIF rule ids (opaque, stable), one-line help, the fix, and
GitLab Code Quality severities.  The rules themselves (what fails) are stated
in :mod:`alpha_audit.policy`; this module only words them.
"""

from __future__ import annotations

from alpha_audit.policy import Rule

__all__ = ["RULE_FIX", "RULE_HELP", "RULE_IDS", "SEVERITY"]

# Rule ids are opaque and stable (SARIF 3.49.3: "ruleId" should not be the
# readable name, which lives in "name").  Never renumber: dashboards key on these.
RULE_IDS: dict[Rule, str] = {
    Rule.LOSS: "AA001",
    Rule.BELOW_THRESHOLD: "AA002",
    Rule.NEWLY_FAILING: "AA003",
    Rule.COLLISION: "AA004",
    Rule.NEW_COLLISION: "AA005",
    Rule.SEPARATION: "AA006",
    Rule.UNRENDERABLE: "AA007",
    Rule.FIXED_COLOUR: "AA008",
    Rule.NOT_AUDITED: "AA009",
    Rule.DRIFT: "AA010",
    Rule.LOCK: "AA011",
    Rule.CONFUSION: "AA012",
    Rule.THIN_STROKES: "AA013",
    Rule.CVD_COLLISION: "AA014",
    Rule.CVD_CONFUSION: "AA015",
}

RULE_HELP: dict[Rule, str] = {
    Rule.LOSS: "The icon's WCAG contrast on this canvas is lower at its alpha than at alpha 1.",
    Rule.BELOW_THRESHOLD: "The icon is below the contrast threshold on this canvas at its alpha.",
    Rule.NEWLY_FAILING: "The icon meets the threshold at alpha 1 but not at its alpha.",
    Rule.COLLISION: "Distinct source colours give the same 8-bit output on this canvas.",
    Rule.NEW_COLLISION: "Distinct colours collide at their alpha but not at alpha 1.",
    Rule.SEPARATION: "Two of the set's colours are closer than the minimum CIEDE2000.",
    Rule.UNRENDERABLE: "The icon's SVG could not be rendered.",
    Rule.FIXED_COLOUR: "The SVG hard-codes a paint colour that will not follow the theme.",
    Rule.NOT_AUDITED: "The SVG draws something the audit cannot judge (gradient, text, image).",
    Rule.DRIFT: "The paint's colour moves further than max-drift (CIEDE2000) at its alpha.",
    Rule.LOCK: "A locked brand colour changes by more than one just-noticeable difference.",
    Rule.CONFUSION: "Two palette roles told apart at alpha 1 are no longer told apart.",
    Rule.THIN_STROKES: "At a raster size the antialiased paint falls below min-size-contrast.",
    Rule.CVD_COLLISION: "Distinct colours newly look identical under simulated colour blindness.",
    Rule.CVD_CONFUSION: "Two roles are no longer told apart under simulated colour blindness.",
}

# What to do about each rule (help.markdown, shown by code-scanning dashboards).
RULE_FIX: dict[Rule, str] = {
    Rule.LOSS: (
        "Lower the icon's `alpha` (run `alpha-audit suggest` for the largest safe value "
        "per colour), or exempt the canvas with a reason."
    ),
    Rule.BELOW_THRESHOLD: (
        "Raise the icon's `alpha` above 1 where that helps, or pick a source colour "
        "with more contrast on this canvas."
    ),
    Rule.NEWLY_FAILING: (
        "Lower the icon's `alpha` back towards 1 (`alpha-audit suggest` gives the "
        "largest value that still passes)."
    ),
    Rule.COLLISION: "Move one of the colliding colours apart, or lower the set's `alpha`.",
    Rule.NEW_COLLISION: (
        "Lower the set's `alpha` below the value `alpha-audit suggest` reports, or move "
        "one of the colours apart."
    ),
    Rule.SEPARATION: (
        "Move the two closest colours apart, or lower the `alpha` that pulls them together."
    ),
    Rule.UNRENDERABLE: "Fix the SVG file (the message names the problem) or remove the icon.",
    Rule.FIXED_COLOUR: (
        "Paint with `currentColor` (or a theme token) instead of the fixed colour, or "
        "exempt the icon with a reason if the colour is meant to stay."
    ),
    Rule.NOT_AUDITED: (
        "Audit the element by hand, or draw it with plain fills and strokes the audit can read."
    ),
    Rule.DRIFT: (
        "Lower the icon's `alpha` towards 1 (drift is zero at 1), or raise `max-drift` "
        "if the shift is acceptable."
    ),
    Rule.LOCK: "Keep locked brand colours at `alpha: 1`, or remove the lock.",
    Rule.CONFUSION: (
        "Lower the `alpha` that pulls the two roles together, or move one role's colour "
        "further from the other."
    ),
    Rule.THIN_STROKES: (
        "Use a heavier stroke or a larger size, or a source colour with more contrast."
    ),
    Rule.CVD_COLLISION: "Move the two colours apart in lightness, not only in hue.",
    Rule.CVD_CONFUSION: (
        "Separate the two roles in lightness (CVD keeps lightness), or lower the `alpha`."
    ),
}


# Contrast that no longer meets the threshold is what the gate exists for;
# collisions and separation make icons hard to tell apart, a lesser harm.
SEVERITY: dict[Rule, str] = {
    Rule.LOSS: "major",
    Rule.BELOW_THRESHOLD: "major",
    Rule.NEWLY_FAILING: "major",
    Rule.COLLISION: "minor",
    Rule.NEW_COLLISION: "minor",
    Rule.SEPARATION: "minor",
    Rule.UNRENDERABLE: "major",
    Rule.FIXED_COLOUR: "minor",
    Rule.NOT_AUDITED: "info",
    Rule.DRIFT: "minor",
    Rule.LOCK: "major",
    Rule.CONFUSION: "major",
    Rule.THIN_STROKES: "minor",
    Rule.CVD_COLLISION: "minor",
    Rule.CVD_CONFUSION: "minor",
}
