"""Writing sheets: PNG or WebP files through the one writer (atomic, existing ones only when
asked)."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import Any

from alpha_audit.output import check_targets, write_bytes
from alpha_audit.preview.sheets.plan import ImageFormat
from alpha_audit.preview.sheets.surface import Sheet

__all__ = ["check_writable", "write_sheet"]

# PNG: zlib level 1 (flat canvases compress well even at 1; level 6 is ~3x slower).
# WebP: lossless (every pixel as drawn), method 4 of 0-6 (a third of the PNG's size).
_SAVE: dict[ImageFormat, dict[str, Any]] = {
    ImageFormat.PNG: {"format": "PNG", "compress_level": 1},
    ImageFormat.WEBP: {"format": "WEBP", "lossless": True, "method": 4},
}


def write_sheet(
    sheet: Sheet,
    folder: str | Path,
    *,
    overwrite: bool = False,
    image_format: ImageFormat = ImageFormat.PNG,
) -> Path:
    """Save ``sheet`` as ``folder/<name>`` atomically (:func:`alpha_audit.output.write_bytes`),
    the name's suffix that of ``image_format``.

    An existing file is replaced only with ``overwrite=True``.
    """
    options = _SAVE[image_format]
    return write_bytes(
        Path(folder) / image_format.file_name(sheet.spec.name),
        lambda fh: sheet.image.save(fh, **options),
        overwrite=overwrite,
    )


def check_writable(targets: Sequence[Path], *, overwrite: bool) -> None:
    """Refuse before any work if the targets cannot all be written (:mod:`alpha_audit.output`)."""
    check_targets(targets, overwrite=overwrite)
