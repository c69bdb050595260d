"""Planning: which sheets a layout produces, their file names, and their coefficient rows."""

from __future__ import annotations

import re
from collections.abc import Sequence
from dataclasses import dataclass
from enum import StrEnum
from typing import TYPE_CHECKING, assert_never

if TYPE_CHECKING:  # numpy loads where alphas are made: the CLI reads Layout at start-up
    import numpy as np
    from numpy.typing import NDArray

    from alpha_audit.model import Canvas, Icon, IconSet

__all__ = [
    "ICON_ALPHA",
    "SWATCH_ALPHAS",
    "Alpha",
    "Layout",
    "Page",
    "SheetSpec",
    "alpha_label",
    "alphas_for",
    "default_alphas",
    "plan_sheets",
    "sheet_rows",
    "sheet_title",
]

Alpha = float | None
ICON_ALPHA: Alpha = None
"""An alpha row that uses each icon's own coefficient from the manifest."""

# Coefficients for the swatch layout when none are given: conventional
# transparency, the reference, and same-direction expansion up to the paper's
# gallery value of 2 (Appendix A.3).
SWATCH_ALPHAS: tuple[float, ...] = (0.6, 1.0, 1.1, 1.2, 1.4, 2.0)


class Layout(StrEnum):
    """Sheet layouts offered by ``alpha-audit preview --layout``."""

    GRID = "grid"
    SWATCHES = "swatches"
    COMPARE = "compare"


class ImageFormat(StrEnum):
    """Sheet files offered by ``alpha-audit preview --format``: both lossless.

    WebP (lossless, Pillow's method 4) is about a third of the size of the
    PNG (zlib level 1) of the same sheet and takes about twice as long to write.
    """

    PNG = "png"
    WEBP = "webp"

    def file_name(self, name: str) -> str:
        """A sheet's name (``...png``) with this format's suffix.

        >>> ImageFormat.WEBP.file_name("demo-grid-paper-16px.png")
        'demo-grid-paper-16px.webp'
        """
        return f"{name.removesuffix('.png')}.{self.value}"


@dataclass(frozen=True)
class Page:
    """Which part of a sheet too large for one image a page shows.

    ``first:stop`` indexes the set's icons (grid, compare) or its swatch
    colours (swatches); ``note`` says the same in words for the sheet's title.
    """

    number: int
    count: int
    first: int
    stop: int
    note: str


@dataclass(frozen=True)
class SheetSpec:
    """One planned sheet: its file name, layout, canvases and icon size (and page, if split)."""

    name: str
    layout: Layout
    canvases: tuple[Canvas, ...]
    size: int
    page: Page | None = None


def sheet_title(spec: SheetSpec, title: str) -> str:
    """The title a sheet carries: ``title``, and which page it is when the sheet is split."""
    if spec.page is None:
        return title
    return f"{title} · page {spec.page.number} of {spec.page.count} ({spec.page.note})"


def sheet_rows(layout: Layout, iconset: IconSet, alphas: Sequence[Alpha] | None) -> list[Alpha]:
    """The coefficient rows of a sheet: ``alphas``, or the layout's default for ``None``.

    Grid and compare default to :func:`default_alphas`; swatches take only
    real coefficients and default to :data:`SWATCH_ALPHAS`.
    """
    match layout:
        case Layout.GRID | Layout.COMPARE:
            return default_alphas(iconset) if alphas is None else list(alphas)
        case Layout.SWATCHES:
            return [a for a in (alphas or ()) if a is not None] or list(SWATCH_ALPHAS)
        case _:
            assert_never(layout)


def default_alphas(iconset: IconSet) -> list[Alpha]:
    """``1`` and the set's own coefficients (dropped when every icon has 1)."""
    return [1.0] if all(i.alpha == 1.0 for i in iconset.icons) else [1.0, ICON_ALPHA]


def _slug(text: str) -> str:
    return re.sub(r"[^a-z0-9]+", "-", text.lower()).strip("-") or "x"


def plan_sheets(
    layout: Layout, canvases: Sequence[Canvas], sizes: Sequence[int], prefix: str
) -> list[SheetSpec]:
    """The sheets a layout produces, with predictable, distinct file names.

    >>> from alpha_audit.model import Canvas
    >>> [s.name for s in plan_sheets(Layout.GRID, [Canvas("Paper", "#fff")], [16, 48], "demo")]
    ['demo-grid-paper-16px.png', 'demo-grid-paper-48px.png']
    """
    stem = _slug(prefix)
    slugs: list[str] = []
    for canvas in canvases:
        slug = _slug(canvas.name)
        slugs.append(slug if slug not in slugs else f"{slug}-{len(slugs) + 1}")
    match layout:
        case Layout.GRID:
            return [
                SheetSpec(f"{stem}-grid-{slug}-{size}px.png", layout, (canvas,), size)
                for canvas, slug in zip(canvases, slugs, strict=True)
                for size in sizes
            ]
        case Layout.SWATCHES:
            return [
                SheetSpec(f"{stem}-swatches-{slug}.png", layout, (canvas,), max(sizes))
                for canvas, slug in zip(canvases, slugs, strict=True)
            ]
        case Layout.COMPARE:
            return [
                SheetSpec(f"{stem}-compare-{size}px.png", layout, tuple(canvases), size)
                for size in sizes
            ]
        case _:
            assert_never(layout)


def alpha_label(alpha: Alpha, icons: Sequence[Icon]) -> str:
    """How a coefficient row is captioned on a sheet."""
    if alpha is not None:
        return f"alpha = {alpha:g}"
    values = sorted({i.alpha for i in icons})
    if len(values) == 1:
        return f"alpha = {values[0]:g} (the set's)"
    return f"alpha = each icon's own ({values[0]:g} to {values[-1]:g})"


def alphas_for(alpha: Alpha, icons: Sequence[Icon]) -> NDArray[np.float64]:
    """The coefficient of every icon in a row: ``alpha``, or each icon's own for ``None``."""
    import numpy as np

    if alpha is None:
        return np.array([i.alpha for i in icons], dtype=np.float64)
    return np.full(len(icons), float(alpha))
