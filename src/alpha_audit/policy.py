"""Gate policy: which rules fail a build or are reported, shared by ``check`` and ``suggest``.

The rules and their defaults are :data:`alpha_audit.rules.RULES`: no contrast
loss, no paint newly failing the threshold, no collision that did not already
exist at alpha = 1, and no two palette roles told apart at alpha 1 but confused
at the icons' alpha fail by default; icons that cannot be rendered and
hard-coded paints are reported.  Each numeric rule is stated once here (the
``*_breaks`` / ``*_floor`` functions) and used by the gate and by ``suggest``.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import TYPE_CHECKING

from alpha_audit import ranges
from alpha_audit.constants import CONTRAST_TOLERANCE, DELTA_E_TOLERANCE
from alpha_audit.errors import InputError, UsageError
from alpha_audit.ranges import CONTRAST_LOSS, CONTRAST_RATIO, DELTA_E
from alpha_audit.rules import (
    CONTRAST_RULES,
    DEFAULT_RULES,
    DEFAULT_WARNINGS,
    RENDER_DEFAULT_RULES,
    RENDER_DEFAULT_WARNINGS,
    Level,
    Rule,
    did_you_mean,
)

if TYPE_CHECKING:  # numpy is imported where a rule is applied: the CLI's --help reads Policy
    import numpy as np
    from numpy.typing import ArrayLike, NDArray

__all__ = [
    "LOSS_TOLERANCE",
    "NEAR_DUPLICATE_DELTA_E",
    "RENDER_DRIFT_TOLERANCE",
    "RENDER_POLICY",
    "VISIBILITY_FLOOR",
    "Exemption",
    "Policy",
    "collision_rules",
    "confusion_breaks",
    "confusion_possible",
    "contrast_breaks",
    "contrast_floor",
    "drift_breaks",
    "drift_ceiling",
    "loss_reported",
    "size_contrast_floor",
]


# A paint below this contrast at alpha 1 is already all but invisible on the canvas
# (a brand logo in the canvas's own colour): its further loss is reported, not gated.
# 1.5:1 is half of WCAG 2.2 SC 1.4.11's 3:1 for graphical objects.
VISIBILITY_FLOOR = 1.5
# A loss smaller than this share of the contrast at alpha 1 is reported, not gated.
# The smallest relative contrast change one 8-bit code step can make is 2.24e-5
# (blue 0 -> 1 beside full red and green, luminance weights of WCAG 2.2), so 1e-6
# tolerates no visible change, only float noise and sub-code losses (2e-10).
LOSS_TOLERANCE = 1e-6
# Two colours closer than this CIEDE2000 at alpha 1 already look the same: one
# just-noticeable difference, the usual reading of dE00 = 1 (as for ``lock``).  Alpha
# rounding them onto one 8-bit code makes no collision a reader could see.
NEAR_DUPLICATE_DELTA_E = 1.0


@dataclass(frozen=True)
class Exemption:
    """A finding not to fail on: by canvas and/or icon (and optionally rule), with a reason."""

    reason: str
    canvas: str | None = None
    icon: str | None = None
    rule: Rule | None = None
    # Where the config wrote it (for errors); not part of its identity.
    path: Path | None = field(default=None, compare=False)
    line: int | None = field(default=None, compare=False)
    key: str | None = field(default=None, compare=False)

    def covers(self, rule: Rule, canvas: str | None, icons: tuple[str, ...]) -> bool:
        """Whether this exemption applies to a finding of ``rule`` on ``canvas`` for ``icons``."""
        if self.rule is not None and self.rule != rule:
            return False
        if self.canvas is not None and self.canvas != canvas:
            return False
        return self.icon is None or self.icon in icons


@dataclass(frozen=True)
class Policy:
    """Which rules fail the gate and which are reported, with their limits and exemptions.

    ``rules`` fail the gate; ``warnings`` are reported without failing it (a
    rule in both fails).
    """

    rules: frozenset[Rule] = DEFAULT_RULES
    max_loss: float = 0.0  # contrast-ratio units; losses up to this are tolerated
    min_delta_e: float = 10.0  # CIEDE2000; Rule.SEPARATION, CONFUSION, CVD_CONFUSION
    exemptions: tuple[Exemption, ...] = ()
    max_drift: float = 10.0  # CIEDE2000; Rule.DRIFT
    min_size_contrast: float | None = None  # Rule.THIN_STROKES; None: the threshold
    warnings: frozenset[Rule] = DEFAULT_WARNINGS
    # Rule.LOSS gates only paints at or above this contrast at alpha 1 ...
    visibility_floor: float = VISIBILITY_FLOOR
    # ... that lose more than this share of it (both: reported, not gated, below).
    loss_tolerance: float = LOSS_TOLERANCE
    # Rule.NEW_COLLISION gates only colours at least this far apart at alpha 1; closer
    # ones are Rule.NEAR_DUPLICATE (reported, not gated, by default).
    near_duplicate_delta_e: float = NEAR_DUPLICATE_DELTA_E

    def __post_init__(self) -> None:
        # The ranges the config keys and the flags of the same names obey.
        limits = [
            ("max_loss", self.max_loss, CONTRAST_LOSS),
            ("min_delta_e", self.min_delta_e, DELTA_E),
            ("max_drift", self.max_drift, DELTA_E),
            ("min_size_contrast", self.min_size_contrast, CONTRAST_RATIO),
            ("visibility_floor", self.visibility_floor, CONTRAST_RATIO),
            ("loss_tolerance", self.loss_tolerance, ranges.LOSS_TOLERANCE),
            ("near_duplicate_delta_e", self.near_duplicate_delta_e, DELTA_E),
        ]
        for name, value, allowed in limits:
            if value is not None and not allowed.allows(value):
                raise UsageError(allowed.refusal(f"{name} {value:g}"))
        if any(not e.reason.strip() for e in self.exemptions):
            raise UsageError("every exemption needs a reason")

    def with_overrides(
        self,
        *,
        rules: Iterable[str] | None = None,
        max_loss: float | None = None,
        min_delta_e: float | None = None,
        max_drift: float | None = None,
        min_size_contrast: float | None = None,
        visibility_floor: float | None = None,
        loss_tolerance: float | None = None,
        near_duplicate_delta_e: float | None = None,
    ) -> Policy:
        """This policy with command-line overrides applied (``None`` keeps a field)."""
        return replace(
            self,
            rules=frozenset(Rule.parse(r) for r in rules) if rules else self.rules,
            warnings=self.warnings,
            visibility_floor=(
                self.visibility_floor if visibility_floor is None else visibility_floor
            ),
            loss_tolerance=self.loss_tolerance if loss_tolerance is None else loss_tolerance,
            near_duplicate_delta_e=(
                self.near_duplicate_delta_e
                if near_duplicate_delta_e is None
                else near_duplicate_delta_e
            ),
            max_loss=self.max_loss if max_loss is None else max_loss,
            min_delta_e=self.min_delta_e if min_delta_e is None else min_delta_e,
            max_drift=self.max_drift if max_drift is None else max_drift,
            min_size_contrast=(
                self.min_size_contrast if min_size_contrast is None else min_size_contrast
            ),
        )

    def level(self, rule: Rule) -> Level:
        """What the gate does with ``rule``'s findings."""
        if rule in self.rules:
            return Level.FAIL
        return Level.WARN if rule in self.warnings else Level.OFF

    @property
    def reported(self) -> frozenset[Rule]:
        """Rules whose findings are computed: the failing ones and the reported ones."""
        return self.rules | self.warnings

    def exempt(self, rule: Rule, canvas: str | None, icons: tuple[str, ...]) -> Exemption | None:
        """The first exemption covering this finding, if any."""
        return next((e for e in self.exemptions if e.covers(rule, canvas, icons)), None)

    def check_exemptions(self, canvases: Iterable[str], icons: Iterable[str]) -> None:
        """Refuse an exemption naming a canvas or icon that none of the inputs has.

        A misspelt name would silently exempt nothing; the error names the
        config line and the closest real name.  (Unknown rules are refused
        when the config is read.)
        """
        known = {"canvas": sorted(set(canvases)), "icon": sorted(set(icons))}
        for e in self.exemptions:
            for what, name in (("canvas", e.canvas), ("icon", e.icon)):
                if name is None or name in known[what]:
                    continue
                where = "theme" if what == "canvas" else "icon set"
                key = f"{e.key}.{what}" if e.key else None
                raise InputError(
                    f"exemption names {what} {name!r}, which no {where} has; "
                    f"{did_you_mean(name, known[what])}check the spelling",
                    path=e.path,
                    line=e.line,
                    key=key,
                )

    def size_contrast_limit(self, threshold: float) -> float:
        """The size contrast ``thin-strokes`` asks for: min-size-contrast, else ``threshold``."""
        return threshold if self.min_size_contrast is None else self.min_size_contrast

    def loss_margin(self, tolerance: float = CONTRAST_TOLERANCE) -> float:
        """How far contrast may drop before ``loss`` objects.

        A loss counts beyond both the policy's allowance and the float
        tolerance under which a change is "unchanged" (the product brief: 1e-10).
        """
        return max(self.max_loss, tolerance)

    @property
    def contrast_rules(self) -> tuple[Rule, ...]:
        """The enabled per icon x canvas contrast rules, in :data:`CONTRAST_RULES` order."""
        return tuple(r for r in CONTRAST_RULES if r in self.rules)

    def collision_rule(
        self, delta_e_ref: float, rules: frozenset[Rule] | None = None
    ) -> Rule | None:
        """The one rule a collision is reported under, of ``rules`` (default: the reported).

        ``delta_e_ref`` is the widest CIEDE2000 between the colliding colours at
        alpha 1 (:func:`collision_rules`).  A failing rule comes before a reported
        one, then ``collision`` before the narrower rules: with both ``collision``
        and ``new-collision`` failing a new collision is reported once, as ``collision``.
        """
        chosen = self.reported if rules is None else rules
        found = [
            r for r in collision_rules(delta_e_ref, self.near_duplicate_delta_e) if r in chosen
        ]
        failing = [r for r in found if r in self.rules]
        return next(iter(failing or found), None)


