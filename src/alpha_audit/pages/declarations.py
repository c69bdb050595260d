"""Every measured paint points at a line: the CSS that sets its colour, else its story or page.

:mod:`alpha_audit.pages.cascade` says which declarations set an icon's
colour and its backdrop's, and where the engine says they are written (a
served URL, and from devtools a line and column).  :class:`ServedFiles`
turns that into places in the project:

* the served file behind the URL (the page server's own mapping: inside the
  source folder and the project root), read capped;
* the declaration in it: at the line and column devtools gave, checked
  against the text it said is there; or, from the probe's walk, in the rule
  the walk matched (tinycss2 over the sheet: the rule with that selector
  and a declaration of that property, at or after the rule's index), a
  ``<style>`` element found in the page by its text, a ``style`` or SVG
  presentation attribute found in the page by its text (once, or not at
  all);
* through a source map where the served CSS names one
  (``/*# sourceMappingURL=... */``, :mod:`alpha_audit.pages.sourcemap`): the
  original file and line, when it is a file inside the project root whose
  line there holds the property; else the served file itself (a Storybook
  build's ``assets/*.css``: Vite writes no CSS source maps).

:func:`paint_locations` gives one measured paint's places, in the order a
finding names them: the declaration that writes its colour's value
(``css-colour``: with a custom property, that property's winning
declaration, the line a fix edits), the declaration that reads it
(``css-colour-use``), the same two for the backdrop (``css-backdrop``,
``css-backdrop-use``), then the story's export in its file (``story``) or
the page (``page``).  :func:`finding_locations` puts a manifest's or design
token's lines first (they win when the icon maps to one) and gives
:class:`~alpha_audit.model.Location` objects.  A trace whose last value
does not give the colour the engine computed is not named at all: no line is
better than a wrong one.
"""

from __future__ import annotations

import re
import threading
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from coloraide import Color

from alpha_audit.errors import InputError
from alpha_audit.load.files import read_text_capped
from alpha_audit.load.spans import LineIndex
from alpha_audit.model import Location, Span
from alpha_audit.pages.capture import FoundIcon
from alpha_audit.pages.cascade import Declaration, Trace
from alpha_audit.pages.sourcemap import (
    MAX_MAP_BYTES,
    SourceMap,
    SourceMapError,
    inline_map,
    mapping_url,
    source_file,
)
from alpha_audit.pages.sources import Target

__all__ = [
    "PaintLocation",
    "ServedFiles",
    "SourcePlace",
    "finding_locations",
    "paint_index",
    "paint_locations",
    "story_line",
]

MAX_SOURCE_BYTES = 16 << 20  # a served style sheet, page or story file read to find a line
_DECLARATION_CHARS = 8192  # a declaration is read this far for its value's end
_BACKGROUND = {"background-color": ("background-color", "background"),
               "background-image": ("background-image", "background")}  # fmt: skip


@dataclass(frozen=True)
class PaintLocation:
    """One place a measured paint's finding names.

    ``file`` is inside the project root; ``line`` and ``column`` are 1-based
    (columns count code points, SARIF's ``unicodeCodePoints``).  ``what`` is
    ``css-colour``, ``css-colour-use``, ``css-backdrop``,
    ``css-backdrop-use``, ``story`` or ``page``.  For CSS: ``property`` is
    the property the paint reads (``color`` through ``currentColor``,
    ``fill``, ``stroke``, ``background-color``), ``custom_property`` the one
    written here or read here, ``value`` the value written here, ``token``
    the custom property at the end of the ``var()`` chain, and ``span`` the
    value's exact region (what a fix rewrites) where it is known.
    """

    file: Path
    line: int
    what: str
    column: int | None = None
    property: str | None = None
    custom_property: str | None = None
    value: str | None = None
    token: str | None = None
    span: Span | None = None

    def location(self) -> Location:
        """The same place as a finding's :class:`~alpha_audit.model.Location`."""
        return Location(self.file, self.line, self.what, self.span)


@dataclass(frozen=True)
class SourcePlace:
    """Where a declaration is written in the project: file, 1-based line and column, and
    its value's exact region where known."""

    file: Path
    line: int
    column: int
    span: Span | None


@dataclass(frozen=True)
class _StyleRule:
    index: int
    selector: str  # normalised (see _normal)
    declarations: tuple[Any, ...]  # tinycss2 Declaration nodes of its own block


