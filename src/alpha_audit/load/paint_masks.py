"""Per-paint coverage: each paint of each icon rendered on its own, reduced to size metrics.

For every icon the paints are read (:mod:`alpha_audit.load.paints`) and grouped
by colour and opacity; each group is rasterised alone, opaque, at every size
(:func:`~alpha_audit.load.paints.isolate_paints`) by the same sandboxed
worker pool as every other render, and its mask is reduced at once to
:class:`~alpha_audit.color.coverage.CoverageStats`.  Masks are never kept:
jobs go to the pool in batches, so memory stays bounded by the batch whatever
the number of icons, paints and sizes.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path

from alpha_audit.color.coverage import CoverageStats, coverage_stats
from alpha_audit.errors import SvgError
from alpha_audit.load.paints import PaintGroup, SvgPaints, extract_paints, isolate_groups
from alpha_audit.load.svg import IconProblem, RenderLimits, read_svg

__all__ = ["MAX_PAINT_GROUPS", "IconPaints", "PaintCoverage", "PaintSet", "measure_paints"]

# Distinct (colour, opacity) pairs measured per icon.  Icon sets use one to a
# handful; an illustration with hundreds is not an icon this audit can judge
# paint by paint, and one render per paint would be unbounded work.
MAX_PAINT_GROUPS = 32
# Masks held at once: the pool returns each job's masks as float64, so a batch
# of jobs is sized to stay under this many bytes (at least one job: 1024 px x 3
# sizes is 24 MiB).  Larger batches keep the workers busier.
_BATCH_BYTES = 64 << 20
_MAX_BATCH = 1024


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
) -> PaintSet:
    """Read every (name, file)'s paints and measure each paint group at every size.

    A file that cannot be read, parsed or rendered, or that has more than
    :data:`MAX_PAINT_GROUPS` paint groups, is one problem; the rest go on.
    ``progress`` is called once per icon.
    """
    from alpha_audit.load.sandbox import RenderPool

    limits = limits or RenderLimits()
    sizes = tuple(int(s) for s in sizes)
    problems: list[IconProblem] = []
    read: list[tuple[str, Path, SvgPaints, tuple[PaintGroup, ...]]] = []
    jobs: list[tuple[int, int, bytes]] = []  # (icon index in read, group index, svg)
    for name, file in icons:
        path = Path(file)
        try:
            data = read_svg(path)
            paints = extract_paints(data, path=path)
            groups = paints.groups()
            if len(groups) > MAX_PAINT_GROUPS:
                raise SvgError(
                    f"draws {len(groups)} distinct paints (colour and opacity); at most "
                    f"{MAX_PAINT_GROUPS} are audited per icon",
                    path=path,
                )
            variants = isolate_groups(data, groups, path=path)
        except SvgError as exc:
            problems.append(IconProblem(name, path, _with_line(exc)))
            if progress is not None:
                progress()
            continue
        jobs += [(len(read), k, v) for k, v in enumerate(variants)]
        read.append((name, path, paints, groups))
        if not groups and progress is not None:
            progress()
    stats: dict[tuple[int, int], dict[int, CoverageStats]] = {}
    failed: dict[int, str] = {}
    remaining = {i: len(groups) for i, (_, _, _, groups) in enumerate(read)}
    with RenderPool(limits, workers=max(1, min(limits.workers, len(jobs)))) as pool:
        per_job = 8 * sum(s * s for s in sizes)
        step = max(1, min(_MAX_BATCH, _BATCH_BYTES // max(1, per_job)))
        for start in range(0, len(jobs), step):
            batch = jobs[start : start + step]
            outcomes = pool.map([(svg, sizes) for _, _, svg in batch])
            for (icon, group, _), outcome in zip(batch, outcomes, strict=True):
                if isinstance(outcome, str):
                    failed.setdefault(icon, outcome)
                else:
                    per_size: dict[int, CoverageStats] = {}
                    for size, mask in zip(sizes, outcome, strict=True):
                        if isinstance(mask, str):
                            failed.setdefault(icon, mask)
                        else:
                            per_size[size] = coverage_stats(mask)
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
