"""Per-paint coverage: each paint of each icon rendered on its own, reduced to size metrics.

For every icon the paints are read (:mod:`alpha_audit.load.paints`) and grouped
by colour and opacity; each group is rasterised alone, opaque, at every size
(:func:`~alpha_audit.load.paints.isolate_paints`), and its mask is reduced at
once to :class:`~alpha_audit.color.coverage.CoverageStats`.  Both happen in
the sandboxed render workers (:class:`~alpha_audit.load.sandbox.ReadPaints`):
one job per icon, so one time budget covers its reading and all its groups and
sizes, and this process only reads files and reduces masks.  Masks are not
kept unless asked for (:func:`paint_masks`): memory stays bounded by the pool
whatever the number of icons, paints and sizes.

What a render gave is kept in the render cache
(:mod:`alpha_audit.load.render_cache`): an icon whose bytes, sizes and
renderer are unchanged since an earlier run is neither read nor rendered
again, nor is a file the paint reader refused (its bounds are counted, so it
always will).
"""

from __future__ import annotations

import contextlib
import hashlib
import itertools
import math
import struct
import zlib
from collections.abc import Callable, Iterable, Iterator, Sequence
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from alpha_audit.color.coverage import CoverageStats, coverage_stats_of
from alpha_audit.errors import SvgError
from alpha_audit.load.paints import decode_paints, encode_paints
from alpha_audit.load.render_cache import RenderCache, entry_key, open_default
from alpha_audit.load.sandbox import PaintsReply, ReadPaints, RenderLimits, RenderPool
from alpha_audit.load.svg import read_svg
from alpha_audit.model import IconProblem
from alpha_audit.paints import IconPaints, PaintCoverage, PaintGroup, PaintSet, SvgPaints

__all__ = [
    "MAX_PAINT_GROUPS",
    "IconMasks",
    "PaintMasks",
    "measure_paints",
    "paint_masks",
]

# Distinct (colour, opacity) pairs measured per icon.  Icon sets use one to a
# handful; an illustration with hundreds is not an icon this audit can judge
# paint by paint, and one render per paint would be unbounded work.
MAX_PAINT_GROUPS = 32

Mask = NDArray[np.uint8]  # 8-bit coverage codes, alpha x 255


@dataclass(frozen=True)
class IconMasks:
    """An icon's paint groups and, per size, one coverage mask per group (same order).

    ``masks[size][k]`` is the ``size x size`` mask of ``groups[k]`` as cairo's
    8-bit codes (coverage x 255, read-only): the group's geometry drawn alone
    and opaque, so a preview draws it in the group's colour at the group's
    opacity times the coverage.  The groups are the audit's
    (:meth:`SvgPaints.groups`).
    """

    icon: str
    file: Path
    paints: SvgPaints
    groups: tuple[PaintGroup, ...]
    masks: dict[int, tuple[Mask, ...]]
    stats: dict[int, tuple[CoverageStats, ...]] = field(default_factory=dict)


@dataclass(frozen=True)
class PaintMasks:
    """Per-icon paint-group masks plus the icons that could not be read or rendered."""

    icons: dict[str, IconMasks]
    problems: tuple[IconProblem, ...]

    def paint_set(self) -> PaintSet:
        """The same icons as :func:`measure_paints` gives them: coverage figures, no masks."""
        return PaintSet(
            {
                name: IconPaints(
                    m.icon,
                    m.file,
                    m.paints,
                    tuple(
                        PaintCoverage(g, {size: m.stats[size][k] for size in m.stats})
                        for k, g in enumerate(m.groups)
                    ),
                )
                for name, m in self.icons.items()
            },
            self.problems,
        )


def measure_paints(
    icons: Iterable[tuple[str, Path]],
    sizes: Sequence[int],
    *,
    progress: Callable[[], None] | None = None,
    limits: RenderLimits | None = None,
    pool: RenderPool | None = None,
    cache: RenderCache | bool = True,
) -> PaintSet:
    """Read every (name, file)'s paints and measure each paint group at every size.

    A file that cannot be read, parsed or rendered, or that has more than
    :data:`MAX_PAINT_GROUPS` paint groups, is one problem; the rest go on.
    ``progress`` is called once per icon.  ``pool`` is a render pool the
    caller started early (:meth:`RenderPool.prestart`); it renders with that
    pool's limits, and the caller closes it.  ``cache``: True for the user's
    render cache (unless turned off, :func:`~alpha_audit.load.render_cache.disable`),
    False for none, or an open :class:`RenderCache`.
    """
    return _measure(
        icons, sizes, progress=progress, limits=limits, pool=pool, cache=cache, keep_masks=False
    ).paint_set()


