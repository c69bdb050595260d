"""JSON with the line of every value, read within size and depth bounds.

The standard ``json`` module returns plain data without positions.  Here the
document's *structure* (objects, arrays, keys) is walked by a small loop and
every string and scalar is decoded by ``json`` itself
(``json.decoder.scanstring`` and ``JSONDecoder.raw_decode``), so the grammar
stays the standard library's while each key path gets its line (and each
token's string value its exact place, quotes included, for fixes that rewrite it).  Duplicate
keys, ``NaN``/``Infinity`` and nesting deeper than :data:`MAX_JSON_DEPTH` are
input errors, because a token file is untrusted.
"""

from __future__ import annotations

import bisect
import json
import json.decoder
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path
from typing import Any

from alpha_audit.errors import InputError
from alpha_audit.load.files import read_capped
from alpha_audit.load.spans import LineIndex
from alpha_audit.load.tokens.model import TokenPlace
from alpha_audit.model import Span

__all__ = [
    "MAX_JSON_BYTES",
    "MAX_JSON_DEPTH",
    "JsonDoc",
    "JsonPath",
    "load_json",
    "parse_json",
    "pointer_parts",
    "walk_pointer",
]

MAX_JSON_BYTES = 8 << 20  # 8 MiB: large design systems export a few MiB of tokens
MAX_JSON_DEPTH = 64  # token groups nest a handful of levels
MAX_JSON_VALUES = 1_000_000

JsonPath = tuple[str | int, ...]

_WHITESPACE = " \t\n\r"
# The members whose string a fix may rewrite: a token's value (DTCG ``$value``,
# Style Dictionary and Tokens Studio ``value``).  Only these get offsets, so a
# large file's descriptions and names cost nothing.
_VALUE_KEYS = frozenset({"$value", "value"})


@dataclass(frozen=True)
class JsonDoc:
    """Plain data from a JSON file plus the line of every key path and the place of every string.

    ``offsets`` holds the ``(start, end)`` in ``text`` of each string that is
    a token's value (the member ``$value`` or ``value``), quotes included;
    :meth:`span` makes the :class:`~alpha_audit.model.Span` on demand.
    """

    path: Path
    data: Any
    lines: dict[JsonPath, int]
    offsets: dict[JsonPath, tuple[int, int]] = field(default_factory=dict, repr=False)
    text: str = field(default="", repr=False, compare=False)
    bom: bool = field(default=False, repr=False, compare=False)  # the file began with one

    def line(self, keys: JsonPath) -> int | None:
        """Line of ``keys`` or of its nearest recorded parent."""
        for n in range(len(keys), -1, -1):
            if keys[:n] in self.lines:
                return self.lines[keys[:n]]
        return None

    def place(self, keys: JsonPath, token: str | None = None) -> TokenPlace:
        """This file, the line of ``keys`` and the token path: an error's ``**place``."""
        return {"path": self.path, "line": self.line(keys), "key": token}

    def error(self, keys: JsonPath, message: str, token: str | None = None) -> InputError:
        """An input error naming this file, the line of ``keys`` and the token path."""
        return InputError(message, **self.place(keys, token))

    def at(self, keys: JsonPath, message: str) -> InputError:
        """An input error at ``keys``, named by them (``sets.base.sources.0``)."""
        return self.error(keys, message, ".".join(map(str, keys)) or None)

    @cached_property
    def _index(self) -> LineIndex:
        return LineIndex(self.text, self.path, "json", bom=self.bom)

    def span(self, keys: JsonPath) -> Span | None:
        """The exact span of the string value at ``keys`` (``None``: not a string)."""
        where = self.offsets.get(keys)
        return None if where is None else self._index.span(*where)


def pointer_parts(pointer: str) -> tuple[str, ...]:
    """A JSON Pointer's (RFC 6901) unescaped steps: ``/a~1b/c`` -> ``("a/b", "c")``."""
    return tuple(p.replace("~1", "/").replace("~0", "~") for p in pointer.split("/")[1:])


def walk_pointer(node: Any, parts: tuple[str, ...]) -> Any:
    """The value ``parts`` lead to from ``node`` (an object's member, an array's index);
    a step that leads nowhere raises :class:`KeyError` naming it."""
    for part in parts:
        if isinstance(node, dict) and part in node:
            node = node[part]
        elif isinstance(node, list) and part.isdigit() and int(part) < len(node):
            node = node[int(part)]
        else:
            raise KeyError(part)
    return node


def _no_constant(name: str) -> Any:
    raise ValueError(f"{name} is not JSON")