# render's gate without a config: below-threshold fails, render-drift and not-audited
# are reported (rules.py: each rule's ``render`` level).
RENDER_POLICY = Policy(rules=RENDER_DEFAULT_RULES, warnings=RENDER_DEFAULT_WARNINGS)


def contrast_breaks(
    rule: Rule,
    policy: Policy,
    contrast_ref: ArrayLike,
    contrast: ArrayLike,
    threshold: float,
    tolerance: float = CONTRAST_TOLERANCE,
) -> NDArray[np.bool_]:
    """Where a contrast rule objects, given contrast at alpha = 1 and at the icon's alpha.

    The one statement of the three contrast rules; :func:`contrast_floor` is
    the same statement solved for contrast.

    >>> contrast_breaks(Rule.NEWLY_FAILING, Policy(), [3.2, 2.0], [2.9, 1.5], 3.0).tolist()
    [True, False]
    """
    import numpy as np

    ref = np.asarray(contrast_ref, dtype=np.float64)
    now = np.asarray(contrast, dtype=np.float64)
    if rule is Rule.LOSS:
        margin = np.maximum(policy.loss_margin(tolerance), policy.loss_tolerance * ref)
        return ((now - ref) < -margin) & (ref >= policy.visibility_floor)
    if rule is Rule.BELOW_THRESHOLD:
        return now < threshold
    if rule is Rule.NEWLY_FAILING:
        return (ref >= threshold) & (now < threshold)
    raise ValueError(f"{rule.value} is not a contrast rule")


