"""One colour on a few backgrounds at a few coefficients: the designer's quick check."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from alpha_audit.color import (
    composite_css,
    composite_raw,
    contrast_ratio,
    delta_e_2000,
    linear_to_hex,
    parse_color,
    srgb_decode,
)

__all__ = ["PairReport", "PairRow", "pair_report", "pair_table"]


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
class PairReport:
    """What ``alpha-audit pair`` reports: the colour as given and its rows."""

    color: str
    rows: tuple[PairRow, ...]


def pair_report(color: str, backgrounds: Sequence[str], alphas: Sequence[float]) -> PairReport:
    """:func:`pair_table` with the colour it was asked about, ready for a renderer."""
    return PairReport(color, tuple(pair_table(color, backgrounds, alphas)))


def pair_table(color: str, backgrounds: Sequence[str], alphas: Sequence[float]) -> list[PairRow]:
    """Rows for every background x alpha (background-major, in the given order).

    >>> [r.output for r in pair_table("#ee7733", ["#ffffff"], [1.1])]
    ['#ec5a00']
    >>> [(r.output, r.css_output) for r in pair_table("#ee7733", ["#ffffff"], [0.6])]
    [('#f5bdad', '#f5ad85')]
    """
    source = srgb_decode(parse_color(color))
    rows = []
    for bg_text in backgrounds:
        bg = srgb_decode(parse_color(bg_text))
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
