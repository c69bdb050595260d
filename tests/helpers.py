"""Helpers shared by test modules (importable: ``pythonpath = tests``)."""

from __future__ import annotations

from pathlib import Path


def solid_paints(iconset, problems=(), sizes=None):  # type: ignore[no-untyped-def]
    """Hand-made paints (no rendering): each icon one solid currentColor fill at every size.

    ``problems`` are icons that "could not be rendered" (their names need not be in the set).
    """
    from alpha_audit.color.coverage import CoverageStats
    from alpha_audit.load.paint_masks import IconPaints, PaintCoverage, PaintSet
    from alpha_audit.load.paints import CURRENT_COLOR, Paint, PaintGroup, SvgPaints

    solid = CoverageStats(q50=1.0, full_share=1.0, ink=10.0, pixels=10)
    gone = {p.icon for p in problems}
    icons = {}
    for icon in iconset.icons:
        if icon.name in gone:
            continue
        paint = Paint(CURRENT_COLOR, "fill", 1.0, "<path>", None)
        group = PaintGroup(CURRENT_COLOR, 1.0, (paint,))
        cov = (PaintCoverage(group, dict.fromkeys(sizes or iconset.sizes, solid)),)
        icons[icon.name] = IconPaints(icon.name, Path(icon.file), SvgPaints((paint,)), cov)
    return PaintSet(icons, tuple(problems))
