"""Per-paint coverage: each paint of each icon rendered on its own, reduced to size metrics.

For every icon the paints are read (:mod:`alpha_audit.load.paints`) and grouped
by colour and opacity; each group is rasterised alone, opaque, at every size
(:func:`~alpha_audit.load.paints.isolate_paints`) by the same sandboxed
worker pool as every other render, and its mask is reduced at once to
:class:`~alpha_audit.color.coverage.CoverageStats`.  Icons are read lazily,
as the pool asks for work, so parsing runs while the workers render, and masks
are never kept: memory stays bounded by the pool whatever the number of icons,
paints and sizes.
"""

from __future__ import annotations

import contextlib
from collections.abc import Callable, Iterable, Iterator, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from alpha_audit.color.coverage import CoverageStats, coverage_stats
from alpha_audit.errors import SvgError
from alpha_audit.load.paints import PaintGroup, SvgPaints, paints_and_isolates
from alpha_audit.load.svg import IconProblem, RenderLimits, read_svg

if TYPE_CHECKING:
    from alpha_audit.load.sandbox import RenderPool

__all__ = ["MAX_PAINT_GROUPS", "IconPaints", "PaintCoverage", "PaintSet", "measure_paints"]

# Distinct (colour, opacity) pairs measured per icon.  Icon sets use one to a
# handful; an illustration with hundreds is not an icon this audit can judge
# paint by paint, and one render per paint would be unbounded work.
MAX_PAINT_GROUPS = 32


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


def measure_paints(
    icons: Iterable[tuple[str, Path]],
    sizes: Sequence[int],
    *,
    progress: Callable[[], None] | None = None,
    limits: RenderLimits | None = None,
    pool: RenderPool | None = None,
) -> PaintSet:
    """Read every (name, file)'s paints and measure each paint group at every size.

    A file that cannot be read, parsed or rendered, or that has more than
    :data:`MAX_PAINT_GROUPS` paint groups, is one problem; the rest go on.
    ``progress`` is called once per icon.  ``pool`` is a render pool the
    caller started early (:meth:`RenderPool.prestart`); it renders with that
    pool's limits, and the caller closes it.
    """
    from alpha_audit.load.sandbox import RenderPool

    limits = pool.limits if pool is not None else limits or RenderLimits()
    sizes = tuple(int(s) for s in sizes)
    icons = list(icons)
    problems: list[IconProblem] = []
    read: list[tuple[str, Path, SvgPaints, tuple[PaintGroup, ...]]] = []
    remaining: list[int] = []  # per icon in ``read``: paint groups not yet measured

    def jobs() -> Iterator[tuple[tuple[int, int], bytes, tuple[int, ...]]]:
        """Each icon read and split into paint groups only when the pool asks for work."""
        for name, file in icons:
            path = Path(file)
            try:
                data = read_svg(path)
                paints, variants = paints_and_isolates(data, path=path, max_groups=MAX_PAINT_GROUPS)
            except SvgError as exc:
                problems.append(IconProblem(name, path, _with_line(exc)))
                if progress is not None:
                    progress()
                continue
            read.append((name, path, paints, paints.groups()))
            remaining.append(len(variants))
            if not variants and progress is not None:
                progress()
            for k, variant in enumerate(variants):
                yield (len(read) - 1, k), variant, sizes

    stats: dict[tuple[int, int], dict[int, CoverageStats]] = {}
    failed: dict[int, str] = {}
    workers = max(1, min(limits.workers, len(icons)))
    with contextlib.nullcontext(pool) if pool else RenderPool(limits, workers=workers) as used:
        used.size = workers
        for (icon, group), outcome in used.stream(jobs()):
            if isinstance(outcome, str):
                failed.setdefault(icon, outcome)
            else:
                per_size: dict[int, CoverageStats] = {}
                for size, mask in zip(sizes, outcome, strict=True):
                    if isinstance(mask, str):
                        failed.setdefault(icon, mask)
                    else:
                        per_size[size] = coverage_stats(mask)  # the mask is dropped here
                stats[(icon, group)] = per_size
            remaining[icon] -= 1
            if remaining[icon] == 0 and progress is not None:
                progress()
    result: dict[str, IconPaints] = {}
    for i, (name, path, paints, groups) in enumerate(read):
        if i in failed:
            problems.append(IconProblem(name, path, failed[i]))
            continue
        coverage = tuple(PaintCoverage(g, stats[(i, k)]) for k, g in enumerate(groups))
        result[name] = IconPaints(name, path, paints, coverage)
    return PaintSet(result, tuple(problems))


def _with_line(exc: SvgError) -> str:
    return f"line {exc.line}: {exc.message}" if exc.line else exc.message
