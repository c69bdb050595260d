"""Source maps (ECMA-426, revision 3): from a bundled file's position to its source's.

A bundler that writes ``/*# sourceMappingURL=theme.css.map */`` at the end
of a CSS file (esbuild, webpack's css-loader, Sass, PostCSS, Lightning CSS)
says in the map where each piece of the output came from.  :class:`SourceMap`
reads a map's ``sources`` (joined to ``sourceRoot`` and resolved against the
map's own place) and decodes its ``mappings`` -- per generated line,
``;``-separated; per segment, ``,``-separated Base64 VLQ fields (generated
column, source, original line, original column, each relative to the
previous one) -- and :meth:`SourceMap.original` answers the original place
of a generated one: the segment that starts at or before it on its line.
Lines and columns are 0-based and count UTF-16 code units, as the format
does.

No well-kept Python library reads source maps (the PyPI ones were last
released between 2015 and 2018), so this is the few dozen lines of the
format's section 6 that lookups need; index maps (``sections``) are not
read.
"""

from __future__ import annotations

import base64
import binascii
import bisect
import json
import re
from dataclasses import dataclass
from pathlib import Path
from urllib.parse import unquote, urlsplit

__all__ = [
    "MAX_MAP_BYTES",
    "SourceMap",
    "SourceMapError",
    "decode_vlq",
    "inline_map",
    "mapping_url",
    "source_file",
]

MAX_MAP_BYTES = 32 << 20  # a large app's CSS map is a few MB
_BASE64 = {c: k for k, c in enumerate(
    "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/"
)}  # fmt: skip
# ECMA-426, 11.1: the last sourceMappingURL comment of a CSS file.
_CSS_COMMENT = re.compile(r"/\*[#@]\s*sourceMappingURL=([^\s*]+)\s*\*/\s*$")


class SourceMapError(ValueError):
    """A map that is not one (bad JSON, a bad VLQ digit, an index map)."""


def decode_vlq(field: str) -> list[int]:
    """The signed integers of one segment's Base64 VLQ digits (ECMA-426, 5.1).

    >>> decode_vlq("AAgBC")
    [0, 0, 16, 1]
    >>> decode_vlq("D")
    [-1]
    """
    values: list[int] = []
    shift = value = 0
    for char in field:
        digit = _BASE64.get(char)
        if digit is None:
            raise SourceMapError(f"{char!r} is not a Base64 VLQ digit")
        value += (digit & 31) << shift
        if digit & 32:
            shift += 5
            continue
        values.append(-(value >> 1) if value & 1 else value >> 1)
        shift = value = 0
    if shift:
        raise SourceMapError("a VLQ value ends in a continuation digit")
    return values


def mapping_url(css: str) -> str | None:
    """The ``sourceMappingURL`` a CSS text ends with, if any.

    >>> mapping_url("a{color:red}\\n/*# sourceMappingURL=a.css.map */\\n")
    'a.css.map'
    """
    match = _CSS_COMMENT.search(css[-4096:])
    return match.group(1) if match else None


def inline_map(url: str) -> str | None:
    """The JSON text of a ``data:application/json;base64,...`` map URL, else ``None``."""
    if not url.startswith("data:"):
        return None
    head, _, body = url[5:].partition(",")
    if not head.startswith("application/json"):
        return None
    try:
        return (
            base64.b64decode(body, validate=True).decode("utf-8")
            if head.endswith(";base64")
            else unquote(body)
        )
    except (binascii.Error, UnicodeDecodeError):
        return None


@dataclass(frozen=True)
class SourceMap:
    """A decoded map: ``sources`` as written (joined to ``sourceRoot``), segments per line."""

    sources: tuple[str, ...]
    lines: tuple[tuple[tuple[int, int, int, int], ...], ...]

    @classmethod
    def parse(cls, text: str) -> SourceMap:
        """Decode a map's JSON text; :class:`SourceMapError` when it is none we can read."""
        try:
            data = json.loads(text)
        except (json.JSONDecodeError, RecursionError) as exc:
            raise SourceMapError(f"not JSON: {exc}") from exc
        if not isinstance(data, dict) or data.get("version") != 3 or "sections" in data:
            raise SourceMapError("not a version 3 source map with mappings")
        root = data.get("sourceRoot") or ""
        raw_sources = data.get("sources")
        mappings = data.get("mappings")
        if not isinstance(raw_sources, list) or not isinstance(mappings, str):
            raise SourceMapError("no sources or mappings")
        if not isinstance(root, str):
            root = ""
        if root and not root.endswith("/"):
            root += "/"
        sources = tuple(f"{root}{s}" if isinstance(s, str) else "" for s in raw_sources)
        lines: list[tuple[tuple[int, int, int, int], ...]] = []
        source = line = column = 0
        for text_line in mappings.split(";"):
            generated = 0
            segments: list[tuple[int, int, int, int]] = []
            for field in text_line.split(","):
                if not field:
                    continue
                values = decode_vlq(field)
                generated += values[0]
                if len(values) >= 4:
                    source += values[1]
                    line += values[2]
                    column += values[3]
                    segments.append((generated, source, line, column))
                elif len(values) != 1:
                    raise SourceMapError(f"a segment of {len(values)} fields")
            segments.sort()
            lines.append(tuple(segments))
        return cls(sources, tuple(lines))

    def original(self, line: int, column: int) -> tuple[str, int, int] | None:
        """``(source, line, column)`` of generated ``line``/``column`` (0-based), if mapped.

        The segment that starts at or before ``column`` on that line answers
        (ECMA-426, 6: a mapping covers up to the next one); a position before
        a line's first segment, or on a line with none, is unmapped.
        """
        if not 0 <= line < len(self.lines):
            return None
        segments = self.lines[line]
        k = bisect.bisect_right(segments, (column, 1 << 62, 0, 0)) - 1
        if k < 0:
            return None
        _, source, source_line, source_column = segments[k]
        if not 0 <= source < len(self.sources) or not self.sources[source]:
            return None
        return self.sources[source], source_line, source_column


def source_file(source: str, map_file: Path, root: Path) -> Path | None:
    """The project file a map's source names, or ``None``: another scheme, or outside ``root``.

    A relative source resolves against the map's own folder (ECMA-426, 6.1);
    ``webpack://name/./src/a.css`` is ``src/a.css`` of webpack's context, the
    project root.  Only an existing file inside ``root`` (symlinks followed)
    is named.
    """
    parts = urlsplit(source)
    if parts.scheme == "webpack":
        candidate = root / unquote(parts.path).lstrip("/")
    elif parts.scheme == "file" and not parts.netloc:
        candidate = Path(unquote(parts.path))
    elif parts.scheme or parts.netloc or not parts.path:
        return None
    else:
        candidate = map_file.parent / unquote(parts.path)
    try:
        resolved = candidate.resolve(strict=True)
    except (OSError, RuntimeError):
        return None
    inside = resolved.is_relative_to(root.resolve())
    return resolved if inside and resolved.is_file() else None
