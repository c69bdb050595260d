"""Every gate rule, once: its name, report ids, default, help and fix wording.

One :class:`RuleSpec` per :class:`Rule` drives everything about it: the
``--fail-on`` choices and their help, the default policy, SARIF rule ids
(opaque and stable), GitLab Code Quality severities, the docs table
(``docs/rules.md``, checked by a test) and the advice every report prints.
What a rule *objects to* is stated in :mod:`alpha_audit.policy` (numbers) and
:mod:`alpha_audit.findings` (findings); this module only names and words it.
"""

from __future__ import annotations

import difflib
from collections.abc import Iterable
from dataclasses import dataclass, field
from enum import StrEnum
from typing import Literal

from alpha_audit.errors import UsageError

__all__ = [
    "CHECK_RULES",
    "CONTRAST_RULES",
    "DEFAULT_RULES",
    "DEFAULT_WARNINGS",
    "RENDER_DEFAULT_RULES",
    "RENDER_DEFAULT_WARNINGS",
    "RENDER_RULES",
    "RULES",
    "Family",
    "Fixer",
    "Level",
    "Rule",
    "RuleSpec",
    "did_you_mean",
    "rules_table",
]


class Rule(StrEnum):
    """A kind of finding the gate can fail on (or report)."""

    LOSS = "loss"
    BELOW_THRESHOLD = "below-threshold"
    NEWLY_FAILING = "newly-failing"
    COLLISION = "collision"
    NEW_COLLISION = "new-collision"
    SEPARATION = "separation"
    UNRENDERABLE = "unrenderable"
    FIXED_COLOUR = "fixed-colour"
    NOT_AUDITED = "not-audited"
    DRIFT = "drift"
    LOCK = "lock"
    CONFUSION = "confusion"
    THIN_STROKES = "thin-strokes"
    CVD_COLLISION = "cvd-collision"
    CVD_CONFUSION = "cvd-confusion"
    RENDER_DRIFT = "render-drift"
    NEAR_DUPLICATE = "near-duplicate"

    @classmethod
    def parse(cls, text: str, flag: str | None = None) -> Rule:
        """A rule by name; unknown names raise :class:`UsageError` listing the valid ones."""
        name = text.strip().lower()
        try:
            return cls(name)
        except ValueError:
            names = [r.value for r in cls]
            where = f"{flag}: " if flag else ""
            raise UsageError(
                f"{where}unknown rule {text!r}; {did_you_mean(name, names)}"
                f"use one of: {', '.join(names)}"
            ) from None


class Level(StrEnum):
    """What the gate does with a rule's findings: nothing, report them, or fail on them."""

    OFF = "off"
    WARN = "warn"
    FAIL = "fail"


Severity = Literal["info", "minor", "major"]


class Family(StrEnum):
    """What a rule judges; its findings carry that family's figures (:mod:`alpha_audit.figures`)."""

    CONTRAST = "contrast"  # one paint's contrast on a canvas
    COLLISION = "collision"  # colours sharing one 8-bit output
    SEPARATION = "separation"  # the closest two colours of the set
    CONFUSION = "confusion"  # two palette roles no longer told apart
    CVD_COLLISION = "cvd-collision"  # colours alike under a simulated deficiency
    DRIFT = "drift"  # one paint's colour moved by its alpha
    THIN_STROKES = "thin-strokes"  # antialiased ink at a raster size
    SVG = "svg"  # what an SVG draws, whatever the alpha
    RENDER_DRIFT = "render-drift"  # a browser draws another colour than the model


# What answers a failing finding (alpha_audit.fixes): a fix of one paint's colour
# (its largest safe alpha, reaching alpha and nearest colour), or the joint alpha of a
# group of colours.
Fixer = Literal["colour", "group"]


@dataclass(frozen=True)
class RuleSpec:
    """Everything said about one rule.

    ``sarif_id`` is opaque and stable (SARIF 2.1.0, 3.49.3: ``ruleId`` should
    not be the readable name, which lives in ``name``): never renumber,
    dashboards key on it.  ``severity`` is GitLab Code Quality's; ``default``
    what ``check``'s gate does without a policy, ``render`` what ``alpha-audit
    render``'s gate does (``None``: rows measured in a browser never raise it);
    ``help`` one line for ``--help`` and code-scanning dashboards; ``fix`` what
    to do about a finding.

    ``family`` says what the rule judges (and which figures its findings
    carry); ``closed_form`` whether ``suggest`` finds the alpha where it
    starts to object exactly (else it brackets it on a grid and re-checks);
    ``fixed_by`` which fix answers a failing finding (``None``: no alpha or
    colour fix); ``reach_clears`` whether the smallest alpha reaching the
    threshold clears it (contrast below the threshold; not a loss, which can
    stay lower than at alpha 1).
    """

    rule: Rule
    sarif_id: str
    severity: Severity
    default: Level
    help: str
    fix: str
    render: Level | None = None
    # Raised only from a browser's pixels (``render``): ``check`` and ``suggest`` refuse it.
    browser_only: bool = False
    family: Family = field(kw_only=True)
    closed_form: bool = field(default=True, kw_only=True)
    fixed_by: Fixer | None = field(default=None, kw_only=True)
    reach_clears: bool = field(default=False, kw_only=True)


