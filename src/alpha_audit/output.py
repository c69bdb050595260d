"""The one writer: atomic, checked before anything is written, never over a file unasked.

Every output goes through here: reports, baselines, PNG sheets, the preview
page, ``reproduce --out`` results and figures, and ``suggest --apply``.

- :func:`check_targets` validates every target of a run *before* any is written
  (an existing file without ``overwrite``, two outputs to one path, a missing
  folder, something that is not a regular file), so a run never fails after
  writing part of its outputs.
- :func:`write_files` writes several outputs as one step: every temporary file
  is complete before the first is renamed into place; on any error all
  temporary files are removed and nothing is left behind.
- A target that is a symbolic link is replaced by the new file (``os.replace``
  renames over the link), never written *through*, so a link in a checkout
  cannot aim our output at a file elsewhere; and a target named inside the
  project (the folder with ``.git``) must stay inside it once every folder on
  the way is resolved, so a *folder* committed as a link (``reports -> /etc``)
  cannot either.  A path given outside the project is the user's choice.
- ``OSError`` while writing (a full disk, a file-size limit) is a
  :class:`~alpha_audit.errors.UsageError` naming the file, not a traceback.
"""

from __future__ import annotations

import os
import tempfile
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import BinaryIO

from alpha_audit.errors import UsageError

__all__ = ["Output", "check_targets", "make_folder", "write_bytes", "write_files", "write_text"]


@dataclass(frozen=True)
class Output:
    """One file to write: its path and what to put there.

    ``data`` is the content, or a function that streams it to an open binary
    file (a PNG encoder), so large images are not held twice in memory.
    ``mode`` is the file mode to give it (default: 0666 less the umask, as for
    any new file).
    """

    path: Path
    data: bytes | Callable[[BinaryIO], None]
    mode: int | None = None

    @classmethod
    def text(cls, path: str | Path, text: str, mode: int | None = None) -> Output:
        """A UTF-8 text file, line endings as given."""
        return cls(Path(path), text.encode("utf-8"), mode)


def _umask() -> int:
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


def _folder(target: Path) -> Path:
    return target.parent if str(target.parent) else Path(".")


def _refuse_leaving(folder: Path, named: Path) -> None:
    """Refuse ``folder`` (of ``named``) if, resolved, it leaves a project its name is in."""
    from alpha_audit.load.paths import enclosing_roots

    real = folder.resolve()
    for root in enclosing_roots(folder / "-"):
        if not real.is_relative_to(root):
            raise UsageError(
                f"folder {folder} leads outside the project {root} ({real}) "
                "through a link; refusing to write there",
                path=named,
            )


def make_folder(folder: str | Path) -> Path:
    """Create an output folder (and its parents), checked like a target's folder first.

    ``dist/new`` with ``dist -> /elsewhere`` is refused before any folder is made.
    """
    path = Path(folder)
    _refuse_leaving(path, path)
    try:
        path.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise UsageError(f"cannot create the folder: {exc.strerror or exc}", path=path) from exc
    return path


def check_targets(targets: Iterable[str | Path], *, overwrite: bool) -> None:
    """Refuse, before anything is written, a set of targets that cannot all be written.

    Raises :class:`UsageError` naming the first target that already exists
    (without ``overwrite``), is not a regular file, sits in a missing folder,
    or is given twice (the same file reached by two names counts too).
    """
    seen: dict[Path, Path] = {}
    for given in targets:
        target = Path(given)
        _refuse_leaving(_folder(target), target)
        key = _folder(target).resolve() / target.name
        if key in seen:
            raise UsageError(f"is the target of two outputs (also {seen[key]})", path=target)
        seen[key] = target
        if target.is_symlink():
            if target.exists() and not overwrite:
                raise UsageError("already exists; pass `overwrite=True` to replace it", path=target)
            continue  # the link itself is replaced, whatever it points at
        if target.exists() and not target.is_file():
            raise UsageError("is not a regular file; refusing to replace it", path=target)
        if target.exists() and not overwrite:
            raise UsageError("already exists; pass `overwrite=True` to replace it", path=target)
        if not _folder(target).is_dir():
            raise UsageError(f"folder {_folder(target)} does not exist", path=target)


def _temporary(output: Output) -> str:
    """A complete temporary file next to ``output.path``; removed again on any error."""
    target = output.path
    fd, tmp = tempfile.mkstemp(prefix=f".{target.name}.", suffix=".tmp", dir=_folder(target))
    try:
        with os.fdopen(fd, "wb") as fh:
            if callable(output.data):
                output.data(fh)
            else:
                fh.write(output.data)
            fh.flush()
            os.fsync(fh.fileno())  # the rename must not publish a file the disk does not hold
        # mkstemp creates 0600; a report is an ordinary file unless a mode is kept.
        os.chmod(tmp, (0o666 & ~_umask()) if output.mode is None else output.mode)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    return tmp


def write_files(outputs: Sequence[Output], *, overwrite: bool = False) -> list[Path]:
    """Write every output, or none: checked first, then all temporary files, then renames.

    Returns the paths written, in order.
    """
    check_targets([o.path for o in outputs], overwrite=overwrite)
    done: list[tuple[str, Path]] = []
    current: Path | None = None
    renamed = 0
    try:
        for output in outputs:
            current = output.path
            done.append((_temporary(output), output.path))
        for tmp, target in done:
            current = target
            os.replace(tmp, target)  # over a symlink: replaces the link, not its target
            renamed += 1
    except OSError as exc:
        for tmp, _ in done:
            Path(tmp).unlink(missing_ok=True)
        reason = exc.strerror or str(exc)
        left = "nothing was written" if not renamed else f"{renamed} other file(s) already written"
        raise UsageError(f"cannot write: {reason}; {left}", path=current) from exc
    except BaseException:
        for tmp, _ in done:
            Path(tmp).unlink(missing_ok=True)
        raise
    return [target for _, target in done]


def write_text(path: str | Path, text: str, *, overwrite: bool = False) -> Path:
    """Write ``text`` (UTF-8) to ``path`` atomically; see :func:`write_files`."""
    return write_files([Output.text(path, text)], overwrite=overwrite)[0]


def write_bytes(
    path: str | Path,
    data: bytes | Callable[[BinaryIO], None],
    *,
    overwrite: bool = False,
    mode: int | None = None,
) -> Path:
    """Write ``data`` to ``path`` atomically; see :func:`write_files`."""
    return write_files([Output(Path(path), data, mode)], overwrite=overwrite)[0]
