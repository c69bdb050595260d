"""Writing sheets: PNG files through the one writer (atomic, existing ones only when asked)."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

from alpha_audit.output import check_targets, write_bytes
from alpha_audit.preview.sheets.surface import Sheet

__all__ = ["check_writable", "write_sheet"]

_PNG_LEVEL = 1  # zlib level: flat canvases compress well even at 1; level 6 is ~3x slower


def write_sheet(sheet: Sheet, folder: str | Path, *, overwrite: bool = False) -> Path:
    """Save ``sheet`` as ``folder/<name>`` atomically (:func:`alpha_audit.output.write_bytes`).

    An existing file is replaced only with ``overwrite=True``.
    """
    return write_bytes(
        Path(folder) / sheet.spec.name,
        lambda fh: sheet.image.save(fh, format="PNG", compress_level=_PNG_LEVEL),
        overwrite=overwrite,
    )


def check_writable(targets: Sequence[Path], *, overwrite: bool) -> None:
    """Refuse before any work if the targets cannot all be written (:mod:`alpha_audit.output`)."""
    check_targets(targets, overwrite=overwrite)
