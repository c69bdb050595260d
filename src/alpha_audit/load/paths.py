"""Containment of every path read from a pull request: one mechanism, used before any I/O.

Every file of the checkout is attacker-controlled, symlinks included (git
stores them).  So a path is *resolved first* -- symlinks followed, ``..``
collapsed -- and only then compared with the one project root; a glob is
expanded by walking real directories under its base (symlinked directories
are never entered), and each match is contained the same way.  Nothing here
reads a file's contents.

:class:`PathRefused` carries a one-line reason; loaders turn it into their
:class:`~alpha_audit.errors.InputError` naming the file and key.
"""

from __future__ import annotations

import fnmatch
import os
import re
from collections.abc import Iterator
from pathlib import Path, PurePosixPath
from typing import NamedTuple

from alpha_audit.safe_text import first_unsafe, safe_text

__all__ = [
    "MAX_GLOB_ENTRIES",
    "PathRefused",
    "contain",
    "contain_argument",
    "enclosing_roots",
    "glob_contained",
    "project_root",
    "resolve",
]

# Directory entries one glob may visit before it is refused (time bound on a
# PR that adds a huge or deep tree; the icon count cap is checked separately).
MAX_GLOB_ENTRIES = 200_000
# RFC 3986, 3.1: scheme = ALPHA *( ALPHA / DIGIT / "+" / "-" / "." ) ":"; two
# letters at least so that Windows drive letters are reported as absolute.
_URL = re.compile(r"^[A-Za-z][A-Za-z0-9+.-]+:")


class PathRefused(ValueError):
    """A path or pattern that may not be used; the message says why, on one line."""


def _shown(text: str) -> str:
    return f"'{safe_text(text)}'"


def _check_text(text: str) -> PurePosixPath:
    """The relative POSIX path of ``text``, or :class:`PathRefused`."""
    if not text or not text.strip() or text.strip() in (".", "./"):
        raise PathRefused(f"{_shown(text)} is empty; give a path like svg/icon.svg")
    bad = first_unsafe(text)
    if bad is not None:
        raise PathRefused(
            f"{_shown(text)} contains the control or format character {safe_text(bad)}; not allowed"
        )
    if _URL.match(text) and not re.match(r"^[A-Za-z]:[\\/]", text):
        raise PathRefused(f"{_shown(text)} is a URL; give a path relative to the file")
    pure = PurePosixPath(text.replace("\\", "/"))
    if pure.is_absolute() or re.match(r"^[A-Za-z]:[\\/]", text):
        raise PathRefused(f"{_shown(text)} is absolute; give a path relative to the file")
    return pure


def resolve(path: Path) -> Path:
    """``path`` with every symlink followed; loops and unreadable links refused."""
    try:
        return path.resolve(strict=False)
    except RuntimeError as err:  # Python < 3.13: "Symlink loop from ..."
        raise PathRefused(f"{_shown(str(path))} is a symlink loop") from err
    except OSError as err:
        raise PathRefused(f"{_shown(str(path))} cannot be resolved: {err.strerror}") from err


def project_root(start: Path, markers: tuple[str, ...] = (".git",)) -> Path:
    """The nearest folder at or above ``start`` holding one of ``markers``, else ``start``.

    Never above: without a marker the search does not climb to ``/tmp`` or
    ``$HOME``, whose files a pull request does not control but an attacker
    on a shared runner might.
    """
    start = resolve(start)
    for folder in (start, *start.parents):
        if any((folder / marker).exists() for marker in markers):
            return folder
    return start


def enclosing_roots(path: str | Path, markers: tuple[str, ...] = (".git",)) -> list[Path]:
    """Every project root ``path``'s *name* lies in, nearest first, each resolved.

    The name is made absolute and normalised as text (``os.path.abspath``),
    never resolved: a folder committed as a link (``reports -> /``) does not
    choose the root it is measured against.  The roots are the ancestors that
    hold a marker, and the working folder's project root when the name lies
    under it; with none, the name's own folder (resolved).
    """
    name = Path(os.path.abspath(path))
    found = [resolve(a) for a in name.parents if any((a / m).exists() for m in markers)]
    here = project_root(Path.cwd(), markers)
    if name.is_relative_to(here) and here not in found:
        found.append(here)
    return found or [resolve(name.parent)]


def _through_link(path: Path, markers: tuple[str, ...] = (".git",)) -> bool:
    """Whether the name passes through a link inside its project (the name, or a folder
    between it and the project root its name lies in), rather than lying outside it."""
    name = Path(os.path.abspath(path))
    inside: list[Path] = []
    for folder in (name, *name.parents):
        if any((folder / m).exists() for m in markers):
            return any(q.is_symlink() for q in inside)
        inside.append(folder)
    return False  # in no project at all: outside it, whatever links lead there


def contain_argument(path: str | Path, root: Path | None = None) -> Path:
    """A file named by the user or found by discovery, resolved and inside its project root.

    The root comes from where the *name* is (:func:`enclosing_roots`), never
    from where a link points, so a link cannot pick its own base:
    ``theme.yaml -> /etc/passwd`` and ``linked/theme.yaml`` with
    ``linked -> /elsewhere`` are refused before a byte is read.
    """
    p = Path(path)
    if first_unsafe(str(p)) is not None:
        raise PathRefused(f"{_shown(str(p))} has a control or format character; not allowed")
    target = resolve(p.absolute())
    for base in [resolve(root)] if root is not None else enclosing_roots(p):
        if target.is_relative_to(base):
            continue
        if not _through_link(p):
            raise PathRefused(
                f"{_shown(str(p))} is outside the project root {base}: alpha-audit reads "
                "files of the project it runs in only; run it from the project holding it"
            )
        raise PathRefused(
            f"{_shown(str(p))} leads through a symlink to a file outside the project "
            f"root {base}; not allowed"
        )
    return target


