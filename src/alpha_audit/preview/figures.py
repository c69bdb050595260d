"""What previews draw and print, from the audit's rows: drawings, labels and marks.

A preview shows the rows of ``alpha-audit check``: every icon is drawn paint
group by paint group (:class:`~alpha_audit.preview.compose.Drawing`), and the
number under it is the size contrast its rows have at the drawn size and
coefficient: the minimum over the icon's paint rows on that canvas, the same
number as ``check --format json``'s ``rows[].sizes[size].contrast``.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field, replace

import numpy as np
from numpy.typing import NDArray

from alpha_audit.color.composite import Pipeline
from alpha_audit.color.srgb import hex_to_linear
from alpha_audit.load.paint_masks import PaintMasks
from alpha_audit.model import Icon, IconSet, Theme
from alpha_audit.paints import CURRENT_COLOR
from alpha_audit.preview.compose import Drawing, Layer, solid_drawing
from alpha_audit.rows import AuditResult, audit, with_alphas

__all__ = ["PreviewRows", "drawings_of", "preview_rows", "solid_rows"]


def drawings_of(icons: Sequence[Icon], masks: PaintMasks) -> dict[str, Drawing]:
    """Each measured icon as drawn: its paint groups (in the audit's order) and their masks.

    A ``currentColor`` group takes the icon's manifest colour; icons in
    ``masks.problems`` are absent.
    """
    out = {}
    for icon in icons:
        measured = masks.icons.get(icon.name)
        if measured is None:
            continue
        layers = tuple(
            Layer(g.color, icon.linear if g.color == CURRENT_COLOR else _linear(g.color), g.opacity)
            for g in measured.groups
        )
        out[icon.name] = Drawing(icon.name, layers, measured.masks)
    return out


def _linear(hex_color: str) -> tuple[float, float, float]:
    r, g, b = (float(v) for v in hex_to_linear(hex_color))
    return r, g, b


@dataclass
class PreviewRows:
    """The audit's rows of the previewed icons, and their drawings.

    ``result`` is the audit at each icon's own coefficient over the previewed
    canvases and sizes; figures at another coefficient come from
    :func:`~alpha_audit.rows.with_alphas` (the same files with that alpha in
    the manifest), computed once per coefficient.
    """

    result: AuditResult
    drawings: Mapping[str, Drawing]
    _at: dict[float | None, AuditResult] = field(default_factory=dict)

    @property
    def pipeline(self) -> Pipeline:
        """The pipeline the rows (and the pixels) are drawn under."""
        return self.result.pipeline

    def canvas_index(self, name: str) -> int:
        """Where canvas ``name`` sits in the rows' canvases."""
        return [c.name for c in self.result.theme.canvases].index(name)

    def size_contrast(
        self, alpha: float | None, size: int, icons: Sequence[Icon]
    ) -> NDArray[np.float64]:
        """``(n, m)``: each icon's lowest size contrast over its rows, per canvas, at ``size``.

        ``alpha`` is every icon's coefficient (``None``: each its own).  NaN
        where the icon has no rows (it draws nothing) or was not audited.
        """
        result = self._result(alpha)
        k = result.sizes.index(size)
        figures = result.size_contrast[:, :, k]  # (p, m)
        m = len(result.theme.canvases)
        by_icon: dict[str, list[int]] = {}
        for r, entry in enumerate(result.entries):
            by_icon.setdefault(entry.icon.name, []).append(r)
        out = np.full((len(icons), m), math.nan)
        for i, icon in enumerate(icons):
            rows = by_icon.get(icon.name)
            if rows:  # fmin: NaN only where every row is NaN
                out[i] = np.fmin.reduce(figures[rows], axis=0)
        return out

    def q50(
        self, icons: Sequence[Icon], sizes: Sequence[int]
    ) -> dict[str, list[dict[int, float | None]]]:
        """Each icon's groups' median coverage per size (None: the group draws nothing there)."""
        result = self.result
        out: dict[str, list[dict[int, float | None]]] = {i.name: [] for i in icons}
        index = [result.sizes.index(s) for s in sizes]
        for r, entry in enumerate(result.entries):
            if entry.icon.name in out:
                values = result.q50[r]
                out[entry.icon.name].append(
                    {
                        s: None if math.isnan(values[k]) else float(values[k])
                        for s, k in zip(sizes, index, strict=True)
                    }
                )
        return out

    def _result(self, alpha: float | None) -> AuditResult:
        if alpha is None:
            return self.result
        if alpha not in self._at:
            names = {i.name: float(alpha) for i in self.result.iconset.icons}
            self._at[alpha] = with_alphas(self.result, names)
        return self._at[alpha]


def preview_rows(
    theme: Theme,
    iconset: IconSet,
    masks: PaintMasks,
    sizes: Sequence[int],
    pipeline: Pipeline = "linear",
) -> PreviewRows:
    """The rows of ``iconset``'s paints on ``theme`` at ``sizes``, and the icons' drawings.

    ``masks`` are every icon's paint-group masks at ``sizes``
    (:func:`~alpha_audit.load.paint_masks.paint_masks`); icons in its problems
    are left out of both.
    """
    result = audit(
        theme, replace(iconset, sizes=tuple(sizes)), masks.paint_set(), pipeline=pipeline
    )
    return PreviewRows(result, drawings_of(iconset.icons, masks))


def solid_rows(
    theme: Theme,
    iconset: IconSet,
    masks: Mapping[tuple[str, int], NDArray[np.float64]],
    sizes: Sequence[int] | None = None,
) -> PreviewRows:
    """Icons drawn as one ``currentColor`` mask each (the paper's validation and timing).

    ``masks`` maps ``(icon, size)`` to a whole-icon coverage mask (values
    ``k / 255``) at ``sizes`` (default: every size it holds); icons without a
    mask at every size are left out.  With no SVG paints read, each icon's row
    is its manifest colour (no size figures).
    """
    sizes = tuple(sorted({s for _, s in masks})) if sizes is None else tuple(sizes)
    drawn = [i for i in iconset.icons if all((i.name, s) in masks for s in sizes)]
    drawings = {i.name: solid_drawing(i, {s: masks[(i.name, s)] for s in sizes}) for i in drawn}
    missing = {i.name for i in iconset.icons} - set(drawings)
    return PreviewRows(audit(theme, replace(iconset.without(missing), sizes=sizes)), drawings)