def paint_masks(
    icons: Iterable[tuple[str, Path]],
    sizes: Sequence[int],
    *,
    progress: Callable[[], None] | None = None,
    limits: RenderLimits | None = None,
    pool: RenderPool | None = None,
    cache: RenderCache | bool = True,
) -> PaintMasks:
    """Every paint group's coverage mask of every (name, file) at every size.

    The same reading, groups, rendering, problems and cache as
    :func:`measure_paints` (an icon the audit measured is not rendered again),
    but the masks are kept: memory grows with icons x groups x sizes squared.
    """
    return _measure(
        icons, sizes, progress=progress, limits=limits, pool=pool, cache=cache, keep_masks=True
    )


@dataclass
class _Measured:
    """One icon as it is measured: read, then found in the cache or rendered."""

    index: int
    name: str
    path: Path
    digest: bytes
    data: bytes
    paints: SvgPaints | None = None
    groups: tuple[PaintGroup, ...] = ()
    stats: dict[int, tuple[CoverageStats, ...]] | None = None
    masks: dict[int, tuple[Mask, ...]] | None = None
    failure: str | None = None
    cached_paints: bool = False
    refused: str | None = None  # why the paint reader refused it, found this run


def _measure(
    icons: Iterable[tuple[str, Path]],
    sizes: Sequence[int],
    *,
    progress: Callable[[], None] | None,
    limits: RenderLimits | None,
    pool: RenderPool | None,
    cache: RenderCache | bool,
    keep_masks: bool,
) -> PaintMasks:
    """Measured icons in input order (masks empty unless kept), and the problems:
    unreadable ones, then unrenderable."""
    limits = pool.limits if pool is not None else limits or RenderLimits()
    sizes = tuple(dict.fromkeys(int(s) for s in sizes))
    opened = open_default() if cache is True else None
    store = opened if cache is True else cache or None
    early: dict[int, IconProblem] = {}  # unreadable or unparsable, by input position
    todo: list[_Measured] = []
    icons = list(icons)
    try:
        chunks = _uncached(icons, sizes, store, keep_masks, progress, early, todo)
        first, read = next(((c, end) for c, end in chunks if c), ([], len(icons)))
        if first:
            # No more icons can need rendering than those of this chunk and those unread.
            workers = min(limits.workers, len(first) + len(icons) - read)
            missing = itertools.chain(first, itertools.chain.from_iterable(c for c, _ in chunks))
            _render(missing, workers, sizes, limits, pool, keep_masks, progress, early, store)
        elif pool is not None:
            pool.pause()  # nothing to render: its workers starting up need not compete
        if store is not None:
            store.flush()
    finally:
        if opened is not None:
            opened.close()
    measured = {
        m.name: IconMasks(
            m.name,
            m.path,
            m.paints,
            m.groups,
            {size: m.masks[size] for size in sizes} if m.masks else {},
            {size: m.stats[size] for size in sizes},  # in the order asked for
        )
        for m in todo
        if m.index not in early and m.failure is None and m.paints is not None and m.stats
    }
    failed = [IconProblem(m.name, m.path, m.failure) for m in todo if m.failure is not None]
    return PaintMasks(measured, tuple(early[k] for k in sorted(early)) + tuple(failed))


