"""What the library hands to renderers: reports, fixes and largest-safe-alpha answers.

Types only.  The pipeline computes them (:mod:`alpha_audit.pipeline`,
:mod:`alpha_audit.fixes`, :mod:`alpha_audit.suggest`) and renderers read
them, so a renderer never imports what computes a fix.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from alpha_audit.gate import GateResult
from alpha_audit.model import GamutAdjustment, IconSet, Theme
from alpha_audit.observed import PageRun
from alpha_audit.policy import Policy
from alpha_audit.rows import AuditResult
from alpha_audit.rules import Rule

__all__ = [
    "CanvasLimit",
    "CheckReport",
    "ColorFix",
    "ColorSuggestion",
    "Fix",
    "GroupFix",
    "GroupSuggestion",
    "IconSuggestion",
    "Limit",
    "NearestColor",
    "Progress",
    "ReachAlpha",
    "SafeAlpha",
    "SuggestResult",
]


Progress = tuple[Callable[[int], None], Callable[[], None]]
"""``(start(total), one done)``: what a progress bar is told (icons, questions ...)."""


@dataclass(frozen=True)
class Limit:
    """What stops a coefficient: a rule broken on a canvas by some icons.

    ``at`` is the first unsafe alpha, the infimum of the unsafe coefficients.
    When ``attained`` it is itself unsafe; otherwise it is the last safe one
    and every coefficient just above it is unsafe.  ``grid`` is ``None`` when
    found exactly from events, else the bracketing grid step (then bisected to
    1e-9): a dip narrower than it could be missed.  ``roles`` are the two palette
    roles a role rule (``confusion``, ``cvd-confusion``) finds pulled together.
    """

    rule: Rule
    canvas: str
    icons: tuple[str, ...]
    at: float
    attained: bool
    grid: float | None = None
    roles: tuple[str, ...] = ()


@dataclass(frozen=True)
class CanvasLimit:
    """The largest safe alpha if this canvas were the only one."""

    canvas: str
    alpha: float | None
    limit: Limit | None


@dataclass(frozen=True)
class SafeAlpha:
    """A largest safe alpha with what limits it.

    ``alpha`` is rounded down to the precision and re-checked (``None``: not
    even alpha = 1 is safe); ``exact`` is the unrounded supremum; ``limit``
    is ``None`` when nothing breaks up to ``alpha_max``.
    """

    alpha: float | None
    exact: float | None
    limit: Limit | None
    per_canvas: tuple[CanvasLimit, ...] = ()


@dataclass(frozen=True)
class ColorSuggestion:
    """Every icon of one palette colour moving together."""

    color: str  # palette name (or the colour itself when it has none)
    source: str
    icons: tuple[str, ...]
    safe: SafeAlpha


@dataclass(frozen=True)
class GroupSuggestion:
    """Roles that pull each other under the separation floor, moving as one (the joint answer).

    ``confused`` are the roles the gate finds confused at their alphas, connected
    through confusion; ``colors`` the group they grow into (every role the joint
    answer finds pulled under the floor with one of them), in palette order; the
    limit's ``roles`` name the pair that limits it.
    """

    colors: tuple[str, ...]
    icons: tuple[str, ...]
    safe: SafeAlpha
    confused: tuple[str, ...] = ()


@dataclass(frozen=True)
class IconSuggestion:
    """One icon moving alone."""

    icon: str
    color: str
    configured: float
    safe: SafeAlpha


@dataclass(frozen=True)
class SuggestResult:
    """Set-wide, per-colour, per-group and per-icon largest safe alphas of one audit.

    ``left_out`` names the icons that could not be rendered (left out as
    ``check`` leaves them out).
    """

    audit: AuditResult
    policy: Policy
    alpha_max: float
    precision: int
    overall: SafeAlpha
    per_color: tuple[ColorSuggestion, ...]
    per_icon: tuple[IconSuggestion, ...]
    per_group: tuple[GroupSuggestion, ...] = ()
    left_out: tuple[str, ...] = ()

    @property
    def alpha(self) -> float | None:
        """The set-wide suggestion (one coefficient for every icon)."""
        return self.overall.alpha

    @property
    def theme(self) -> Theme:
        """The theme the rows were audited on."""
        return self.audit.theme

    @property
    def iconset(self) -> IconSet:
        """The icons audited (those that could not be rendered are in ``left_out``)."""
        return self.audit.iconset

    @property
    def threshold(self) -> float:
        """The contrast threshold of the audit."""
        return self.audit.threshold


@dataclass(frozen=True)
class ReachAlpha:
    """The smallest alpha >= 1 at which a colour reaches the threshold on every canvas of a mode.

    ``alpha`` is rounded up to the precision and re-checked (``None``: no
    alpha up to ``alpha_max`` reaches it); ``exact`` is the infimum itself.
    """

    mode: str
    canvases: tuple[str, ...]
    threshold: float
    alpha: float | None
    exact: float | None


@dataclass(frozen=True)
class NearestColor:
    """The nearest passing colour at the source's OKLCH hue.

    ``color`` is the 8-bit hex to write (checked to pass); ``delta_e`` is its
    CIEDE2000 from the source.  ``lightness``/``chroma``/``hue`` are the OKLCH
    of the continuous optimum the hex rounds (hue in degrees).
    """

    color: str
    delta_e: float
    lightness: float
    chroma: float
    hue: float


@dataclass(frozen=True)
class ColorFix:
    """How to fix one colour failing a contrast rule (or any rule) on one canvas.

    ``color`` is the palette name, or the colour itself when it has none;
    ``icons`` every icon drawing it.
    """

    theme: str
    iconset: str
    color: str
    source: str
    canvas: str
    mode: str
    icons: tuple[str, ...]
    rules: tuple[Rule, ...]  # the rules it fails on this canvas
    largest_safe: SafeAlpha
    reach: ReachAlpha
    nearest: NearestColor | None
    manifest: Path | None = None
    line: int | None = None  # manifest line that sets the colour (first icon), if known
    # A paint a browser drew with CSS at this opacity: the answers are an opacity
    # (``reach.alpha`` times it) and a colour, not a coefficient.  None: the model's.
    opacity: float | None = None
    # The colours that move with it for ``largest_safe``: those that leave it no safe
    # alpha alone (a role it is confused with at 1 while they keep their alpha).
    together: tuple[str, ...] = ()
    # With no safe alpha: the colours whose alpha holds it at 1 (alpha 1 itself may pass).
    held: tuple[str, ...] = ()


@dataclass(frozen=True)
class GroupFix:
    """The largest safe alpha for a finding between several colours, for its rule alone.

    ``colors`` are the roles moving together (a confusion's group); empty: every
    icon of the set.  ``confused`` are the roles the failing findings connect,
    from which the group grew (:class:`GroupSuggestion`); the limit's ``roles``
    name the pair that limits it.
    """

    theme: str
    iconset: str
    rule: Rule
    colors: tuple[str, ...]
    safe: SafeAlpha
    confused: tuple[str, ...] = ()


Fix = ColorFix | GroupFix


@dataclass(frozen=True)
class CheckReport:
    """What ``check`` and ``render`` produce: the audits, the gate over all, the fixes.

    ``check``'s audits are one per theme x icon set; ``render``'s one per story
    or page, state, engine and backdrop, their rows measured in a browser
    (:attr:`~alpha_audit.rows.AuditResult.observed`), with ``pages`` saying what
    the run saw besides (page states, problems, blocked requests, crops).

    Each failing finding names the fixes that answer it by index
    (:attr:`~alpha_audit.findings.Finding.fixes`); ``fixes_left_out`` counts
    failing colours beyond the fix budget (``alpha-audit suggest`` answers them).
    """

    audits: tuple[AuditResult, ...]
    gate: GateResult
    fixes: tuple[Fix, ...] = ()
    fixes_left_out: int = 0
    gamut: tuple[GamutAdjustment, ...] = ()  # colours outside sRGB the gamut policy moved
    notes: tuple[str, ...] = ()  # what the token loader noted: modes found, tokens skipped
    pages: PageRun | None = None  # render: what the page run saw besides its paints
