"""SVG files to coverage masks: the only module that imports cairosvg.

A mask is the rendered alpha channel as float64 in [0, 1], ``size x size`` (kept as
8-bit codes in :class:`CoverageMasks` and converted on each lookup).
Icons are always rasterised at the requested icon size, never at the SVG's
declared width/height.  Problems are per file: a broken icon is reported and
the rest of the audit goes on.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from alpha_audit.errors import SvgError
from alpha_audit.load.files import read_capped

__all__ = [
    "MAX_SVG_BYTES",
    "IconProblem",
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


@dataclass(frozen=True)
class RenderLimits:
    """Bounds on rendering one untrusted SVG (documented in docs/ci.md).

    ``timeout`` is wall-clock seconds per icon for all its sizes; ``memory``
    the worker's address-space limit in bytes; ``cpu`` the worker's CPU-time
    backstop in seconds; ``workers`` how many render processes run at once.
    """

    timeout: float = 5.0
    memory: int = 1 << 30  # 1 GiB address space: Python + cairo need ~300 MiB
    cpu: int = 600
    workers: int = max(1, min(4, os.cpu_count() or 1))


@dataclass(frozen=True)
class IconProblem:
    """An icon that could not be used, with the reason."""

    icon: str
    file: Path
    message: str


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
) -> MaskSet:
    """Rasterise every (name, file) at every size; failures become problems.

    Files are read here (capped at :data:`MAX_SVG_BYTES`, refused when not SVG
    text) and rendered in sandboxed worker processes bounded by ``limits``: a
    file that takes too long, needs too much memory or crashes the renderer is
    one problem, and the rest of the set goes on.  ``progress`` is called once
    per icon.
    """
    from alpha_audit.load.sandbox import RenderPool

    limits = limits or RenderLimits()
    sizes = tuple(int(s) for s in sizes)
    masks: dict[tuple[str, int], NDArray[np.uint8]] = {}
    problems: list[IconProblem] = []
    jobs: list[tuple[str, Path, bytes]] = []
    for name, file in icons:
        try:
            jobs.append((name, Path(file), read_svg(file)))
        except SvgError as exc:
            problems.append(IconProblem(name, Path(file), exc.message))
            if progress is not None:
                progress()
    failed: dict[str, IconProblem] = {}
    with RenderPool(limits, workers=min(limits.workers, len(jobs))) as pool:
        for (name, file, _), outcome in zip(
            jobs, pool.map([(data, sizes) for _, _, data in jobs]), strict=True
        ):
            if isinstance(outcome, str):
                failed[name] = IconProblem(name, file, outcome)
            else:
                for size, mask in zip(sizes, outcome, strict=True):
                    if isinstance(mask, str):
                        failed.setdefault(name, IconProblem(name, file, mask))
                    elif not mask.any():
                        failed.setdefault(
                            name,
                            IconProblem(name, file, f"renders nothing at {size}px (empty icon)"),
                        )
                    else:
                        masks[(name, size)] = mask
            if progress is not None:
                progress()
    for name in failed:
        for size in sizes:
            masks.pop((name, size), None)
    order = {name: i for i, (name, _, _) in enumerate(jobs)}
    problems += sorted(failed.values(), key=lambda p: order[p.icon])
    return MaskSet(CoverageMasks(masks), tuple(problems))
