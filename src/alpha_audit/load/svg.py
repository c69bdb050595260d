"""SVG files to coverage masks: the only module that imports cairosvg.

A mask is the rendered alpha channel as float64 in [0, 1], ``size x size`` (kept as
8-bit codes in :class:`CoverageMasks` and converted on each lookup).
Icons are always rasterised at the requested icon size, never at the SVG's
declared width/height.  Problems are per file: a broken icon is reported and
the rest of the audit goes on.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from alpha_audit.errors import SvgError
from alpha_audit.load.files import read_capped
from alpha_audit.load.sandbox import RenderLimits, RenderPool
from alpha_audit.model import IconProblem

if TYPE_CHECKING:
    from alpha_audit.load.render_cache import RenderCache

__all__ = [
    "MAX_SVG_BYTES",
    "MaskSet",
    "RenderLimits",
    "rasterize",
    "rasterize_icons",
    "read_svg",
]

MAX_SVG_BYTES = 1 << 20  # 1 MiB; icon SVGs are a few KiB

_NOT_SVG = {
    b"\x89PNG": "a PNG image",
    b"\xff\xd8\xff": "a JPEG image",
    b"GIF8": "a GIF image",
    b"\x1f\x8b": "gzip-compressed data (.svgz is not accepted)",
    b"PK\x03\x04": "a ZIP archive",
    b"%PDF": "a PDF document",
    b"RIFF": "a RIFF (WebP/WAV) file",
}


def read_svg(path: str | Path) -> bytes:
    """Read an SVG file's bytes, refusing what is not small UTF-8 SVG text."""
    p = Path(path)
    data = read_capped(p, MAX_SVG_BYTES, SvgError, "an icon")
    for magic, kind in _NOT_SVG.items():
        if data.startswith(magic):
            raise SvgError(f"is {kind}, not SVG text", path=p)
    if b"\x00" in data:
        raise SvgError("contains NUL bytes; binary data, not SVG text", path=p)
    try:
        text = data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise SvgError(f"is not UTF-8 text (bad byte at offset {exc.start})", path=p) from exc
    if "<svg" not in text:
        raise SvgError("has no <svg> element; not an SVG file", path=p)
    return data


def rasterize(svg: bytes, size: int) -> NDArray[np.float64]:
    """Render SVG bytes to a ``size x size`` coverage mask (alpha / 255), in this process.

    No URL is ever fetched (external images, stylesheets, ``<use>`` targets and
    ``data:`` URLs all render as nothing) and entities are refused, but time
    and memory are not bounded here: for files from strangers use
    :func:`rasterize_icons`, which renders in sandboxed worker processes.
    """
    from alpha_audit.load._svg_worker import render_alpha

    alpha = np.frombuffer(render_alpha(svg, size), dtype=np.uint8).reshape(size, size)
    return alpha.astype(np.float64) / 255.0


class CoverageMasks(Mapping[tuple[str, int], NDArray[np.float64]]):
    """Masks by (icon name, size), stored as cairo's 8-bit codes, read as float64.

    Cairo's alpha holds only the values ``k / 255``, so the codes lose nothing;
    storing them takes 1 byte a pixel (300 icons at 1024 px: 0.3 GB, not 2.4).
    Each lookup builds the float64 mask on demand; :meth:`codes` gives the bytes.
    """

    def __init__(self, codes: dict[tuple[str, int], NDArray[np.uint8]] | None = None) -> None:
        self._codes: dict[tuple[str, int], NDArray[np.uint8]] = dict(codes or {})

    def __getitem__(self, key: tuple[str, int]) -> NDArray[np.float64]:
        return self._codes[key].astype(np.float64) / 255.0

    def __iter__(self) -> Iterator[tuple[str, int]]:
        return iter(self._codes)

    def __len__(self) -> int:
        return len(self._codes)

    def codes(self, key: tuple[str, int]) -> NDArray[np.uint8]:
        """The 8-bit coverage codes of one mask (read-only)."""
        return self._codes[key]


@dataclass(frozen=True)
class MaskSet:
    """Coverage masks by (icon name, size) plus the icons that failed."""

    masks: CoverageMasks
    problems: tuple[IconProblem, ...]

    def ok(self, icon: str) -> bool:
        """Whether ``icon`` rendered at every size."""
        return all(p.icon != icon for p in self.problems)


