"""Where pages come from: a built Storybook, a folder of HTML pages, loopback URLs.

Each source lists its :class:`Target` pages: one per selected story
(``iframe.html?id=...``, Storybook 8 to 10's ``index.json``), one per HTML
file, or the URL itself.  Folders are served by alpha-audit's own loopback
server (:mod:`alpha_audit.browser.server`) under a path of their own.
"""

from __future__ import annotations

import fnmatch
import json
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from urllib.parse import quote, urlsplit

from alpha_audit.errors import InputError, UsageError
from alpha_audit.load.files import read_text_capped
from alpha_audit.load.names import check_name
from alpha_audit.load.paths import PathRefused, glob_contained

__all__ = [
    "LOOPBACK_HOSTS",
    "FolderSource",
    "Source",
    "StorybookSource",
    "Target",
    "UrlSource",
    "check_loopback_url",
    "targets",
    "url_origin",
]

LOOPBACK_HOSTS = ("localhost", "127.0.0.1", "::1")  # urlsplit's hostname: [::1] is "::1"
MAX_INDEX_BYTES = 32 << 20  # a Storybook of thousands of stories has an index of a few MB
MAX_PAGES = 20_000  # pages, stories and URLs of one run, every source together


@dataclass(frozen=True)
class StorybookSource:
    """A built Storybook (``storybook-static/`` with ``index.json``); ``stories`` are globs.

    A glob matches a story's id (``icons--toolbar``) or its ``Title/Name``
    path (``Icons/Toolbar``).
    """

    folder: Path
    stories: tuple[str, ...] = ("*",)


@dataclass(frozen=True)
class FolderSource:
    """A folder of HTML pages served on loopback; ``pattern`` selects the pages."""

    folder: Path
    pattern: str = "**/*.html"


@dataclass(frozen=True)
class UrlSource:
    """A page already served on loopback (``http://localhost:6006/...``)."""

    url: str


Source = StorybookSource | FolderSource | UrlSource


@dataclass(frozen=True)
class Target:
    """One page to audit: ``name`` (story id or path) and where to load it.

    ``mount`` is the index of the folder on alpha-audit's server (``None`` for
    a URL source) and ``path`` the URL path below it, query included.
    ``file`` is the source file a finding points at: the story's
    ``importPath`` from ``index.json`` (where it exists beside the build), or
    the HTML page; ``None`` for a URL.  ``export`` is the story's
    ``exportName`` in that file (Storybook 7 and later index it).
    """

    kind: str  # "storybook", "page", "url"
    name: str
    mount: int | None
    path: str
    storybook: bool
    file: Path | None = None
    export: str | None = None


_LOOPBACK_FORMS = (
    "give http://localhost:PORT/..., http://127.0.0.1:PORT/... or http://[::1]:PORT/... "
    "(pages are audited with no network but loopback)"
)


def check_loopback_url(url: str) -> str:
    """``url`` if it is ``http://`` on a loopback host with a port, else a :class:`UsageError`.

    >>> check_loopback_url("http://[::1]:6006/iframe.html")
    'http://[::1]:6006/iframe.html'
    >>> check_loopback_url("http://localhost:99999/")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    alpha_audit.errors.UsageError: 'http://localhost:99999/' is not a URL (Port out of range ...
    """
    shown = repr(url[:200])
    try:
        parts = urlsplit(url)
        port = parts.port  # a port that is not a number from 0 to 65535 raises here
    except ValueError as exc:  # also "[::1" (an unclosed IPv6 host)
        raise UsageError(f"{shown} is not a URL ({exc}): {_LOOPBACK_FORMS}") from None
    if parts.scheme != "http" or parts.hostname not in LOOPBACK_HOSTS or not port:
        raise UsageError(f"{shown} is not a loopback page: {_LOOPBACK_FORMS}")
    if parts.username is not None or parts.password is not None:
        raise UsageError(f"{shown} holds a user name or password; give the page's address alone")
    return url


def url_origin(url: str) -> str:
    """``host:port`` of a loopback URL (:func:`check_loopback_url`), as proxy lists take it.

    >>> url_origin("http://[::1]:6006/x"), url_origin("http://localhost:6006")
    ('[::1]:6006', 'localhost:6006')
    """
    parts = urlsplit(check_loopback_url(url))
    host = parts.hostname or ""
    return f"[{host}]:{parts.port}" if ":" in host else f"{host}:{parts.port}"


def _story_file(source: StorybookSource, import_path: object) -> Path | None:
    """A story's ``importPath`` (relative to where Storybook was built: the build's parent).

    Only named, never read: kept when it is a file inside that folder.
    """
    if not isinstance(import_path, str) or not import_path or "\x00" in import_path:
        return None
    base = source.folder.parent.resolve()
    path = (base / import_path).resolve()
    return path if path.is_relative_to(base) and path.is_file() else None