class _Parser:
    def __init__(self, text: str, path: Path) -> None:
        self.text = text
        self.path = path
        self.newlines = [i for i, ch in enumerate(text) if ch == "\n"]
        self.lines: dict[JsonPath, int] = {}
        self.offsets: dict[JsonPath, tuple[int, int]] = {}
        self.count = 0
        self.decoder = json.JSONDecoder(parse_constant=_no_constant)

    def line_of(self, pos: int) -> int:
        return bisect.bisect_left(self.newlines, pos) + 1

    def fail(self, pos: int, message: str) -> InputError:
        return InputError(f"invalid JSON: {message}", path=self.path, line=self.line_of(pos))

    def skip(self, pos: int) -> int:
        text = self.text
        while pos < len(text) and text[pos] in _WHITESPACE:
            pos += 1
        return pos

    def expect(self, pos: int, char: str) -> int:
        pos = self.skip(pos)
        if pos >= len(self.text) or self.text[pos] != char:
            found = "end of file" if pos >= len(self.text) else repr(self.text[pos])
            raise self.fail(pos, f"expected {char!r}, found {found}")
        return pos + 1

    def value(self, pos: int, keys: JsonPath) -> tuple[Any, int]:
        pos = self.skip(pos)
        self.count += 1
        if self.count > MAX_JSON_VALUES:
            raise self.fail(pos, f"more than {MAX_JSON_VALUES} values; not a token file")
        if len(keys) > MAX_JSON_DEPTH:
            raise self.fail(pos, f"nested deeper than {MAX_JSON_DEPTH} levels")
        self.lines.setdefault(keys, self.line_of(pos))
        if pos >= len(self.text):
            raise self.fail(pos, "unexpected end of file")
        char = self.text[pos]
        if char == "{":
            return self.obj(pos + 1, keys)
        if char == "[":
            return self.array(pos + 1, keys)
        try:
            value, end = self.decoder.raw_decode(self.text, pos)
        except json.JSONDecodeError as exc:
            raise self.fail(exc.pos, exc.msg) from exc
        except ValueError as exc:  # NaN, Infinity, or an integer with too many digits
            raise self.fail(pos, str(exc)) from exc
        if isinstance(value, str) and keys and keys[-1] in _VALUE_KEYS:
            self.offsets[keys] = (pos, end)
        return value, end

    def obj(self, pos: int, keys: JsonPath) -> tuple[dict[str, Any], int]:
        out: dict[str, Any] = {}
        pos = self.skip(pos)
        if pos < len(self.text) and self.text[pos] == "}":
            return out, pos + 1
        while True:
            pos = self.skip(pos)
            if pos >= len(self.text) or self.text[pos] != '"':
                raise self.fail(pos, "expected a quoted key")
            key_pos = pos
            try:
                key, pos = json.decoder.scanstring(self.text, pos + 1)  # type: ignore[attr-defined]  # CPython defines json.decoder.scanstring; typeshed omits it
            except json.JSONDecodeError as exc:
                raise self.fail(exc.pos, exc.msg) from exc
            if key in out:
                raise InputError(
                    f"duplicate key {key!r}; JSON names must be unique",
                    path=self.path,
                    line=self.line_of(key_pos),
                    key=".".join(str(k) for k in (*keys, key)),
                )
            child = (*keys, key)  # one tuple for lines and offsets alike
            self.lines[child] = self.line_of(key_pos)
            pos = self.expect(pos, ":")
            out[key], pos = self.value(pos, child)
            pos = self.skip(pos)
            if pos < len(self.text) and self.text[pos] == ",":
                pos += 1
                continue
            return out, self.expect(pos, "}")

    def array(self, pos: int, keys: JsonPath) -> tuple[list[Any], int]:
        out: list[Any] = []
        pos = self.skip(pos)
        if pos < len(self.text) and self.text[pos] == "]":
            return out, pos + 1
        while True:
            item, pos = self.value(pos, (*keys, len(out)))
            out.append(item)
            pos = self.skip(pos)
            if pos < len(self.text) and self.text[pos] == ",":
                pos += 1
                continue
            return out, self.expect(pos, "]")


def parse_json(text: str, path: str | Path = "<string>") -> JsonDoc:
    """Parse JSON text, recording the line of every key path.

    >>> doc = parse_json('{\\n  "a": {\\n    "b": [1, 2]\\n  }\\n}')
    >>> doc.data, doc.lines[("a", "b")]
    ({'a': {'b': [1, 2]}}, 3)
    """
    p = Path(path)
    bom = text.startswith("\ufeff")  # dropped; line 1's columns still count it
    text = text.removeprefix("\ufeff")
    parser = _Parser(text, p)
    data, end = parser.value(0, ())
    end = parser.skip(end)
    if end != len(text):
        raise parser.fail(end, "extra data after the document")
    return JsonDoc(p, data, parser.lines, parser.offsets, text, bom)


def load_json(path: str | Path, *, limit: int = MAX_JSON_BYTES) -> JsonDoc:
    """Read (capped) and parse a UTF-8 JSON file."""
    p = Path(path)
    raw = read_capped(p, limit, InputError, "a token file")
    try:
        text = raw.decode("utf-8")  # a BOM: parse_json
    except UnicodeDecodeError as exc:
        raise InputError(f"not UTF-8 text (byte {exc.start})", path=p) from exc
    return parse_json(text, p)