def _normal(selector: str) -> str:
    """A selector compared loosely: CSSOM serialisation adds quotes and spaces, drops ``&``.

    >>> _normal('html[data-theme="dark"] > a::before') == _normal("html[data-theme=dark]>a:before")
    True
    """
    text = re.sub(r"[\s\"']", "", selector).lower().replace("::", ":")
    return text.removeprefix("&")


def _names(prop: str) -> tuple[str, ...]:
    return _BACKGROUND.get(prop, (prop,))


def _cp_offset(line_text: str, utf16: int) -> int:
    """The code-point offset in ``line_text`` of UTF-16 column ``utf16``."""
    units = 0
    for k, char in enumerate(line_text):
        if units >= utf16:
            return k
        units += 2 if ord(char) > 0xFFFF else 1
    return len(line_text)


def _utf16(line_text: str, offset: int) -> int:
    return sum(2 if ord(c) > 0xFFFF else 1 for c in line_text[:offset])


class ServedFiles:
    """From what the engine reports (served URLs) to files and lines of the project.

    ``local_file`` maps a URL to the file the page server serves there
    (:meth:`~alpha_audit.browser.server.PageServer.local_file`), ``None`` for
    any other; ``root`` is the project root, outside which nothing is
    named.  Files, their rules and source maps are read once each; an
    instance may be shared by threads.
    """

    def __init__(self, local_file: Callable[[str], Path | None], root: Path) -> None:
        self._local_file = local_file
        self.root = root.resolve()
        self._texts: dict[Path, LineIndex | None] = {}
        self._rules: dict[tuple[Path, int], list[_StyleRule]] = {}
        self._maps: dict[Path, tuple[SourceMap, Path] | None] = {}
        self._lock = threading.Lock()

    # ------------------------------------------------------------------ files
    def index(self, path: Path) -> LineIndex | None:
        """The text of a project file as a :class:`LineIndex`, ``None`` when unreadable."""
        with self._lock:
            if path in self._texts:
                return self._texts[path]
        found: LineIndex | None = None
        if path.resolve().is_relative_to(self.root):
            try:
                text = read_text_capped(path, MAX_SOURCE_BYTES, InputError, "a text file")
            except InputError:
                text = None
            if text is not None:
                bom = text.startswith("\ufeff")
                found = LineIndex(text.removeprefix("\ufeff"), path, "css", bom=bom)
        with self._lock:
            self._texts[path] = found
        return found

    def _rules_of(self, index: LineIndex, base: int, text: str) -> list[_StyleRule]:
        """Every style rule of a sheet (``text``, at ``base`` in the file), depth first."""
        import tinycss2

        key = (index.path, base)
        with self._lock:
            if key in self._rules:
                return self._rules[key]
        out: list[_StyleRule] = []
        grouping = {"media", "supports", "layer", "container", "scope", "starting-style",
                    "document"}  # fmt: skip

        def walk(nodes: Sequence[Any], depth: int) -> None:
            if depth > 32:
                return
            for node in nodes:
                if node.type == "qualified-rule":
                    selector = tinycss2.serialize(node.prelude)
                    content = tinycss2.parse_blocks_contents(
                        node.content, skip_comments=True, skip_whitespace=True
                    )
                    mine = tuple(n for n in content if n.type == "declaration")
                    out.append(_StyleRule(len(out), _normal(selector), mine))
                    walk([n for n in content if n.type != "declaration"], depth + 1)
                elif (
                    node.type == "at-rule"
                    and node.content is not None
                    and node.lower_at_keyword in grouping
                ):
                    walk(
                        tinycss2.parse_blocks_contents(
                            node.content, skip_comments=True, skip_whitespace=True
                        ),
                        depth + 1,
                    )

        walk(tinycss2.parse_stylesheet(text, skip_comments=True, skip_whitespace=True), 0)
        with self._lock:
            self._rules[key] = out
        return out

    # ---------------------------------------------------------------- places
    def _at(
        self, index: LineIndex, offset: int, name: str, limit: int | None = None
    ) -> SourcePlace | None:
        """The declaration of ``name`` starting at ``offset``, with its value's span.

        ``limit`` ends the text the declaration may take (a ``style``
        attribute's closing quote).
        """
        import tinycss2

        text = index.text
        if text[offset : offset + len(name)].lower() != name.lower():
            return None
        stop = offset + _DECLARATION_CHARS
        chunk = text[offset : stop if limit is None else min(stop, limit)]
        tokens = tinycss2.parse_component_value_list(chunk, skip_comments=False)
        local = LineIndex(chunk, index.path, "css")

        def start_of(token: Any) -> int:
            return int(local.starts[token.source_line - 1] + token.source_column - 1)

        line, column = index.position(offset)
        span = None
        colon = next(
            (k for k, t in enumerate(tokens) if t.type == "literal" and t.value == ":"), -1
        )
        if colon >= 0:
            value: list[Any] = []
            end = None
            for k in range(colon + 1, len(tokens)):
                t = tokens[k]
                if (t.type == "literal" and t.value in (";", "!")) or t.type == "error":
                    end = start_of(t)
                    break
                value.append(t)
            while value and value[-1].type in ("whitespace", "comment"):
                end = start_of(value.pop())
            while value and value[0].type in ("whitespace", "comment"):
                value.pop(0)
            if value:
                if end is None:
                    end = len(chunk) if offset + len(chunk) < stop else None
                if end is not None:
                    span = index.span(offset + start_of(value[0]), offset + end)
        return SourcePlace(index.path, line, column, span)

    def _from_devtools(self, d: Declaration, index: LineIndex) -> int | None:
        place = d.place
        assert place is not None and place.line is not None and place.column is not None
        if not 0 <= place.line < len(index.starts):
            return None
        start = index.starts[place.line]
        end = index.starts[place.line + 1] if place.line + 1 < len(index.starts) else None
        offset = start + _cp_offset(index.text[start:end], place.column)
        written = (place.text or d.name).strip()
        return offset if index.text.startswith(written, offset) else None

    def _from_walk(self, d: Declaration, index: LineIndex) -> int | None:
        place = d.place
        assert place is not None
        base, sheet = 0, index.text
        if place.sheet_text is not None:
            base, length = self._find_once(index.text, place.sheet_text, first=True)
            if base < 0:
                return None
            sheet = index.text[base : base + length]  # the file's own (CRLF) text
        elif place.inline:
            return None  # a constructed sheet or one a script wrote: not in the file
        rules = self._rules_of(index, base, sheet)
        wanted = _normal(place.selector or "")
        names = _names(d.property) if not d.property.startswith("--") else (d.property,)
        lower = tuple(n.lower() for n in names)
        after = place.rule or 0
        for rule in sorted(rules, key=lambda r: (r.index < after, abs(r.index - after))):
            if rule.selector != wanted:
                continue
            found = [
                n
                for n in rule.declarations
                if (n.name if n.name.startswith("--") else n.lower_name) in (names + lower)
                and bool(n.important) == d.important
            ]
            if found:
                node = found[-1]
                local = LineIndex(sheet, index.path, "css")
                return int(base + local.starts[node.source_line - 1] + node.source_column - 1)
        return None

    @staticmethod
    def _find_once(text: str, needle: str, *, first: bool = False) -> tuple[int, int]:
        """Where ``needle`` is in ``text``, and its length there (CRLF files too).

        HTML parsing turns CRLF into LF, so the DOM's text may be in the file
        with CRs.  ``(-1, 0)`` when absent, or (unless ``first``) repeated.
        """
        if not needle.strip():
            return -1, 0
        for candidate in (needle, needle.replace("\n", "\r\n")):
            at = text.find(candidate)
            if at >= 0:
                if first or text.find(candidate, at + 1) < 0:
                    return at, len(candidate)
                return -1, 0
        return -1, 0

    def _in_markup(self, d: Declaration, index: LineIndex) -> SourcePlace | None:
        """An attribute's declaration in the page's own markup, when it is there once.

        A presentation attribute (``stroke="#a30"``) is found by name and
        value; a ``style`` attribute by its whole text, then the property in
        it.  Text that a script wrote (a story's markup) is in no file.
        """
        place = d.place
        if place is None:
            return None
        if d.kind == "hint":
            pattern = re.compile(
                rf"(?<![\w-]){re.escape(d.name)}\s*=\s*([\"'])(?P<value>{re.escape(d.value)})\1",
                re.IGNORECASE,
            )
            found = list(pattern.finditer(index.text))
            if len(found) != 1:
                return None
            line, column = index.position(found[0].start())
            value = index.span(found[0].start("value"), found[0].end("value"))
            return SourcePlace(index.path, line, column, value)
        if place.text is None:
            return None
        at, length = self._find_once(index.text, place.text)
        written = index.text[at : at + length]
        inner = re.search(rf"(?<![\w-]){re.escape(d.name)}\s*:", written, re.IGNORECASE)
        if at < 0 or inner is None:
            return None
        return self._at(index, at + inner.start(), d.name, limit=at + length)

    def _mapped(self, place: SourcePlace, index: LineIndex, offset: int, name: str) -> SourcePlace:
        """Through the served CSS's source map to its original file, where it leads to one."""
        found = self._map_of(index)
        if found is None:
            return place
        source_map, map_file = found
        line0 = place.line - 1
        line_start = index.starts[line0]
        column16 = _utf16(index.text[line_start:], offset - line_start)
        original = source_map.original(line0, column16)
        if original is None:
            return place
        source, o_line, o_column = original
        path = source_file(source, map_file, self.root)
        target = self.index(path) if path is not None else None
        if target is None or not 0 <= o_line < len(target.starts):
            return place
        start = target.starts[o_line]
        o_offset = start + _cp_offset(target.text[start:], o_column)
        # A map may point at the rule rather than the declaration: the property's
        # first occurrence from there, within the rule.
        rest = target.text[o_offset : o_offset + _DECLARATION_CHARS]
        hit = re.search(rf"(?<![\w-]){re.escape(name)}\s*:|}}", rest, re.IGNORECASE)
        if hit is None or hit.group(0) == "}":
            return place
        return self._at(target, o_offset + hit.start(), name) or place

    def _map_of(self, index: LineIndex) -> tuple[SourceMap, Path] | None:
        path = index.path
        with self._lock:
            if path in self._maps:
                return self._maps[path]
        found = None
        url = mapping_url(index.text) if path.suffix.lower() == ".css" else None
        if url is not None:
            text = inline_map(url)
            map_file = path
            if text is None and ":" not in url.split("/")[0]:
                map_file = path.parent / url.split("?")[0].split("#")[0]
                try:
                    resolved = map_file.resolve(strict=True)
                    inside = resolved.is_relative_to(self.root)
                    text = (
                        read_text_capped(resolved, MAX_MAP_BYTES, InputError, "a source map")
                        if inside
                        else None
                    )
                except (OSError, RuntimeError, InputError):
                    text = None
            if text is not None:
                try:
                    found = (SourceMap.parse(text), map_file)
                except SourceMapError:
                    found = None
        with self._lock:
            self._maps[path] = found
        return found

    def place(self, d: Declaration) -> SourcePlace | None:
        """Where ``d`` is written in the project, or ``None`` when that cannot be known."""
        if d.place is None or d.kind == "ua":
            return None
        path = self._local_file(d.place.url)
        index = self.index(path) if path is not None else None
        if index is None:
            return None
        if d.kind in ("hint", "attribute"):
            return self._in_markup(d, index)
        if d.place.line is not None and d.place.column is not None:
            offset = self._from_devtools(d, index)
        else:
            offset = self._from_walk(d, index)
        if offset is None:
            return None
        found = self._at(index, offset, d.name)
        if found is None:
            return None
        return self._mapped(found, index, offset, d.name)

    # ---------------------------------------------------------------- traces
    def trace_locations(self, trace: Trace, what: str) -> list[PaintLocation]:
        """The places of one trace: its value's declaration, then the one reading it."""
        if not trace.complete or not trace.hops or not _gives(trace):
            return []
        hops = trace.hops
        custom = next((k for k, h in enumerate(hops) if h.property.startswith("--")), None)
        value_hop = hops[custom] if custom is not None else hops[-1]
        use_hop = hops[custom - 1] if custom else None
        reader = use_hop if use_hop is not None else value_hop
        prop = reader.property if not reader.property.startswith("--") else trace.property
        customs = [h.property for h in hops if h.property.startswith("--")]
        token = customs[-1] if customs else None
        out: list[PaintLocation] = []
        for hop, kind in ((value_hop, what), (use_hop, f"{what}-use")):
            if hop is None:
                continue
            place = self.place(hop)
            if place is None:
                continue
            out.append(
                PaintLocation(
                    place.file,
                    place.line,
                    kind,
                    place.column,
                    prop,
                    customs[0] if customs else None,
                    hop.value,
                    token,
                    place.span,
                )
            )
        return out