def _uncached(
    icons: list[tuple[str, Path]],
    sizes: tuple[int, ...],
    store: RenderCache | None,
    keep_masks: bool,
    progress: Callable[[], None] | None,
    early: dict[int, IconProblem],
    todo: list[_Measured],
) -> Iterator[tuple[list[_Measured], int]]:
    """Read the icons and look them up in the cache :data:`_CHUNK` at a time, as the
    workers ask for more: each chunk's icons the cache does not complete, and how
    many icons have been read.

    The first icons render while the rest are read.  Each icon read joins
    ``todo``; one unreadable, or refused by the paint reader in an earlier run,
    joins ``early``.  ``progress`` counts the icons done without a render.
    """
    for begin in range(0, len(icons), _CHUNK):
        chunk: list[_Measured] = []
        for index, (name, file) in enumerate(icons[begin : begin + _CHUNK], begin):
            path = Path(file)
            try:
                data = read_svg(path)
            except SvgError as exc:
                early[index] = IconProblem(name, path, _with_line(exc))
                continue
            chunk.append(_Measured(index, name, path, hashlib.sha256(data).digest(), data))
        todo += chunk
        if store is not None:
            _from_cache(store, chunk, sizes, keep_masks)
        for m in chunk:
            if m.refused is not None:  # refused by the paint reader in an earlier run
                early[m.index] = IconProblem(m.name, m.path, m.refused)
        missing = [
            m for m in chunk if m.refused is None and (m.stats is None or len(m.stats) < len(sizes))
        ]
        end = min(begin + _CHUNK, len(icons))
        if progress is not None:  # icons unread, refused before or all cached: done now
            for _ in range(end - begin - len(missing)):
                progress()
        yield missing, end


_CHUNK = 64


def _render(
    missing: Iterable[_Measured],
    workers: int,
    sizes: tuple[int, ...],
    limits: RenderLimits,
    pool: RenderPool | None,
    keep_masks: bool,
    progress: Callable[[], None] | None,
    early: dict[int, IconProblem],
    store: RenderCache | None,
) -> None:
    """Read and render the icons the cache did not have: one job per icon, its paints
    read in the worker (off this process's path, inside the sandbox's limits).

    Each icon's cache entries are made (``store``, written by its flush) as its reply
    comes, while the workers render the next ones, and its masks are dropped unless
    kept: none waits for the last icon."""
    jobs = (
        ((m, todo), ReadPaints(m.data, MAX_PAINT_GROUPS), todo)
        for m in missing
        for todo in [tuple(s for s in sizes if m.stats is None or s not in m.stats)]
    )
    workers = max(1, workers)
    with contextlib.nullcontext(pool) if pool else RenderPool(limits, workers=workers) as used:
        used.size = workers
        for (m, todo), outcome in used.stream(jobs):
            m.data = b""  # answered: the file's bytes are not needed again
            if progress is not None:
                progress()
            if isinstance(outcome, str):  # out of time, crashed ...
                m.failure = outcome
                continue
            if not isinstance(outcome, PaintsReply):
                raise TypeError(f"a ReadPaints job answered {type(outcome).__name__}")
            if outcome.problem is not None:  # the file's paints could not be read
                early[m.index] = IconProblem(m.name, m.path, outcome.problem)
                m.refused = outcome.problem if outcome.lasting else None
                if store is not None and m.refused is not None and not m.cached_paints:
                    store.put(entry_key("refused", m.digest), m.refused.encode())
                continue
            paints = decode_paints(outcome.paints)
            if paints is None or len(paints.groups()) != len(outcome.masks):
                m.failure = "renderer sent a malformed reply; refused"
                continue
            m.paints, m.groups = paints, paints.groups()
            rendered: dict[int, tuple[Mask, ...]] = {}
            for k, size in enumerate(todo):
                per_group = [masks[k] for masks in outcome.masks]
                failure = next((r for r in per_group if isinstance(r, str)), None)
                if failure is not None:
                    m.failure = failure
                    break
                rendered[size] = tuple(r for r in per_group if not isinstance(r, str))
            else:
                stats = _keep(m, rendered, keep_masks)
                if store is not None:
                    _to_cache(store, m, paints, {size: stats[size] for size in rendered}, rendered)


def _keep(
    m: _Measured, rendered: dict[int, tuple[Mask, ...]], keep_masks: bool
) -> dict[int, tuple[CoverageStats, ...]]:
    """Add what was rendered to what the cache gave, reduced to statistics (returned)."""
    stats = dict(m.stats or {})
    reduced = iter(coverage_stats_of([mask for masks in rendered.values() for mask in masks]))
    for size, masks in rendered.items():
        stats[size] = tuple(next(reduced) for _ in masks)
    m.stats = stats
    if keep_masks:
        m.masks = {**(m.masks or {}), **rendered}
    return stats


# --- the render cache's entries ---------------------------------------------------------------

_STATS = struct.Struct(">dddI")