def _stories(source: StorybookSource) -> list[tuple[str, str, Path | None, str | None]]:
    """``(id, "Title/Name", story file, export name)`` of every story in the index, in order."""
    index = source.folder / "index.json"
    if not index.is_file():
        raise UsageError(
            "is not a built Storybook (no index.json): run 'storybook build' first, "
            "or give a folder of HTML pages",
            path=source.folder,
        )
    text = read_text_capped(index, MAX_INDEX_BYTES, InputError, "a Storybook index.json")
    try:
        data = json.loads(text)
    except (json.JSONDecodeError, RecursionError) as exc:
        raise InputError(f"not valid JSON: {exc}", path=index) from exc
    entries = data.get("entries") if isinstance(data, dict) else None
    if not isinstance(entries, dict) or data.get("v") not in (4, 5):
        raise InputError(
            f"not a Storybook 7-10 index (v {data.get('v') if isinstance(data, dict) else '?'}, "
            "expected 4 or 5 with entries)",
            path=index,
        )
    if len(entries) > MAX_PAGES:  # before any entry is read: the bound of every source
        raise InputError(
            f"lists {len(entries):,} entries; a run audits at most {MAX_PAGES:,} pages and "
            "stories (choose some with stories: globs, or split the Storybook)",
            path=index,
        )
    found = []
    for key, entry in entries.items():
        if not isinstance(entry, dict) or entry.get("type", "story") != "story":
            continue  # docs pages draw no story of their own
        # Ids, titles and names reach reports, URLs and globs: the one name policy of
        # every input (no control characters, at most MAX_NAME characters).
        story = check_name(str(entry.get("id", key)), path=index, key=str(key), what="story id")
        parts = []
        for field in ("title", "name"):
            value = entry.get(field)
            text = "" if value is None else str(value)
            if text:
                check_name(text, path=index, key=f"{key}.{field}", what=f"story {field}")
            parts.append(text)
        export = entry.get("exportName")
        found.append(
            (
                story,
                "/".join(parts),
                _story_file(source, entry.get("importPath")),
                export if isinstance(export, str) and export.isidentifier() else None,
            )
        )
    return found


def _bounded(count: int, folder: Path | None) -> None:
    """Refuse a run of more than :data:`MAX_PAGES` pages, stories and URLs together."""
    if count > MAX_PAGES:
        raise UsageError(
            f"more than {MAX_PAGES:,} pages and stories in one run; choose fewer "
            "(stories: globs, a narrower pattern) or split the sources",
            path=folder,
        )


def targets(sources: Sequence[Source]) -> list[Target]:
    """Every page of every source, in order; a selection that matches nothing is an error."""
    out: list[Target] = []
    for mount, source in enumerate(sources):
        if isinstance(source, StorybookSource):
            stories = _stories(source)
            chosen = [
                (story, file, export)
                for story, path, file, export in stories
                if any(fnmatch.fnmatchcase(story, g) or fnmatch.fnmatchcase(path, g)
                       for g in source.stories)
            ]  # fmt: skip
            if not chosen:
                raise UsageError(
                    f"no story matches {', '.join(source.stories)} "
                    f"({len(stories)} stories; globs match ids such as {stories[0][0]!r} "
                    "or Title/Name)"
                    if stories
                    else "the Storybook has no stories",
                    path=source.folder,
                )
            _bounded(len(out) + len(chosen), source.folder)
            for story, file, export in chosen:
                path = f"iframe.html?id={quote(story, safe='')}&viewMode=story"
                out.append(Target("storybook", story, mount, path, True, file, export))
        elif isinstance(source, FolderSource):
            try:
                pages = glob_contained(
                    source.folder, source.folder, source.pattern, limit=MAX_PAGES - len(out)
                )
            except PathRefused as exc:
                raise UsageError(str(exc), path=source.folder) from exc
            # The server never serves a dot file (browser.server): such a page is not one.
            relatives = [(p, p.relative_to(source.folder)) for p in pages]
            shown = [(p, r.as_posix()) for p, r in relatives
                     if not any(part.startswith(".") for part in r.parts)]  # fmt: skip
            if not shown:
                raise UsageError(f"no page matches {source.pattern!r}", path=source.folder)
            for page, relative in shown:
                out.append(Target("page", relative, mount, quote(relative), False, page))
        else:
            check_loopback_url(source.url)
            _bounded(len(out) + 1, None)
            out.append(Target("url", source.url, None, source.url, "iframe.html" in source.url))
    return out