def _eight_bit(text: str | None) -> tuple[int, int, int, int] | None:
    """A colour's 8-bit sRGB and alpha, or ``None`` when it is no colour coloraide reads."""
    if not text:
        return None
    try:
        color = Color(text.strip()).convert("srgb").fit("srgb", method="clip")
    except (ValueError, TypeError, AttributeError):
        return None
    r, g, b = (round(max(0.0, min(1.0, float(c))) * 255) for c in color.coords(nans=False))
    return r, g, b, round(float(color.alpha(nans=False)) * 255)


_REFERENCE = re.compile(r"\s*(?:var\(\s*--[^\s,)]+\s*(?:,.*)?\)|currentcolor)\s*", re.I | re.S)


def _gives(trace: Trace) -> bool:
    """Whether the trace's last value is the colour the engine computed, where it must be.

    Only a chain of plain references (each value before the last is
    ``var(--x)`` or ``currentColor``) hands its last value on unchanged;
    there, a last value and a computed colour that both parse must be the
    same 8-bit colour, or the walk named the wrong declaration.  A chain
    through ``color-mix()``, a gradient or a system colour is not checked.
    """
    if not all(_REFERENCE.fullmatch(h.value) for h in trace.hops[:-1]):
        return True
    last = _eight_bit(trace.hops[-1].value)
    computed = _eight_bit(trace.computed)
    if last is None or computed is None:
        return True
    return all(abs(a - b) <= 1 for a, b in zip(last, computed, strict=True))