def rasterize_icons(
    icons: Iterable[tuple[str, Path]],
    sizes: Sequence[int],
    *,
    progress: Callable[[], None] | None = None,
    limits: RenderLimits | None = None,
    cache: RenderCache | bool = True,
) -> MaskSet:
    """Rasterise every (name, file) at every size; failures become problems.

    Files are read here (capped at :data:`MAX_SVG_BYTES`, refused when not SVG
    text) and rendered in sandboxed worker processes bounded by ``limits``: a
    file that takes too long, needs too much memory or crashes the renderer is
    one problem, and the rest of the set goes on.  ``progress`` is called once
    per icon.  Masks rendered before come from the render cache
    (:mod:`alpha_audit.load.render_cache`; ``cache`` as in
    :func:`~alpha_audit.load.paint_masks.measure_paints`).
    """
    from alpha_audit.load.render_cache import entry_key, open_default

    limits = limits or RenderLimits()
    sizes = tuple(dict.fromkeys(int(s) for s in sizes))
    problems: list[IconProblem] = []
    jobs = _read_jobs(icons, problems, progress)
    opened = open_default() if cache is True else None
    store = opened if cache is True else cache or None
    keys = {
        (name, size): entry_key("whole", digest, size)
        for name, _, _, digest in jobs
        for size in sizes
    }
    try:
        rendered = _cached(store, keys)
        todo = [(job, tuple(s for s in sizes if (job[0], s) not in rendered)) for job in jobs]
        todo = [(job, missing) for job, missing in todo if missing]
        if progress is not None:
            for _ in range(len(jobs) - len(todo)):
                progress()
        if todo:
            _render(todo, limits, rendered, store, keys, progress)
        if store is not None:
            store.flush()
    finally:
        if opened is not None:
            opened.close()
    return _mask_set(jobs, sizes, rendered, problems)


# An icon to render: its name, file, SVG bytes and their SHA-256.
_Job = tuple[str, Path, bytes, bytes]


def _read_jobs(
    icons: Iterable[tuple[str, Path]],
    problems: list[IconProblem],
    progress: Callable[[], None] | None,
) -> list[_Job]:
    """Read every file; one that cannot be read is a problem (and one step of progress)."""
    import hashlib

    jobs: list[_Job] = []
    for name, file in icons:
        try:
            data = read_svg(file)
        except SvgError as exc:
            problems.append(IconProblem(name, Path(file), exc.message))
            if progress is not None:
                progress()
            continue
        jobs.append((name, Path(file), data, hashlib.sha256(data).digest()))
    return jobs


def _cached(
    store: RenderCache | None, keys: Mapping[tuple[str, int], bytes]
) -> dict[tuple[str, int], NDArray[np.uint8] | str]:
    """The masks the render cache holds; an entry that does not inflate is forgotten."""
    rendered: dict[tuple[str, int], NDArray[np.uint8] | str] = {}
    found = store.get(keys.values()) if store is not None else {}
    for (name, size), key in keys.items():
        value = found.get(key)
        raw = _inflate(value, size * size) if value is not None else None
        if raw is not None:
            rendered[(name, size)] = np.frombuffer(raw, dtype=np.uint8).reshape(size, size)
        elif value is not None and store is not None:
            store.forget(key)
    return rendered


def _render(
    todo: Sequence[tuple[_Job, tuple[int, ...]]],
    limits: RenderLimits,
    rendered: dict[tuple[str, int], NDArray[np.uint8] | str],
    store: RenderCache | None,
    keys: Mapping[tuple[str, int], bytes],
    progress: Callable[[], None] | None,
) -> None:
    """Render each job's missing sizes into ``rendered`` (and the cache), in a sandbox."""
    import zlib

    with RenderPool(limits, workers=min(limits.workers, len(todo))) as pool:
        for (job, missing), outcome in pool.stream(
            ((job, missing), (job[2],), missing) for job, missing in todo
        ):
            for k, size in enumerate(missing):
                if isinstance(outcome, str):
                    mask: NDArray[np.uint8] | str = outcome
                elif isinstance(outcome, list):
                    mask = outcome[0][k]
                else:
                    raise TypeError(f"a render job answered {type(outcome).__name__}")
                rendered[(job[0], size)] = mask
                if store is not None and not isinstance(mask, str):
                    store.put(keys[(job[0], size)], zlib.compress(mask.tobytes()))
            if progress is not None:
                progress()


def _mask_set(
    jobs: Sequence[_Job],
    sizes: Sequence[int],
    rendered: Mapping[tuple[str, int], NDArray[np.uint8] | str],
    problems: list[IconProblem],
) -> MaskSet:
    """Each icon's masks, or its first problem (a reason, or nothing drawn at a size)."""
    masks: dict[tuple[str, int], NDArray[np.uint8]] = {}
    for name, file, _, _ in jobs:
        good = {}
        for size in sizes:
            mask = rendered[(name, size)]
            if isinstance(mask, str):
                problems.append(IconProblem(name, file, mask))
                break
            if not mask.any():
                problems.append(
                    IconProblem(name, file, f"renders nothing at {size}px (empty icon)")
                )
                break
            good[(name, size)] = mask
        else:
            masks.update(good)
    return MaskSet(CoverageMasks(masks), tuple(problems))


def _inflate(value: bytes, length: int) -> bytes | None:
    """A cached mask's bytes, None unless it inflates to exactly ``length`` bytes."""
    import zlib

    try:
        raw = zlib.decompressobj().decompress(value, length + 1)
    except zlib.error:
        return None
    return raw if len(raw) == length else None