def contain(root: Path, base: Path, relative: str) -> Path:
    """``base / relative`` resolved, symlinks included, and required inside ``root``.

    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     root = Path(tmp).resolve()
    ...     contain(root, root, "svg/a.svg") == root / "svg/a.svg"
    True
    """
    pure = _check_text(relative)
    candidate = resolve(base / pure)
    if not candidate.is_relative_to(resolve(root)):
        raise PathRefused(f"{_shown(relative)} resolves outside the project root; not allowed")
    return candidate


class _Matched(NamedTuple):
    """A directory entry a glob matched: a regular file (``plain``) or a symlink."""

    path: Path
    plain: bool


def glob_contained(root: Path, base: Path, pattern: str, *, limit: int) -> list[Path]:
    """Files under ``base`` matching ``pattern`` (``*``, ``?``, ``[...]``, ``**``), contained.

    Walks real directories only: a symlinked directory is never entered, so
    ``up/**`` with ``up -> /`` lists nothing outside; a matched file that is
    a symlink is resolved and must land inside ``root``.  At most ``limit``
    matches and :data:`MAX_GLOB_ENTRIES` visited entries.
    """
    root, start, parts = _glob_start(root, base, pattern)
    walk = _FolderWalk(pattern)
    found: list[Path] = []
    # Depth first with a stack of our own, not recursion: a tree nested thousands of
    # folders deep is bounded by MAX_GLOB_ENTRIES like any other, never by Python's stack.
    stack = [walk.steps(start, parts)] if parts else []
    while stack:
        step = next(stack[-1], None)
        if step is None:
            stack.pop()
        elif not isinstance(step, _Matched):
            stack.append(walk.steps(*step))
        else:
            target = _contained_match(step, root, start, pattern)
            if target is not None:
                found.append(target)
                if len(found) > limit:
                    raise PathRefused(f"{_shown(pattern)} matches more than {limit} files")
    return found


def _glob_start(root: Path, base: Path, pattern: str) -> tuple[Path, Path, list[str]]:
    """The resolved root and base and the pattern's steps; a pattern that leaves the
    manifest's folder, a base outside the root or a pattern ending in ``**`` is refused."""
    pure = _check_text(pattern)
    if ".." in pure.parts:
        raise PathRefused(f"{_shown(pattern)} leaves the manifest's folder; use svg/*.svg")
    root = resolve(root)
    start = resolve(base)
    if not start.is_relative_to(root):
        raise PathRefused(f"{_shown(str(base))} is outside the project root; not allowed")
    parts = [p for p in pure.parts if p not in ("", ".")]
    if parts and parts[-1] == "**":
        raise PathRefused(f"{_shown(pattern)} ends in **; add a file pattern like **/*.svg")
    return root, start, parts


class _FolderWalk:
    """The folders one glob visits, counted against :data:`MAX_GLOB_ENTRIES`."""

    def __init__(self, pattern: str) -> None:
        self.pattern = pattern
        self.visited = 0

    def steps(self, folder: Path, rest: list[str]) -> Iterator[tuple[Path, list[str]] | _Matched]:
        """One folder's work, in order: sub-walks ``(folder, rest)`` and matched files."""
        head, tail = rest[0], rest[1:]
        try:
            with os.scandir(folder) as it:
                entries = sorted(it, key=lambda e: e.name)
        except OSError:
            return
        self.visited += len(entries)
        if self.visited > MAX_GLOB_ENTRIES:
            raise PathRefused(
                f"{_shown(self.pattern)} visits more than {MAX_GLOB_ENTRIES} directory entries"
            )
        if head == "**":
            if tail:
                yield folder, tail  # ** matches zero folders
            for entry in entries:
                if entry.is_dir(follow_symlinks=False) and not entry.name.startswith("."):
                    yield Path(entry.path), rest
            return
        for entry in entries:
            if not fnmatch.fnmatchcase(entry.name, head):
                continue
            if tail:
                if entry.is_dir(follow_symlinks=False):
                    yield Path(entry.path), tail
            elif entry.is_file(follow_symlinks=False):
                yield _Matched(Path(entry.path), plain=True)
            elif entry.is_symlink():
                yield _Matched(Path(entry.path), plain=False)


def _contained_match(step: _Matched, root: Path, start: Path, pattern: str) -> Path | None:
    """The matched file's resolved path (None for a link to no file), refused when its
    name has an unsafe character or it resolves outside ``root``."""
    shown = os.path.relpath(step.path, start)
    if first_unsafe(shown) is not None:  # folders on the way count too
        raise PathRefused(
            f"{_shown(shown)} matched by {_shown(pattern)} has a control or "
            "format character in its name; not allowed"
        )
    # A file that is no link, in folders that are none under the resolved base,
    # is its own resolved path: only a link needs resolving and checking again.
    target = step.path if step.plain else resolve(step.path)
    if not target.is_relative_to(root):
        raise PathRefused(
            f"{_shown(shown)} matched by "
            f"{_shown(pattern)} resolves outside the project root; not allowed"
        )
    return target if step.plain or target.is_file() else None