def contrast_floor(
    rule: Rule,
    policy: Policy,
    contrast_ref: ArrayLike,
    threshold: float,
    tolerance: float = CONTRAST_TOLERANCE,
) -> NDArray[np.float64]:
    """The contrast below which ``rule`` objects (1.0, the least contrast, when it never does).

    ``contrast_breaks(rule, ...)`` is ``contrast < contrast_floor(rule, ...)``
    up to rounding in the loss subtraction; ``suggest`` uses this form to find
    where the contrast crosses it.
    """
    import numpy as np

    ref = np.asarray(contrast_ref, dtype=np.float64)
    if rule is Rule.LOSS:
        margin = np.maximum(policy.loss_margin(tolerance), policy.loss_tolerance * ref)
        # Below the visibility floor a loss never gates: no contrast is below 1.
        return np.where(ref >= policy.visibility_floor, ref - margin, 1.0)
    if rule is Rule.BELOW_THRESHOLD:
        return np.full_like(ref, threshold)
    if rule is Rule.NEWLY_FAILING:
        return np.where(ref >= threshold, threshold, 1.0)  # only icons passing at alpha = 1
    raise ValueError(f"{rule.value} is not a contrast rule")


def loss_reported(
    policy: Policy,
    contrast_ref: ArrayLike,
    contrast: ArrayLike,
    tolerance: float = CONTRAST_TOLERANCE,
) -> NDArray[np.bool_]:
    """Where ``loss`` reports a loss without gating on it.

    A loss beyond the policy's allowance (:meth:`Policy.loss_margin`) on a
    paint already below the visibility floor at alpha 1, or within the
    relative tolerance, is shown to the reviewer but fails nothing
    (:func:`contrast_breaks` is where it fails).

    >>> loss_reported(Policy(), [1.2, 4.0, 4.0], [1.1, 3.9, 4.0 - 2e-10]).tolist()
    [True, False, True]
    """
    import numpy as np

    ref = np.asarray(contrast_ref, dtype=np.float64)
    now = np.asarray(contrast, dtype=np.float64)
    lost = (now - ref) < -policy.loss_margin(tolerance)
    return lost & ~contrast_breaks(Rule.LOSS, policy, ref, now, 1.0, tolerance)


