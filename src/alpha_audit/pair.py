"""One colour on a few backgrounds at a few coefficients: the designer's quick check.

A colour outside sRGB (every chromatic ``-500`` step of Tailwind v4 is one)
follows a gamut policy, ``clip`` by default: each sRGB channel clipped, which
is what browsers draw on an sRGB screen today, so the rows show what the
colour looks like where it ships.  ``map`` (CSS Color 4 gamut mapping) and
``error`` are there to ask; the report says how far the colour moved.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from alpha_audit.color import (
    GamutPolicy,
    composite_css,
    composite_raw,
    contrast_ratio,
    delta_e_2000,
    linear_to_hex,
    srgb_decode,
)
from alpha_audit.color.css import parse_css_color

__all__ = ["DEFAULT_GAMUT", "PairGamut", "PairReport", "PairRow", "pair_report", "pair_table"]

# What a browser draws on an sRGB screen today (module docstring).
DEFAULT_GAMUT: GamutPolicy = "clip"


@dataclass(frozen=True)
class PairRow:
    """``color`` on ``background`` at ``alpha``."""

    background: str
    alpha: float
    output: str
    contrast_ref: float
    contrast: float
    gain: float
    delta_e_from_source: float
    clipped: bool
    # The same alpha drawn by a browser (pipeline css, docs/model.md); None outside [0, 1].
    css_output: str | None = None
    css_contrast: float | None = None


@dataclass(frozen=True)
class PairGamut:
    """A colour (source or background) the gamut policy moved into sRGB."""

    text: str
    policy: str
    output: str  # 8-bit hex of the fitted colour
    delta_e: float  # CIEDE2000 from the colour as given


@dataclass(frozen=True)
class PairReport:
    """What ``alpha-audit pair`` reports: the colour as given, its rows, what the gamut moved."""

    color: str
    rows: tuple[PairRow, ...]
    gamut: tuple[PairGamut, ...] = ()


def _parse(text: str, gamut: GamutPolicy, moved: list[PairGamut]) -> NDArray[np.float64]:
    parsed = parse_css_color(text, gamut=gamut)
    if parsed.adjusted:
        out = linear_to_hex(srgb_decode(parsed.array))
        moved.append(PairGamut(parsed.text, gamut, out, parsed.delta_e))
    return srgb_decode(parsed.array)


def pair_report(
    color: str,
    backgrounds: Sequence[str],
    alphas: Sequence[float],
    *,
    gamut: GamutPolicy = DEFAULT_GAMUT,
) -> PairReport:
    """:func:`pair_table` with the colour it was asked about, ready for a renderer."""
    moved: list[PairGamut] = []
    rows = pair_table(color, backgrounds, alphas, gamut=gamut, moved=moved)
    return PairReport(color, tuple(rows), tuple(dict.fromkeys(moved)))


def pair_table(
    color: str,
    backgrounds: Sequence[str],
    alphas: Sequence[float],
    *,
    gamut: GamutPolicy = DEFAULT_GAMUT,
    moved: list[PairGamut] | None = None,
) -> list[PairRow]:
    """Rows for every background x alpha (background-major, in the given order).

    >>> [r.output for r in pair_table("#ee7733", ["#ffffff"], [1.1])]
    ['#ec5a00']
    >>> [(r.output, r.css_output) for r in pair_table("#ee7733", ["#ffffff"], [0.6])]
    [('#f5bdad', '#f5ad85')]
    """
    notes: list[PairGamut] = [] if moved is None else moved
    source = _parse(color, gamut, notes)
    rows = []
    for bg_text in backgrounds:
        bg = _parse(bg_text, gamut, notes)
        ref = float(contrast_ratio(source, bg))
        for alpha in alphas:
            raw = composite_raw(source, bg, alpha)
            out = np.clip(raw, 0.0, 1.0)
            cr = float(contrast_ratio(out, bg))
            css = composite_css(source, bg, alpha) if 0.0 <= alpha <= 1.0 else None
            rows.append(
                PairRow(
                    background=linear_to_hex(bg),
                    alpha=float(alpha),
                    output=linear_to_hex(out),
                    contrast_ref=ref,
                    contrast=cr,
                    gain=cr - ref,
                    delta_e_from_source=float(delta_e_2000(out, source)),
                    clipped=bool(np.any((raw < 0) | (raw > 1))),
                    css_output=None if css is None else linear_to_hex(css),
                    css_contrast=None if css is None else float(contrast_ratio(css, bg)),
                )
            )
    return rows
