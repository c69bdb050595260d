"""One colour on a few backgrounds at a few coefficients: the designer's quick check.

``pair`` is a one-icon audit: the colour becomes one icon per coefficient, the
backgrounds one theme's canvases, and every figure is the audit's own row
(:func:`~alpha_audit.rows.audit`), judged as ``check`` judges it (the 8-bit
colour that ships on the 8-bit canvas,
:func:`~alpha_audit.color.judged_contrast`); the float contrast of the paper's
maths stays beside it (``contrast_float``).  The ``css`` columns are the same
icon audited under pipeline ``css`` (what a browser draws for an alpha in
[0, 1]).

A colour outside sRGB (every chromatic ``-500`` step of Tailwind v4 is one)
follows a gamut policy, ``clip`` by default: each sRGB channel clipped, which
is what browsers draw on an sRGB screen today, so the rows show what the
colour looks like where it ships.  ``map`` (CSS Color 4 gamut mapping) and
``error`` are there to ask; the report says how far the colour moved.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from alpha_audit.color import (
    NON_TEXT_THRESHOLD,
    GamutPolicy,
    Pipeline,
    composite_raw,
    linear_to_hex,
    srgb_decode,
)
from alpha_audit.color.css import parse_css_color
from alpha_audit.constants import DEFAULT_GAMUT
from alpha_audit.model import Canvas, Icon, IconSet, Theme
from alpha_audit.rows import AuditResult, audit

__all__ = [
    "PairGamut",
    "PairReport",
    "PairRow",
    "pair_audit",
    "pair_report",
    "pair_table",
]


@dataclass(frozen=True)
class PairRow:
    """``color`` on ``background`` at ``alpha``: one row of the one-icon audit.

    ``contrast_ref`` and ``contrast`` (at 1 and at ``alpha``) are ``check``'s
    judged contrast, ``passes`` its verdict at ``threshold``;
    ``delta_e_from_source`` is the row's drift (CIEDE2000 between the 8-bit
    colours shown at 1 and at ``alpha``: the source as shipped and the output).
    """

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
    passes: bool = False
    threshold: float = NON_TEXT_THRESHOLD
    contrast_ref_float: float = float("nan")  # the float colours' (the paper's maths)
    contrast_float: float = float("nan")


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


def _fitted(text: str, gamut: GamutPolicy, moved: list[PairGamut]) -> str:
    """``text`` as a colour the model takes: as given in sRGB, else as ``gamut`` fitted it."""
    parsed = parse_css_color(text, gamut=gamut)
    if not parsed.adjusted:
        return text
    moved.append(
        PairGamut(parsed.text, gamut, linear_to_hex(srgb_decode(parsed.array)), parsed.delta_e)
    )
    return parsed.css


def _inputs(
    color: str, backgrounds: Sequence[str], gamut: GamutPolicy, moved: list[PairGamut]
) -> tuple[str, Theme]:
    """The colour and the theme of its backgrounds, fitted into sRGB."""
    source = _fitted(color, gamut, moved)
    canvases = tuple(
        Canvas(f"background {j + 1}", _fitted(text, gamut, moved))
        for j, text in enumerate(backgrounds)
    )
    return source, Theme("pair", canvases)


def _one_icon(
    source: str, theme: Theme, alphas: Sequence[float], pipeline: Pipeline
) -> AuditResult:
    icons = tuple(Icon(f"alpha {k + 1}", Path(), source, float(a)) for k, a in enumerate(alphas))
    return audit(theme, IconSet("pair", icons), pipeline=pipeline)


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


def pair_audit(
    color: str,
    backgrounds: Sequence[str],
    alphas: Sequence[float],
    *,
    pipeline: Pipeline = "linear",
    gamut: GamutPolicy = DEFAULT_GAMUT,
    moved: list[PairGamut] | None = None,
) -> AuditResult:
    """The one-icon audit ``pair`` reads: row ``k`` is ``alphas[k]``, canvas ``j`` is
    ``backgrounds[j]`` (each a CSS colour, fitted into sRGB by ``gamut``).

    >>> r = pair_audit("#e8600a", ["#0c3720"], [0.7])
    >>> round(float(r.contrast[0, 0]), 4), bool(r.passes[0, 0])
    (2.9954, False)
    """
    source, theme = _inputs(color, backgrounds, gamut, [] if moved is None else moved)
    return _one_icon(source, theme, alphas, pipeline)


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
    if not backgrounds or not alphas:
        return []
    source, theme = _inputs(color, backgrounds, gamut, [] if moved is None else moved)
    linear = _one_icon(source, theme, alphas, "linear")
    drawable = [k for k, a in enumerate(alphas) if 0.0 <= a <= 1.0]
    css = _one_icon(source, theme, [alphas[k] for k in drawable], "css").columns()
    at_css = {k: n for n, k in enumerate(drawable)}  # row k of linear -> row n of css
    # Whether the paper's composite left [0, 1] before its clip (the clip is the audit's).
    raw = composite_raw(linear.sources[:, None, :], theme.backgrounds[None], linear.alpha[:, None])
    clipped = np.any((raw < 0.0) | (raw > 1.0), axis=-1).T.reshape(-1).tolist()
    c = linear.columns()  # canvas-major, then icon (alpha) order: background-major
    rows = []
    for i in range(len(c)):
        j, k = divmod(i, len(alphas))
        n = at_css.get(k)
        css_i = None if n is None else j * len(drawable) + n
        rows.append(
            PairRow(
                background=c.background[i],
                alpha=c.alpha[i],
                output=c.output[i],
                contrast_ref=c.contrast_ref[i],
                contrast=c.contrast[i],
                gain=c.gain[i],
                delta_e_from_source=c.drift[i],
                clipped=clipped[i],
                css_output=None if css_i is None else css.output[css_i],
                css_contrast=None if css_i is None else css.contrast[css_i],
                passes=c.passes[i],
                threshold=float(linear.threshold),
                contrast_ref_float=c.contrast_ref_float[i],
                contrast_float=c.contrast_float[i],
            )
        )
    return rows
