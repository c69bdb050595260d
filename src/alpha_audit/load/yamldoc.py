"""Safe, bounded YAML loading that remembers where every value came from.

PyYAML's safe loader alone lets duplicate keys win silently, expands alias
bombs, reads ``1e3`` as a string and loses line numbers.  Here the document is
composed into nodes (never constructed with arbitrary tags), walked with a node
budget, and converted to plain Python while recording each key path's line
and, for single-line scalars, the exact span a fix may rewrite.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import yaml
from yaml.constructor import SafeConstructor

from alpha_audit.errors import InputError
from alpha_audit.load.files import read_text_capped
from alpha_audit.load.spans import LineIndex
from alpha_audit.model import Span

__all__ = ["MAX_YAML_BYTES", "MAX_YAML_NODES", "KeyPath", "YamlDoc", "load_yaml", "parse_yaml"]

MAX_YAML_BYTES = 1 << 20  # 1 MiB: a theme or manifest is a few KiB
MAX_YAML_NODES = 100_000  # after alias expansion; bounds "billion laughs"

KeyPath = tuple[str | int, ...]

_PLAIN_TAGS = frozenset(
    f"tag:yaml.org,2002:{t}"
    for t in ("str", "int", "float", "bool", "null", "seq", "map", "timestamp", "merge")
)

# YAML 1.2 core-schema floats that YAML 1.1 (PyYAML) leaves as strings: 1e3, -1e308.
_UNQUOTED_HEX = re.compile(r":[ \t]+#[0-9a-fA-F]{3,8}\b")
_YAML12_FLOAT = re.compile(r"[-+]?(\.[0-9]+|[0-9]+(\.[0-9]*)?)([eE][-+]?[0-9]+)?")


def format_key(keys: KeyPath) -> str:
    """``("canvases", 2, "color")`` -> ``canvases[2].color``."""
    out = ""
    for k in keys:
        out += f"[{k}]" if isinstance(k, int) else (f".{k}" if out else str(k))
    return out


@dataclass(frozen=True)
class YamlDoc:
    """Plain data from a YAML file plus the line of every key path.

    ``spans`` holds the exact span of each scalar value written on one line
    as a plain or quoted scalar with no anchor or tag (what a fix can
    replace without touching anything else).
    """

    path: Path
    data: Any
    lines: dict[KeyPath, int]
    spans: dict[KeyPath, Span] = field(default_factory=dict)

    def line(self, keys: KeyPath) -> int | None:
        """Line of ``keys`` or of its nearest recorded parent."""
        for n in range(len(keys), -1, -1):
            if keys[:n] in self.lines:
                return self.lines[keys[:n]]
        return None

    def error(self, keys: KeyPath, message: str) -> InputError:
        """An :class:`InputError` located at ``keys`` in this file."""
        return InputError(message, path=self.path, line=self.line(keys), key=format_key(keys))


# Characters a span may not start with: an anchor, a tag or an alias would be
# inside it, and replacing the span would drop them.
_NOT_A_VALUE = ("&", "!", "*")


class _Converter:
    def __init__(self, path: Path, text: str, *, bom: bool) -> None:
        self.path = path
        self.index = LineIndex(text, path, "yaml", bom=bom)
        self.lines: dict[KeyPath, int] = {}
        self.spans: dict[KeyPath, Span] = {}
        self.budget = MAX_YAML_NODES
        self.constructor = SafeConstructor()
        self.active: set[int] = set()

    def fail(self, node: yaml.Node, message: str, keys: KeyPath | None = None) -> InputError:
        key = format_key(keys) if keys else None
        return InputError(message, path=self.path, line=node.start_mark.line + 1, key=key)

    def convert(self, node: yaml.Node, keys: KeyPath) -> Any:
        self.budget -= 1
        if self.budget < 0:
            raise self.fail(node, f"expands to more than {MAX_YAML_NODES} values (alias bomb?)")
        self.lines.setdefault(keys, node.start_mark.line + 1)
        if node.tag not in _PLAIN_TAGS:
            # Explicit tags (!!python/object, !custom) would construct objects; refuse them.
            raise self.fail(node, f"YAML tag {node.tag!r} is not allowed; write plain values")
        if id(node) in self.active:
            raise self.fail(node, "an alias refers to itself; recursive YAML is not allowed")
        if isinstance(node, yaml.ScalarNode):
            self.record_span(node, keys)
            return self.scalar(node, keys)
        self.active.add(id(node))
        try:
            if isinstance(node, yaml.SequenceNode):
                return [self.convert(item, (*keys, i)) for i, item in enumerate(node.value)]
            if isinstance(node, yaml.MappingNode):
                return self.mapping(node, keys)
        finally:
            self.active.discard(id(node))
        raise self.fail(node, f"unsupported YAML node {node.tag}")  # pragma: no cover

    def record_span(self, node: yaml.ScalarNode, keys: KeyPath) -> None:
        """Keep the scalar's span when replacing it is exact (see :class:`YamlDoc`)."""
        if node.style not in (None, "'", '"') or keys in self.spans:
            return
        start, end = node.start_mark.index, node.end_mark.index
        text = self.index.text[start:end]
        if not text or "\n" in text or "\r" in text or text.startswith(_NOT_A_VALUE):
            return
        quoted = node.style is not None
        if quoted and not (len(text) >= 2 and text[0] == text[-1] == node.style):
            return
        if not quoted and text != node.value:
            return
        self.spans[keys] = self.index.span(start, end)

    def mapping(self, node: yaml.MappingNode, keys: KeyPath) -> dict[str, Any]:
        out: dict[str, Any] = {}
        for key_node, value_node in node.value:
            if key_node.tag == "tag:yaml.org,2002:merge":
                raise self.fail(key_node, "merge keys (<<) are not supported; write keys out")
            if not isinstance(key_node, yaml.ScalarNode):
                raise self.fail(key_node, "mapping keys must be plain strings")
            key = str(self.scalar(key_node))
            if key in out:
                first = self.lines.get((*keys, key))
                raise InputError(
                    f"duplicate key {key!r} (first set on line {first}); each key may appear once",
                    path=self.path,
                    line=key_node.start_mark.line + 1,
                    key=format_key((*keys, key)),
                )
            self.lines[(*keys, key)] = key_node.start_mark.line + 1
            out[key] = self.convert(value_node, (*keys, key))
        return out

    def scalar(self, node: yaml.ScalarNode, keys: KeyPath = ()) -> Any:
        if (
            node.tag == "tag:yaml.org,2002:str"
            and node.style is None
            and _YAML12_FLOAT.fullmatch(node.value)
            and any(ch in node.value for ch in "eE.")
        ):
            return float(node.value)
        try:
            return self.constructor.construct_object(node, deep=True)
        except (
            yaml.YAMLError,
            ValueError,
            OverflowError,
            # Explicit tags on bad scalars: !!float "" (IndexError), !!bool ""
            # (KeyError), !!timestamp "x" (AttributeError) crash PyYAML itself.
            IndexError,
            KeyError,
            AttributeError,
            TypeError,
        ) as exc:
            tag = node.tag.rsplit(":", 1)[-1]
            raise self.fail(
                node,
                f"cannot read value {node.value[:40]!r} as {tag}; write a plain value "
                f"without the !!{tag} tag",
                keys,
            ) from exc