# Contrast that no longer meets the threshold is what the gate exists for;
# collisions and separation make icons hard to tell apart, a lesser harm.
_SPECS = (
    RuleSpec(
        Rule.LOSS,
        "AA001",
        "major",
        Level.FAIL,
        "The paint's WCAG contrast on this canvas is lower at its alpha than at alpha 1 "
        "(a paint below visibility-floor at alpha 1, or a loss within loss-tolerance, is "
        "reported, not gated).",
        "Lower the icon's `alpha` (`alpha-audit suggest` gives the largest safe value per "
        "colour), or exempt the canvas with a reason.",
        family=Family.CONTRAST,
        fixed_by="colour",
    ),
    RuleSpec(
        Rule.BELOW_THRESHOLD,
        "AA002",
        "major",
        Level.OFF,
        "The paint is below the contrast threshold on this canvas at its alpha.",
        "Raise the icon's `alpha` above 1 where that helps, or pick a source colour with "
        "more contrast on this canvas.",
        # On a page the worst measured pixel is the contrast shown: the gate exists for it.
        render=Level.FAIL,
        family=Family.CONTRAST,
        fixed_by="colour",
        reach_clears=True,
    ),
    RuleSpec(
        Rule.NEWLY_FAILING,
        "AA003",
        "major",
        Level.FAIL,
        "The paint meets the threshold at alpha 1 but not at its alpha.",
        "Lower the icon's `alpha` back towards 1 (`alpha-audit suggest` gives the largest "
        "value that still passes).",
        family=Family.CONTRAST,
        fixed_by="colour",
        reach_clears=True,
    ),
    RuleSpec(
        Rule.COLLISION,
        "AA004",
        "minor",
        Level.OFF,
        "Distinct colours give the same 8-bit output on this canvas.",
        "Move one of the colliding colours apart, or lower the set's `alpha`.",
        family=Family.COLLISION,
        fixed_by="group",
    ),
    RuleSpec(
        Rule.NEW_COLLISION,
        "AA005",
        "minor",
        Level.FAIL,
        "Colours told apart at alpha 1 (CIEDE2000 at least near-duplicate-delta-e) share one "
        "8-bit output at their alpha.",
        "Lower the set's `alpha` below the value `alpha-audit suggest` reports, or move one "
        "of the colours apart.",
        family=Family.COLLISION,
        fixed_by="group",
    ),
    RuleSpec(
        Rule.SEPARATION,
        "AA006",
        "minor",
        Level.OFF,
        "Two of the set's colours are closer than the minimum CIEDE2000.",
        "Move the two closest colours apart, or lower the `alpha` that pulls them together.",
        family=Family.SEPARATION,
        closed_form=False,
        fixed_by="group",
    ),
    RuleSpec(
        Rule.UNRENDERABLE,
        "AA007",
        "major",
        Level.WARN,
        "The icon's SVG could not be rendered.",
        "Fix the SVG file (the message names the problem) or remove the icon.",
        family=Family.SVG,
    ),
    RuleSpec(
        Rule.FIXED_COLOUR,
        "AA008",
        "minor",
        Level.WARN,
        "The SVG hard-codes a paint colour that will not follow the theme.",
        "Paint with `currentColor` (or a theme token) instead of the fixed colour, or exempt "
        "the icon with a reason if the colour is meant to stay.",
        family=Family.SVG,
    ),
    RuleSpec(
        Rule.NOT_AUDITED,
        "AA009",
        "info",
        # Listed by default (issue 28): an icon the audit cannot judge never passes silently.
        Level.WARN,
        "The SVG draws something the audit cannot judge (a gradient, text, an image, `<use>`); "
        "on a page, no pixel shows a paint at full coverage (a hairline). It is not audited.",
        "Audit the element by hand, or draw it with plain fills and strokes the audit can read "
        "(on a page: strokes of at least 1 CSS px).",
        # A paint a browser drew too thin to measure is said, never passed in silence.
        render=Level.WARN,
        family=Family.SVG,
    ),
    RuleSpec(
        Rule.DRIFT,
        "AA010",
        "minor",
        Level.OFF,
        "The paint's colour moves further than max-drift (CIEDE2000) at its alpha.",
        "Lower the icon's `alpha` towards 1 (drift is zero at 1), or raise `max-drift` if the "
        "shift is acceptable.",
        family=Family.DRIFT,
        closed_form=False,
        fixed_by="colour",
    ),
    RuleSpec(
        Rule.LOCK,
        "AA011",
        "major",
        Level.OFF,
        "A locked brand colour changes by more than one just-noticeable difference.",
        "Keep locked brand colours at `alpha: 1`, or remove the lock.",
        family=Family.DRIFT,
        closed_form=False,
        fixed_by="colour",
    ),
    RuleSpec(
        Rule.CONFUSION,
        "AA012",
        "major",
        Level.FAIL,
        "Two palette roles told apart at alpha 1 are no longer told apart.",
        "Lower the `alpha` that pulls the two roles together, or move one role's colour "
        "further from the other.",
        family=Family.CONFUSION,
        closed_form=False,
        fixed_by="group",
    ),
    RuleSpec(
        Rule.THIN_STROKES,
        "AA013",
        "minor",
        Level.OFF,
        "At a raster size the antialiased paint falls below min-size-contrast.",
        "Use a heavier stroke or a larger size, or a source colour with more contrast.",
        family=Family.THIN_STROKES,
        fixed_by="colour",
    ),
    RuleSpec(
        Rule.CVD_COLLISION,
        "AA014",
        "minor",
        Level.OFF,
        "Distinct colours newly look identical under simulated colour blindness.",
        "Move the two colours apart in lightness, not only in hue.",
        family=Family.CVD_COLLISION,
        closed_form=False,
        fixed_by="group",
    ),
    RuleSpec(
        Rule.CVD_CONFUSION,
        "AA015",
        "minor",
        Level.OFF,
        "Two roles are no longer told apart under simulated colour blindness.",
        "Separate the two roles in lightness (CVD keeps lightness), or lower the `alpha`.",
        family=Family.CONFUSION,
        closed_form=False,
        fixed_by="group",
    ),
    # Only a browser draws it (render); reported by default: a page drawing another
    # colour than the manifest's is often meant (a themed override), and the contrast
    # rules judge what it draws either way.
    RuleSpec(
        Rule.RENDER_DRIFT,
        "AA016",
        "minor",
        Level.OFF,
        "The browser draws the icon in another colour than the model predicts from the "
        "manifest (CIEDE2000 above the render-drift tolerance): a CSS override, a hard-coded "
        "fill, a color-mix() chain.",
        "Paint the icon with the manifest's colour (`currentColor` from the theme token), or "
        "write the colour the page draws into the manifest so `check` audits it.",
        render=Level.WARN,
        browser_only=True,
        family=Family.RENDER_DRIFT,
    ),
    # Alpha did not make these collide: the colours already look the same at alpha 1
    # and only share a code once it rounds them together.  Listed once, never gated
    # by default, never a limit of ``suggest``.
    RuleSpec(
        Rule.NEAR_DUPLICATE,
        "AA017",
        "info",
        Level.WARN,
        "Distinct colours that already look the same at alpha 1 (CIEDE2000 below "
        "near-duplicate-delta-e) share one 8-bit output at their alpha.",
        "Use one colour for both if they mean the same, or move them apart if they should "
        "be told apart; alpha only rounds them together.",
        family=Family.COLLISION,
    ),
)
RULES: dict[Rule, RuleSpec] = {spec.rule: spec for spec in _SPECS}
DEFAULT_RULES = frozenset(r for r, s in RULES.items() if s.default is Level.FAIL)
DEFAULT_WARNINGS = frozenset(r for r, s in RULES.items() if s.default is Level.WARN)
# The per paint x canvas contrast rules, in rule order.
CONTRAST_RULES = tuple(r for r, s in RULES.items() if s.family is Family.CONTRAST)
# The rules ``alpha-audit check`` (and ``suggest``) can raise from the model's rows.
CHECK_RULES = tuple(r for r, s in RULES.items() if not s.browser_only)
# The rules ``alpha-audit render`` can raise from measured paints, and its defaults.
RENDER_RULES = tuple(r for r, s in RULES.items() if s.render is not None)
RENDER_DEFAULT_RULES = frozenset(r for r, s in RULES.items() if s.render is Level.FAIL)
RENDER_DEFAULT_WARNINGS = frozenset(r for r, s in RULES.items() if s.render is Level.WARN)


def did_you_mean(name: str, known: Iterable[str]) -> str:
    """``"did you mean 'x'? "`` for the closest known name, else ``""``."""
    close = difflib.get_close_matches(name, list(known), n=1)
    return f"did you mean {close[0]!r}? " if close else ""


def rules_table() -> str:
    """The Markdown table of every rule (``docs/rules.md`` holds it; a test compares)."""
    lines = [
        "| rule | SARIF id | default | in `render` | GitLab severity | what it objects to "
        "| the fix |",
        "| --- | --- | --- | --- | --- | --- | --- |",
    ]
    for s in _SPECS:
        render = "—" if s.render is None else s.render.value
        lines.append(
            f"| `{s.rule.value}` | {s.sarif_id} | {s.default.value} | {render} | {s.severity} | "
            f"{s.help} | {s.fix} |"
        )
    return "\n".join(lines) + "\n"