_EXPORT = (
    r"^[ \t]*export\s+(?:declare\s+)?(?:const|let|var|class|(?:async\s+)?function\s*\*?)\s*"
    r"{name}(?![\w$])"
)


def story_line(file: Path, export: str | None, files: ServedFiles) -> int:
    """The line of a story's export in its file (CSF: ``export const Name``), else 1."""
    if not export:
        return 1
    index = files.index(file)
    if index is None:
        return 1
    name = re.escape(export)
    for pattern in (_EXPORT.format(name=name), rf"^[ \t]*export\s*\{{[^}}]*(?<![\w$]){name}\b"):
        match = re.search(pattern, index.text, re.MULTILINE)
        if match:
            return index.position(match.start())[0]
    return 1


def _page_location(target: Target, files: ServedFiles) -> PaintLocation | None:
    if target.file is None or not target.file.resolve().is_relative_to(files.root):
        return None
    if target.kind == "storybook":
        return PaintLocation(target.file, story_line(target.file, target.export, files), "story")
    return PaintLocation(target.file, 1, "page")


def paint_index(icon: FoundIcon, kinds: Sequence[str], color: str | None = None) -> int | None:
    """The index in ``icon.paints`` of the paint drawn with ``kinds`` (and ``color`` text)."""
    for k, paint in enumerate(icon.paints):
        if tuple(paint.get("kinds", ())) == tuple(kinds) and (
            color is None or paint.get("color") == color
        ):
            return k
    return None


