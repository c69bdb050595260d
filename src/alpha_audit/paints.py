"""What an icon draws: its paints, grouped by colour and opacity, and their coverage per size.

The loaders fill these in (:mod:`alpha_audit.load.paints` reads an SVG's
paints, :mod:`alpha_audit.load.paint_masks` measures each group's coverage);
the rows (:func:`alpha_audit.rows.audit`), previews and the page audit read
them.  Plain values: nothing here reads a file.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Literal

if TYPE_CHECKING:  # annotations only: the SVG paint reader runs in the render workers,
    # which import neither numpy nor the colour maths
    from alpha_audit.color.coverage import CoverageStats
    from alpha_audit.model import IconProblem

__all__ = [
    "CURRENT_COLOR",
    "IconPaints",
    "Paint",
    "PaintCoverage",
    "PaintGroup",
    "PaintKind",
    "PaintSet",
    "SvgPaints",
    "Unaudited",
]

# A paint of the host's colour: the manifest's colour stands for it (it follows the theme).
CURRENT_COLOR = "currentColor"
PaintKind = Literal["fill", "stroke"]


@dataclass(frozen=True)
class Paint:
    """One fill or stroke of one element.

    ``color`` is ``#rrggbb`` (a fixed colour: it will not follow the theme) or
    ``currentColor`` (the manifest colour).  ``opacity`` is effective: the
    product of ``opacity`` on the element and every ancestor, the
    ``fill-opacity`` or ``stroke-opacity``, and any alpha in the colour itself.
    """

    color: str
    kind: PaintKind
    opacity: float
    element: str
    line: int | None = None

    @property
    def fixed(self) -> bool:
        """Whether the colour is hard-coded rather than ``currentColor``."""
        return self.color != CURRENT_COLOR


@dataclass(frozen=True)
class Unaudited:
    """Something the SVG draws that the audit cannot judge, naming the element."""

    element: str
    line: int | None
    reason: str


@dataclass(frozen=True)
class PaintGroup:
    """Paints that draw the same colour at the same effective opacity (one audit row each)."""

    color: str
    opacity: float
    paints: tuple[Paint, ...]

    @property
    def key(self) -> tuple[str, float]:
        """``(color, opacity)``, what :func:`~alpha_audit.load.paints.isolate_paints` keeps."""
        return (self.color, self.opacity)

    @property
    def fixed(self) -> bool:
        """Whether the colour is hard-coded rather than ``currentColor``."""
        return self.color != CURRENT_COLOR


@dataclass(frozen=True)
class SvgPaints:
    """Every visible paint of one SVG, in document order, and what was not audited."""

    paints: tuple[Paint, ...]
    unaudited: tuple[Unaudited, ...] = field(default=())

    def groups(self) -> tuple[PaintGroup, ...]:
        """Paints grouped by ``(color, opacity)``, in order of first appearance."""
        by_key: dict[tuple[str, float], list[Paint]] = {}
        for p in self.paints:
            by_key.setdefault((p.color, p.opacity), []).append(p)
        return tuple(PaintGroup(c, o, tuple(ps)) for (c, o), ps in by_key.items())


@dataclass(frozen=True)
class PaintCoverage:
    """One paint group of one icon with its coverage at every size."""

    group: PaintGroup
    sizes: dict[int, CoverageStats]


@dataclass(frozen=True)
class IconPaints:
    """An icon's paints, what was not audited, and each paint group's coverage."""

    icon: str
    file: Path
    paints: SvgPaints
    coverage: tuple[PaintCoverage, ...]


@dataclass(frozen=True)
class PaintSet:
    """Per-icon paint coverage plus the icons that could not be read or rendered."""

    icons: dict[str, IconPaints]
    problems: tuple[IconProblem, ...]