def parse_yaml(text: str, path: Path) -> YamlDoc:
    """Parse YAML text safely; errors name ``path`` and the line.

    A leading byte-order mark is dropped (and still counted in line 1's columns).
    """
    bom = text.startswith("\ufeff")
    text = text.removeprefix("\ufeff")
    try:
        root = yaml.compose(text, Loader=yaml.SafeLoader)
    except yaml.MarkedYAMLError as exc:
        mark = exc.problem_mark or exc.context_mark
        line = mark.line + 1 if mark else None
        problem = exc.problem or exc.context or "invalid YAML"
        if _UNQUOTED_HEX.search(text):
            problem += '; an unquoted #hex starts a YAML comment: quote colours, e.g. "#0d1117"'
        raise InputError(f"invalid YAML: {problem}", path=path, line=line) from exc
    except yaml.YAMLError as exc:
        raise InputError(f"invalid YAML: {exc}", path=path) from exc
    except RecursionError as exc:
        raise InputError("YAML is nested too deeply", path=path) from exc
    if root is None:
        return YamlDoc(path, None, {})
    converter = _Converter(path, text, bom=bom)
    try:
        data = converter.convert(root, ())
    except RecursionError as exc:
        raise InputError("YAML is nested too deeply", path=path) from exc
    return YamlDoc(path, data, converter.lines, converter.spans)


def load_yaml(path: str | Path) -> YamlDoc:
    """Read and parse a YAML file of at most :data:`MAX_YAML_BYTES`."""
    p = Path(path)
    kind = "a YAML theme, manifest or config"
    text = read_text_capped(p, MAX_YAML_BYTES, InputError, kind)  # a BOM: parse_yaml
    return parse_yaml(text, p)
