"""Helpers shared by test modules (importable: ``pythonpath = tests``)."""

from __future__ import annotations

from pathlib import Path


def solid_paints(iconset, problems=(), sizes=None):  # type: ignore[no-untyped-def]
    """Hand-made paints (no rendering): each icon one solid currentColor fill at every size.

    ``problems`` are icons that "could not be rendered" (their names need not be in the set).
    """
    from alpha_audit.color.coverage import CoverageStats
    from alpha_audit.paints import (
        CURRENT_COLOR,
        IconPaints,
        Paint,
        PaintCoverage,
        PaintGroup,
        PaintSet,
        SvgPaints,
    )

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


# -- an independent reference: the spec formulas written out, not alpha_audit's ---------


def spec_decode(v):  # type: ignore[no-untyped-def]
    """CSS Color 4 sRGB decode of encoded values in [0, 1]."""
    import numpy as np

    v = np.asarray(v, dtype=float)
    return np.where(v <= 0.04045, v / 12.92, ((v + 0.055) / 1.055) ** 2.4)


def spec_hex(text: str):  # type: ignore[no-untyped-def]
    """``#rrggbb`` as linear sRGB."""
    import numpy as np

    return spec_decode(np.array([int(text[k : k + 2], 16) for k in (1, 3, 5)]) / 255.0)


def spec_ship(linear):  # type: ignore[no-untyped-def]
    """What an 8-bit screen shows: CSS Color 4 encode, x255, round half to even, decode."""
    import numpy as np

    v = np.clip(np.asarray(linear, dtype=float), 0.0, 1.0)
    encoded = np.where(v <= 0.0031308, 12.92 * v, 1.055 * v ** (1 / 2.4) - 0.055)
    return spec_decode(np.rint(encoded * 255.0) / 255.0)


def spec_contrast(a, b) -> float:  # type: ignore[no-untyped-def]
    """WCAG 2.2 contrast of two linear colours (luminance 0.2126/0.7152/0.0722)."""
    import numpy as np

    la, lb = (float(np.dot(np.asarray(c, dtype=float), [0.2126, 0.7152, 0.0722])) for c in (a, b))
    return (max(la, lb) + 0.05) / (min(la, lb) + 0.05)


def _lin(text: str):  # type: ignore[no-untyped-def]
    r, g, b = (float(v) for v in spec_hex(text))
    return r, g, b


def measured_paint(**changes):  # type: ignore[no-untyped-def]
    """A measured paint (alpha_audit.observed.MeasuredPaint) for tests without a browser:
    a red alert icon drawn as a manifest says (#cf222e) on white, 5.36:1 by the specs.
    ``drawn`` and ``behind`` set the pair (and its contrast, by spec_contrast)."""
    from dataclasses import replace

    from alpha_audit.observed import Coverage, IconMatch, MeasuredPaint, Prediction

    drawn = str(changes.pop("drawn", "#cf222e"))
    behind = str(changes.pop("behind", "#ffffff"))
    contrast = spec_contrast(spec_hex(drawn), spec_hex(behind))
    base = MeasuredPaint(
        source="icons--alert",
        source_kind="storybook",
        state="theme:light",
        engine="chromium",
        name="div.alert > svg",
        icon=None,
        match=IconMatch.NONE,
        element="svg",
        dom_path="div.alert > svg",
        paint="currentColor",
        kinds=("stroke",),
        declared=drawn,
        declared_opacity=1.0,
        drawn=drawn,
        drawn_linear=_lin(drawn),
        behind=behind,
        behind_linear=_lin(behind),
        around=behind,
        around_linear=_lin(behind),
        coverage=Coverage(100, 40, 60.0, 1.0, 0.6),
        contrast=contrast,
        contrast_worst=contrast,
        contrast_median=contrast,
        model_source="#cf222e",
        model_alpha=1.0,
        model_opacity=1.0,
        predictions=(
            Prediction("linear", "#cf222e", _lin("#cf222e"), 5.36, 0.0),
            Prediction("css", "#cf222e", _lin("#cf222e"), 5.36, 0.0),
        ),
        render_drift=0.0,
        box=(0.0, 0.0, 24.0, 24.0),
    )
    return replace(base, **changes)


def render_all(pool, jobs):  # type: ignore[no-untyped-def]
    """Every ``(svgs, sizes)`` job through ``pool.stream``, outcomes in job order."""
    results = dict(pool.stream((i, svgs, sizes) for i, (svgs, sizes) in enumerate(jobs)))
    return [results[i] for i in range(len(jobs))]