def _from_cache(
    store: RenderCache, todo: list[_Measured], sizes: tuple[int, ...], keep_masks: bool
) -> None:
    """Fill in what the cache has: each icon's paints, then its masks' statistics per size."""
    paint_keys = {m.index: entry_key("paints", m.digest) for m in todo}
    refused_keys = {m.index: entry_key("refused", m.digest) for m in todo}
    found = store.get([*paint_keys.values(), *refused_keys.values()])
    known = []
    for m in todo:
        refusal = found.get(refused_keys[m.index])
        if refusal is not None:
            m.refused = _decode_refusal(refusal)
            if m.refused is not None:
                m.cached_paints = True  # nothing to write back
                continue
            store.forget(refused_keys[m.index])
        value = found.get(paint_keys[m.index])
        if value is None:
            continue
        paints = decode_paints(value)
        if paints is None or len(paints.groups()) > MAX_PAINT_GROUPS:
            store.forget(paint_keys[m.index])
            continue
        m.paints, m.groups, m.cached_paints = paints, paints.groups(), True
        known.append(m)
    mask_keys = {(m.index, s): entry_key("masks", m.digest, s) for m in known for s in sizes}
    found = store.get(mask_keys.values())
    for m in known:
        stats: dict[int, tuple[CoverageStats, ...]] = {}
        masks: dict[int, tuple[Mask, ...]] = {}
        for size in sizes:
            key = mask_keys[(m.index, size)]
            value = found.get(key)
            if value is None:
                continue
            decoded = _decode_masks(value, len(m.groups), size, keep_masks)
            if decoded is None:
                store.forget(key)
                continue
            stats[size] = decoded[0]
            if keep_masks:
                masks[size] = decoded[1]
        m.stats = stats
        m.masks = masks if keep_masks else None


def _to_cache(
    store: RenderCache,
    m: _Measured,
    paints: SvgPaints,
    stats: dict[int, tuple[CoverageStats, ...]],
    rendered: dict[int, tuple[Mask, ...]],
) -> None:
    """Keep what was rendered of an icon that rendered completely: its paints (unless
    they came from the cache) and each size's statistics and masks."""
    if not m.cached_paints:
        store.put(entry_key("paints", m.digest), encode_paints(paints))
    for size, masks in rendered.items():
        store.put(entry_key("masks", m.digest, size), _encode_masks(stats[size], masks))


def _decode_refusal(value: bytes) -> str | None:
    """A paint reader's refusal from the cache: short printable text, else None."""
    try:
        text = value.decode()
    except UnicodeDecodeError:
        return None
    return text if 0 < len(value) <= 4096 and text.isprintable() else None


def _encode_masks(stats: Sequence[CoverageStats], masks: Sequence[Mask]) -> bytes:
    head = struct.pack(">I", len(stats))
    body = b"".join(_STATS.pack(s.q50, s.full_share, s.ink, s.pixels) for s in stats)
    return head + body + zlib.compress(b"".join(m.tobytes() for m in masks))


def _decode_masks(
    value: bytes, groups: int, size: int, keep_masks: bool
) -> tuple[tuple[CoverageStats, ...], tuple[Mask, ...]] | None:
    """Every group's statistics (and masks) at one size; None unless they make sense."""
    end = 4 + groups * _STATS.size
    if len(value) < end or struct.unpack_from(">I", value)[0] != groups:
        return None
    stats = tuple(
        CoverageStats(*_STATS.unpack_from(value, 4 + k * _STATS.size)) for k in range(groups)
    )
    for s in stats:
        if not (0 <= s.pixels <= size * size and math.isfinite(s.ink) and 0 <= s.ink <= s.pixels):
            return None
        if s.pixels and not (0 < s.q50 <= 1 and 0 <= s.full_share <= 1):
            return None
    if not keep_masks:
        return stats, ()
    try:
        raw = zlib.decompress(value[end:])
    except zlib.error:
        return None
    if len(raw) != groups * size * size:
        return None
    flat = np.frombuffer(raw, dtype=np.uint8)
    area = size * size
    return stats, tuple(flat[k * area : (k + 1) * area].reshape(size, size) for k in range(groups))


def _with_line(exc: SvgError) -> str:
    return f"line {exc.line}: {exc.message}" if exc.line else exc.message
