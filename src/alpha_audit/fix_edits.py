"""Fixes as text edits: which written value to replace, and with what.

:mod:`alpha_audit.fixes` says how to fix a failing colour on a canvas (the
largest safe alpha, the smallest alpha from 1 reaching the threshold, the
nearest passing colour).  Here each answer becomes an edit of one value the
loaders located exactly (:class:`~alpha_audit.model.Span`): the icon's alpha
(its own or its override's, else the set-wide ``alpha:``) or the value that
sets its colour (the palette entry, the colour written on the icon, or the
design token's value).  An edit is offered only where applying it is known to
clear the finding it is attached to:

- the finding is one icon's contrast on one canvas (``loss``,
  ``newly-failing``, ``below-threshold``), judged on the icon's own colour
  (``currentColor`` at opacity 1: the paint the manifest sets) in the
  ``linear`` pipeline, where the fixes' compositing is the audit's;
- the largest safe alpha answers all three rules; the smallest reaching alpha
  answers ``below-threshold`` and ``newly-failing`` (contrast at least the
  threshold), not ``loss``; the nearest colour answers all three (it passes
  every contrast rule of the policy at the colour's alphas);
- a colour edit is not offered for a locked (brand) colour, nor for a token
  value that also sets a canvas of the theme (the edit would move the canvas);
- the value must be written in a file: a default alpha, ``--alpha``, a
  token's coefficient or a DTCG colour object give no edit (inserting one
  would be guesswork about the file's layout); the fix is still in the text.

Collisions, separations and confusions depend on several colours at once, so
no single edit is known to clear them; they get none.  Pure computation.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Literal

from alpha_audit.audit import AuditResult
from alpha_audit.fixes import ColorFix, fix_lookup, report_fixes
from alpha_audit.gate import CheckReport, Finding
from alpha_audit.load.paints import CURRENT_COLOR
from alpha_audit.model import Icon, Span
from alpha_audit.policy import CONTRAST_RULES, Rule

__all__ = ["FixEdit", "edit_lookup", "edits_for", "format_alpha"]

EditKind = Literal["largest-safe-alpha", "smallest-alpha-reaching", "nearest-color"]
# The rules at whose finding the smallest reaching alpha is an exact fix: both
# mean "contrast below the threshold", which that alpha lifts on every canvas of
# the mode.  A loss can remain above 1 (contrast lower than at alpha 1).
_REACH_RULES = frozenset({Rule.BELOW_THRESHOLD, Rule.NEWLY_FAILING})


@dataclass(frozen=True)
class FixEdit:
    """Replace the text at ``span`` by ``value`` (written as the file writes it)."""

    kind: EditKind
    description: str
    span: Span
    value: str

    @property
    def inserted(self) -> str:
        """The replacement text, quoted as the original was (:meth:`Span.replacement`)."""
        return self.span.replacement(self.value)


def format_alpha(alpha: float) -> str:
    """The shortest text that reads back as ``alpha``.

    >>> format_alpha(1.042), format_alpha(1.0), format_alpha(0.1 + 0.2)
    ('1.042', '1', '0.30000000000000004')
    """
    short = f"{alpha:g}"
    return short if float(short) == alpha else repr(alpha)


def _own_colour(finding: Finding, icon: Icon, result: AuditResult) -> bool:
    """Whether the finding judges the icon's manifest colour as the fixes compute it."""
    n = finding.numbers
    if n.get("source") != icon.color:
        return False
    if n.get("paint", CURRENT_COLOR) != CURRENT_COLOR or float(n.get("opacity", 1.0)) != 1.0:
        return False
    return result.paints is None or result.paints.pipeline == "linear"


def _edits(fix: ColorFix, finding: Finding, icon: Icon, result: AuditResult) -> list[FixEdit]:
    out: list[FixEdit] = []
    alpha_span = icon.alpha_span
    safe = fix.largest_safe.alpha
    if alpha_span is not None and safe is not None and safe != icon.alpha:
        out.append(
            FixEdit(
                "largest-safe-alpha",
                f"set alpha to {format_alpha(safe)}, the largest safe alpha for {fix.color}",
                alpha_span,
                format_alpha(safe),
            )
        )
    reach = fix.reach.alpha
    if (
        alpha_span is not None
        and reach is not None
        and reach != icon.alpha
        and finding.rule in _REACH_RULES
        and reach != safe
    ):
        out.append(
            FixEdit(
                "smallest-alpha-reaching",
                f"set alpha to {format_alpha(reach)}, the smallest alpha from 1 reaching "
                f"{fix.reach.threshold:g}:1 on every {fix.mode} canvas",
                alpha_span,
                format_alpha(reach),
            )
        )
    near = fix.nearest
    color_span = icon.color_span
    locked = result.iconset.locked
    if (
        near is not None
        and near.delta_e > 0
        and color_span is not None
        and icon.name not in locked
        and (icon.color_name or "") not in locked
        and all(c.span != color_span for c in result.theme.canvases if c.span is not None)
    ):
        out.append(
            FixEdit(
                "nearest-color",
                f"use {near.color} for {fix.color}, the nearest passing colour of the same "
                f"OKLCH hue (CIEDE2000 {near.delta_e:.2f} away)",
                color_span,
                near.color,
            )
        )
    return out


def edit_lookup(report: CheckReport) -> Callable[[Finding], tuple[FixEdit, ...]]:
    """A function giving the edits that fix one finding (``()`` where none is exact).

    Uses the report's fixes (:func:`~alpha_audit.fixes.report_fixes`).
    """
    fixes = fix_lookup(report, report_fixes(report))
    audits = {(r.theme.name, r.iconset.name): r for r in report.audits}
    icons = {key: {i.name: i for i in r.iconset.icons} for key, r in audits.items()}

    def lookup(finding: Finding) -> tuple[FixEdit, ...]:
        if (
            not finding.fails
            or finding.canvas is None
            or finding.rule not in CONTRAST_RULES
            or len(finding.icons) != 1
        ):
            return ()
        key = (finding.theme, finding.iconset)
        result = audits.get(key)
        icon = icons.get(key, {}).get(finding.icons[0])
        if result is None or icon is None or not _own_colour(finding, icon, result):
            return ()
        return tuple(e for fix in fixes(finding) for e in _edits(fix, finding, icon, result))

    return lookup


def edits_for(report: CheckReport) -> dict[int, tuple[FixEdit, ...]]:
    """The edits of every failing finding that has some, keyed by its index in ``gate.findings``."""
    lookup = edit_lookup(report)
    out = {}
    for k, finding in enumerate(report.gate.findings):
        edits = lookup(finding)
        if edits:
            out[k] = edits
    return out