# CIEDE2000 between the colour a browser drew and the model's nearer prediction
# above which the page draws another colour than the manifest says (``render-drift``).
# One 8-bit code step in one channel moves a colour by at most 1.21 (200,000 random
# sRGB colours, green), and a browser rounds each composite to a code, so a paint
# drawn as predicted measures within about one step; the fixture Storybook's icons
# that draw the manifest colour measure 0.00, its CSS overrides 17.7 to 28.6.  2.0
# (two of ``lock``'s just-noticeable differences) leaves rounding a margin and misses
# no override a reviewer could see.
RENDER_DRIFT_TOLERANCE = 2.0


def drift_breaks(drift: ArrayLike, limit: float) -> NDArray[np.bool_]:
    """Where ``drift`` (CIEDE2000 from the colour at alpha 1) objects: above ``limit``.

    The one statement of ``drift`` (limit ``max_drift``) and ``lock`` (limit
    one JND); drifts within the CIEDE2000 float tolerance of the limit pass.

    >>> drift_breaks([9.0, 10.0, 10.5], 10.0).tolist()
    [False, False, True]
    """
    import numpy as np

    return np.asarray(drift, dtype=np.float64) > drift_ceiling(limit)


def drift_ceiling(limit: float) -> float:
    """The largest drift :func:`drift_breaks` lets pass (``suggest`` brackets its crossing)."""
    return limit + DELTA_E_TOLERANCE


def size_contrast_floor(limit: float, tolerance: float = CONTRAST_TOLERANCE) -> float:
    """The size contrast below which ``thin-strokes`` objects (NaN, no ink, never does).

    >>> size_contrast_floor(3.0) < 3.0
    True
    """
    return limit - tolerance


def collision_rules(delta_e_ref: float, near_duplicate_delta_e: float) -> tuple[Rule, ...]:
    """The rules that object to distinct colours sharing one 8-bit output on a canvas.

    The one statement of the collision rules.  ``delta_e_ref`` is the widest
    CIEDE2000 between two of the colours as they ship at alpha 1 on that canvas
    (0: they already share the output there).  ``collision`` objects to every
    collision; ``new-collision`` only to one alpha made between colours told apart
    at alpha 1 (at least ``near_duplicate_delta_e``); ``near-duplicate`` to one
    between colours already closer than that, which alpha only rounds together.

    >>> [[r.value for r in collision_rules(d, 1.0)] for d in (0.0, 0.02, 12.0)]
    [['collision'], ['collision', 'near-duplicate'], ['collision', 'new-collision']]
    """
    if delta_e_ref <= 0.0:
        return (Rule.COLLISION,)
    if delta_e_ref < near_duplicate_delta_e:
        return (Rule.COLLISION, Rule.NEAR_DUPLICATE)
    return (Rule.COLLISION, Rule.NEW_COLLISION)


def confusion_possible(delta_e_ref: ArrayLike, min_delta_e: float) -> NDArray[np.bool_]:
    """Pairs of roles that ``confusion`` protects: told apart at alpha 1.

    >>> confusion_possible([9.9, 10.0], 10.0).tolist()
    [False, True]
    """
    import numpy as np

    return np.asarray(delta_e_ref, dtype=np.float64) >= min_delta_e


def confusion_breaks(
    delta_e_ref: ArrayLike, delta_e: ArrayLike, min_delta_e: float
) -> NDArray[np.bool_]:
    """Where ``confusion`` (and ``cvd-confusion``) object: apart at alpha 1, not at alpha.

    ``suggest`` uses the two halves: :func:`confusion_possible`, then where
    ``delta_e`` first drops below ``min_delta_e``.

    >>> confusion_breaks([16.1, 8.0], [5.2, 5.2], 10.0).tolist()
    [True, False]
    """
    import numpy as np

    de = np.asarray(delta_e, dtype=np.float64)
    return confusion_possible(delta_e_ref, min_delta_e) & (de < min_delta_e)