def paint_locations(
    icon: FoundIcon, paint: int | None, target: Target, files: ServedFiles
) -> tuple[PaintLocation, ...]:
    """Where one measured paint's colour and backdrop are written, then its story or page.

    ``paint`` indexes ``icon.paints`` (:func:`paint_index`; ``None`` for an
    ``<img>``'s own drawing: only its backdrop is traced).  Every place is a
    file inside the project root; the story or page comes last, so that
    every paint of a page has at least one place.
    """
    out: list[PaintLocation] = []
    sources = icon.sources
    if sources is not None:
        if paint is not None and 0 <= paint < len(sources.paints):
            traced = sources.paints[paint]
            if traced is not None:
                out += files.trace_locations(traced, "css-colour")
        if sources.backdrop is not None:
            out += files.trace_locations(sources.backdrop, "css-backdrop")
    page = _page_location(target, files)
    if page is not None:
        out.append(page)
    unique = {(p.file, p.line, p.column, p.what): p for p in out}
    return tuple(unique.values())


def finding_locations(
    icon: FoundIcon,
    paint: int | None,
    target: Target,
    files: ServedFiles,
    manifest: Sequence[Location] = (),
) -> tuple[Location, ...]:
    """A finding's :attr:`~alpha_audit.findings.Finding.locations` for one measured paint.

    The manifest's or design token's lines first (``manifest``: where a
    mapped icon's colour and alpha are written), then :func:`paint_locations`.
    """
    found = [*manifest, *(p.location() for p in paint_locations(icon, paint, target, files))]
    return tuple(dict.fromkeys(found))
