"""Writing reports: atomically, and never over a file without being asked."""

from __future__ import annotations

import os
import tempfile
from pathlib import Path

from alpha_audit.errors import UsageError

__all__ = ["write_text"]


def write_text(path: str | Path, text: str, *, overwrite: bool = False) -> Path:
    """Write ``text`` to ``path`` via a temporary file and rename.

    A failed run never leaves a truncated report; an existing file is replaced
    only with ``overwrite=True``.
    """
    target = Path(path)
    if target.exists() and not overwrite:
        raise UsageError("already exists; pass `overwrite=True` to replace it", path=target)
    if target.exists() and not target.is_file():
        raise UsageError("is not a regular file; refusing to replace it", path=target)
    folder = target.parent if str(target.parent) else Path(".")
    if not folder.is_dir():
        raise UsageError(f"folder {folder} does not exist", path=target)
    fd, tmp = tempfile.mkstemp(prefix=f".{target.name}.", dir=folder)
    umask = os.umask(0)
    os.umask(umask)
    os.chmod(tmp, 0o666 & ~umask)  # mkstemp creates 0600; a report is an ordinary file
    try:
        with os.fdopen(fd, "w", encoding="utf-8", newline="\n") as fh:
            fh.write(text)
        os.replace(tmp, target)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    return target
