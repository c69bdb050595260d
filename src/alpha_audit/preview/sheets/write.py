"""Writing sheets: PNG files replaced atomically, existing ones only when asked."""

from __future__ import annotations

import os
import tempfile
from collections.abc import Sequence
from pathlib import Path

from alpha_audit.errors import UsageError
from alpha_audit.preview.sheets.surface import Sheet

__all__ = ["check_writable", "write_sheet"]

_PNG_LEVEL = 1  # zlib level: flat canvases compress well even at 1; level 6 is ~3x slower


def write_sheet(sheet: Sheet, folder: str | Path, *, overwrite: bool = False) -> Path:
    """Save ``sheet`` as ``folder/<name>`` via a temporary file and rename.

    An existing file is replaced only with ``overwrite=True``.
    """
    target = Path(folder) / sheet.spec.name
    check_writable([target], overwrite=overwrite)
    fd, tmp = tempfile.mkstemp(prefix=f".{target.name}.", suffix=".png", dir=target.parent)
    try:
        with os.fdopen(fd, "wb") as fh:
            sheet.image.save(fh, format="PNG", compress_level=_PNG_LEVEL)
        os.chmod(tmp, 0o666 & ~_umask())  # mkstemp makes 0600; a sheet is an ordinary file
        os.replace(tmp, target)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    return target


def _umask() -> int:
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


def check_writable(targets: Sequence[Path], *, overwrite: bool) -> None:
    """Refuse before any work if a target exists (without ``overwrite``) or is not a file."""
    for target in targets:
        if target.exists() and not overwrite:
            raise UsageError("already exists; pass --force to replace it", path=target)
        if target.exists() and not target.is_file():
            raise UsageError("is not a regular file; refusing to replace it", path=target)
        if not target.parent.is_dir():
            raise UsageError(f"folder {target.parent} does not exist", path=target)
