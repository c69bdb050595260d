"""SVG files to coverage masks: the only module that imports cairosvg.

A mask is the rendered alpha channel as float64 in [0, 1], ``size x size``.
Icons are always rasterised at the requested icon size, never at the SVG's
declared width/height.  Problems are per file: a broken icon is reported and
the rest of the audit goes on.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from alpha_audit.errors import SvgError

__all__ = [
    "MAX_SVG_BYTES",
    "IconProblem",
    "MaskSet",
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
class IconProblem:
    """An icon that could not be used, with the reason."""

    icon: str
    file: Path
    message: str


def read_svg(path: str | Path) -> bytes:
    """Read an SVG file's bytes, refusing what is not small UTF-8 SVG text."""
    p = Path(path)
    try:
        with p.open("rb") as fh:
            data = fh.read(MAX_SVG_BYTES + 1)
    except FileNotFoundError as exc:
        raise SvgError("file not found", path=p) from exc
    except OSError as exc:
        raise SvgError(f"cannot read: {exc.strerror}", path=p) from exc
    if len(data) > MAX_SVG_BYTES:
        raise SvgError(f"larger than {MAX_SVG_BYTES // 1024} KiB; not an icon", path=p)
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
    """Render SVG bytes to a ``size x size`` coverage mask (alpha / 255).

    External resources are never fetched (cairosvg's safe mode, bytes only).
    """
    import cairocffi
    import cairosvg.parser
    import cairosvg.surface

    tree = cairosvg.parser.Tree(bytestring=svg, unsafe=False)
    surface = cairosvg.surface.PNGSurface(tree, None, 96, output_width=size, output_height=size)
    image: cairocffi.ImageSurface = surface.cairo
    image.flush()
    stride = image.get_stride()
    height, width = image.get_height(), image.get_width()
    argb = np.frombuffer(image.get_data(), dtype=np.uint32).reshape(height, stride // 4)[:, :width]
    alpha = (argb >> 24).astype(np.float64) / 255.0  # ARGB32 is native-endian, alpha on top
    surface.finish()
    if alpha.shape != (size, size):  # non-square viewBox: centre on a square canvas
        square = np.zeros((size, size))
        h, w = min(size, height), min(size, width)
        top, left = (size - h) // 2, (size - w) // 2
        square[top : top + h, left : left + w] = alpha[:h, :w]
        alpha = square
    return alpha


@dataclass(frozen=True)
class MaskSet:
    """Coverage masks by (icon name, size) plus the icons that failed."""

    masks: dict[tuple[str, int], NDArray[np.float64]]
    problems: tuple[IconProblem, ...]

    def ok(self, icon: str) -> bool:
        """Whether ``icon`` rendered at every size."""
        return all(p.icon != icon for p in self.problems)


def rasterize_icons(
    icons: Iterable[tuple[str, Path]], sizes: Sequence[int], *, progress=None
) -> MaskSet:
    """Rasterise every (name, file) at every size; failures become problems.

    ``progress`` is an optional callable invoked once per icon.
    """
    masks: dict[tuple[str, int], NDArray[np.float64]] = {}
    problems: list[IconProblem] = []
    for name, file in icons:
        try:
            data = read_svg(file)
            for size in sizes:
                mask = rasterize(data, size)
                if not mask.any():
                    raise SvgError(f"renders nothing at {size}px (empty icon)", path=file)
                masks[(name, size)] = mask
        except SvgError as exc:
            problems.append(IconProblem(name, file, exc.message))
        except Exception as exc:
            problems.append(
                IconProblem(name, file, f"cannot render SVG: {type(exc).__name__}: {exc}")
            )
        if progress is not None:
            progress()
    return MaskSet(masks, tuple(problems))
