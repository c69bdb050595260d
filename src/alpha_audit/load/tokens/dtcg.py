"""DTCG Format 2025.10 token trees: merge, flatten, ``$extends``, aliases and ``$ref``.

A document is a tree of groups; an object with ``$value`` is a token.  Groups
may carry ``$type`` (inherited by every token below that sets none),
``$extends`` (``"{other.group}"``: the group also holds every token of the
other group it does not define itself) and a ``$root`` token.  A ``$value``
that is exactly ``"{a.b}"`` is an alias; ``{"$ref": "#/a/b/$value"}`` is a
JSON Pointer (RFC 6901) into the same document.  Chains are followed,
cycles are errors naming the chain, and a token whose type cannot be
resolved is an error (the format forbids guessing).

Several documents merge in order, the last occurrence of a token winning:
that is the Resolver Module's rule and Tokens Studio's set order.

``legacy=True`` reads Style Dictionary and Tokens Studio files, whose tokens
say ``value``/``type`` without ``$``.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from typing import Any

from alpha_audit.errors import InputError
from alpha_audit.load.names import check_name
from alpha_audit.load.tokens.jsondoc import (
    MAX_JSON_DEPTH,
    JsonDoc,
    JsonPath,
    pointer_parts,
    walk_pointer,
)
from alpha_audit.load.tokens.model import (
    MAX_ALIAS_CHAIN,
    MAX_TOKENS,
    Steps,
    Token,
    TokenPlace,
    Unresolved,
    follow,
    too_long,
)

__all__ = ["ALIAS", "MAX_VALUE_NODES", "TokenTree"]

# JSON values in one resolved token value (pointers expanded): a colour object
# is six, a composite typography or shadow token a few dozen.
MAX_VALUE_NODES = 10_000

ALIAS = re.compile(r"\{([^{}]+)\}")
_GROUP_KEYS = frozenset(
    {"$type", "$description", "$extensions", "$deprecated", "$extends", "$schema", "$metadata"}
)


@dataclass
class _Raw:
    """One token as written, before resolution."""

    path: str
    node: dict[str, Any]
    doc: JsonDoc
    keys: JsonPath
    group_type: str | None

    @property
    def line(self) -> int | None:
        return self.doc.line(self.keys)


@dataclass
class _Group:
    path: str
    extends: str
    doc: JsonDoc
    keys: JsonPath
    type: str | None

    def place(self) -> TokenPlace:
        """Where this group's ``$extends`` is."""
        return self.doc.place((*self.keys, "$extends"), self.path)

    def error(self, message: str) -> InputError:
        """An input error at this group's ``$extends``."""
        return InputError(message, **self.place())


@dataclass
class TokenTree:
    """Token documents merged in order (last wins), resolved on demand.

    ``steps`` counts the work (keys walked, ``$extends`` copies, alias and
    pointer lookups, values measured) against :data:`~.model.MAX_EXPANSION`;
    the trees of one source's modes share it.
    """

    legacy: bool = False
    raw: dict[str, _Raw] = field(default_factory=dict)
    groups: dict[str, _Group] = field(default_factory=dict)
    docs: list[JsonDoc] = field(default_factory=list)
    steps: Steps = field(default_factory=Steps)

    def count(self, n: int, doc: JsonDoc, keys: JsonPath, path: str | None) -> None:
        """Count ``n`` steps; past :data:`~.model.MAX_EXPANSION` an error naming the file."""

        def place() -> TokenPlace:
            return {"path": doc.path, "line": doc.line(keys), "key": path}

        self.steps.take(n, "resolving ($ref, aliases, $extends, groups)", place)

    # ---------------------------------------------------------------- reading
    def add(self, doc: JsonDoc, data: Any = None, keys: JsonPath = ()) -> None:
        """Add the tokens of ``doc`` (or of its sub-tree ``data`` at ``keys``)."""
        self.docs.append(doc)
        root = doc.data if data is None else data
        if not isinstance(root, dict):
            raise InputError("expected a JSON object of token groups", path=doc.path, line=1)
        self._walk(doc, root, keys, [], None)

    def _is_token(self, node: dict[str, Any]) -> bool:
        return "$value" in node or (self.legacy and "value" in node)

    def _walk(
        self,
        doc: JsonDoc,
        node: dict[str, Any],
        keys: JsonPath,
        names: list[str],
        group_type: str | None,
    ) -> None:
        here = ".".join(names)
        # Every key is walked: a source added again and again (a Resolver's sets
        # in each of its modes, a pointer named by many sources) costs each time.
        self.count(len(node) or 1, doc, keys, here or None)
        gtype = node.get("$type", group_type)
        if "$type" in node and not isinstance(node["$type"], str):
            raise doc.error(
                (*keys, "$type"), f"$type must be a string, got {node['$type']!r}", here or None
            )
        if "$extends" in node:
            target = node["$extends"]
            match = ALIAS.fullmatch(target) if isinstance(target, str) else None
            if match is None:
                raise doc.error(
                    (*keys, "$extends"),
                    f'$extends must be a group reference "{{group.name}}", got {target!r}',
                    here or None,
                )
            self.groups[here] = _Group(here, match.group(1), doc, keys, node.get("$type"))
        for name, child in node.items():
            if name in _GROUP_KEYS or (name.startswith("$") and name != "$root"):
                continue
            child_keys = (*keys, name)
            path = ".".join([*names, name])
            if "." in name or "{" in name or "}" in name or not name:
                raise doc.error(
                    child_keys, f"name {name!r} may not be empty or contain '.', '{{' or '}}'", path
                )
            check_name(name, path=doc.path, line=doc.line(child_keys), key=path, what="token name")
            if not isinstance(child, dict):
                # Metadata beside the groups ("version": "1.2", "author": ...):
                # not a token and not a group, so nothing to read.
                continue
            if self._is_token(child):
                if len(self.raw) >= MAX_TOKENS and path not in self.raw:
                    raise doc.error(child_keys, f"more than {MAX_TOKENS} tokens; not allowed", path)
                self.raw[path] = _Raw(path, child, doc, child_keys, gtype)
            else:
                self._walk(doc, child, child_keys, [*names, name], gtype)

    # ------------------------------------------------------------- $extends
    def _apply_extends(self) -> None:
        """Copy each extended group's tokens into the extending group (local ones win).

        Tokens and groups are indexed by every group prefix once, so the
        work is the tokens copied (at most :data:`MAX_TOKENS`), not groups x
        tokens; each copy is a counted step.
        """
        if not self.groups:
            return
        under: dict[str, list[str]] = {}  # group path -> token paths below it
        for path in self.raw:
            self._index(under, path)
        subgroups: dict[str, list[_Group]] = {}
        for g in self.groups.values():
            parts = g.path.split(".") if g.path else []
            for i in range(len(parts) + 1):
                subgroups.setdefault(".".join(parts[:i]), []).append(g)
        done: set[str] = set()

        def visit(group: _Group, stack: list[str]) -> None:
            if group.path in done:
                return
            follow(stack, group.path, "$extends", group.place)
            prefix = group.extends + "."
            # The target and its subgroups get their own inherited tokens first.
            for other in subgroups.get(group.extends, []):
                visit(other, [*stack, group.path])
            inherited = [self.raw[p] for p in under.get(group.extends, [])]
            if not inherited:
                raise group.error(f"$extends names {group.extends!r}, which is no group of tokens")
            self.count(len(inherited), group.doc, group.keys, group.path)
            for r in inherited:
                path = (group.path + "." if group.path else "") + r.path[len(prefix) :]
                if path not in self.raw:
                    if len(self.raw) >= MAX_TOKENS:
                        raise group.error(
                            f"$extends makes more than {MAX_TOKENS} tokens; not allowed"
                        )
                    self.raw[path] = _Raw(path, r.node, r.doc, r.keys, r.group_type or group.type)
                    self._index(under, path)
            done.add(group.path)

        for group in list(self.groups.values()):
            visit(group, [])

    @staticmethod
    def _index(under: dict[str, list[str]], path: str) -> None:
        parts = path.split(".")
        for i in range(1, len(parts)):
            under.setdefault(".".join(parts[:i]), []).append(path)

    # ------------------------------------------------------------ resolution
    def resolve(self) -> dict[str, Token]:
        """Every token with aliases and ``$ref`` followed and its type resolved."""
        self._apply_extends()
        self._cache: dict[str, Token] = {}
        self._sizes: dict[str, int] = {}  # JSON values in each resolved token's value
        self._pointers: dict[tuple[int, str], tuple[Any, int]] = {}
        return {path: self._token(path, []) for path in self.raw}

    def _field(self, node: dict[str, Any], name: str) -> Any:
        if f"${name}" in node:
            return node[f"${name}"]
        return node.get(name) if self.legacy else None

    def _token(self, path: str, stack: list[str]) -> Token:
        if path in self._cache:
            return self._cache[path]
        raw = self.raw[path]
        follow(stack, path, "alias", lambda: raw.doc.place(raw.keys, stack[0]))
        stack = [*stack, path]
        self.count(1, raw.doc, raw.keys, path)
        value_key = "$value" if "$value" in raw.node else "value"
        try:
            value, target, size = self._value(
                raw, raw.node[value_key], (*raw.keys, value_key), stack
            )
        except Unresolved as exc:
            token = self._broken(raw, path, exc.problem, exc.line)
            self._cache[path], self._sizes[path] = token, 1
            return token
        if size > MAX_VALUE_NODES:
            raise raw.doc.error(
                raw.keys,
                f"its value expands to more than {MAX_VALUE_NODES:,} JSON values ($ref)",
                path,
            )
        if target is not None and len(target.chain) >= MAX_ALIAS_CHAIN:
            chain = (path, target.path, *target.chain)
            raise too_long("alias", chain, raw.doc.place(raw.keys, path))
        declared = self._field(raw.node, "type")
        if declared is not None and not isinstance(declared, str):
            raise raw.doc.error(raw.keys, f"$type must be a string, got {declared!r}", path)
        ttype = declared or raw.group_type or (target.type if target else None)
        problem = target.problem if target is not None else None
        if ttype is None and problem is None:
            problem = (
                "token has no $type (on itself or a parent group) and is no alias of a typed "
                'token; add "$type": "color" (DTCG 2025.10: tools must not guess types)'
            )
        extensions = self._field(raw.node, "extensions")
        description = self._field(raw.node, "description")
        token = Token(
            path=path,
            type=ttype or "unknown",
            value=value,
            file=target.file if target else raw.doc.path,
            line=target.line if target else raw.line,
            extensions=extensions if isinstance(extensions, dict) else {},
            description=description if isinstance(description, str) else None,
            deprecated=self._field(raw.node, "deprecated") or False,
            chain=(target.path, *target.chain) if target else (),
            alias_file=raw.doc.path if target else None,
            alias_line=raw.line if target else None,
            # A literal string value is rewritten in place; an object, a list or
            # a $ref into a value has no single span (JsonDoc records strings only).
            span=target.span if target else raw.doc.span((*raw.keys, value_key)),
            problem=problem,
        )
        self._cache[path], self._sizes[path] = token, size
        return token

    def _broken(self, raw: _Raw, path: str, problem: str, line: int | None) -> Token:
        """A token that cannot be resolved: it loads, and is an error only where selected."""
        declared = self._field(raw.node, "type")
        return Token(
            path=path,
            type=declared if isinstance(declared, str) else raw.group_type or "unknown",
            value=None,
            file=raw.doc.path,
            line=line or raw.line,
            problem=problem,
        )

    def _value(
        self, raw: _Raw, value: Any, keys: JsonPath, stack: list[str]
    ) -> tuple[Any, Token | None, int]:
        """Resolved ``value``, the token it names when it is a whole reference, and its size.

        The size counts JSON values with shared sub-values counted each time
        they occur, so a value that doubles through pointers is caught by
        :data:`MAX_VALUE_NODES` before anything walks it.
        """
        if isinstance(value, str) and (match := ALIAS.fullmatch(value.strip())):
            name = self._alias_target(match.group(1))
            if name is None:
                raise Unresolved(
                    f"alias {value} names no token in this file (a library or another "
                    "file's token?)",
                    raw.doc.line(keys),
                )
            target = self._token(name, stack)
            return target.value, target, self._sizes[name]
        if isinstance(value, dict) and "$ref" in value:
            return self._pointer(raw, value["$ref"], keys, stack)
        if isinstance(value, dict):
            out: dict[str, Any] = {}
            size = 1
            for k, v in value.items():
                out[k], _, n = self._value(raw, v, (*keys, k), stack)
                size += n
            return out, None, size
        if isinstance(value, list):
            items = []
            size = 1
            for i, v in enumerate(value):
                item, _, n = self._value(raw, v, (*keys, i), stack)
                items.append(item)
                size += n
            return items, None, size
        return value, None, 1

    def _alias_target(self, name: str) -> str | None:
        """The token an alias names; Style Dictionary's ``{a.b.value}`` names ``a.b``."""
        if name in self.raw:
            return name
        if self.legacy and name.endswith(".value") and name[: -len(".value")] in self.raw:
            return name[: -len(".value")]
        return None

    def _pointer(
        self, raw: _Raw, pointer: Any, keys: JsonPath, stack: list[str]
    ) -> tuple[Any, Token | None, int]:
        """Follow a JSON Pointer ``#/a/b`` in the token's own document (memoised, counted)."""
        where = raw.doc.place(keys, raw.path)
        if not isinstance(pointer, str) or not pointer.startswith("#"):
            raise InputError(
                f"$ref {pointer!r} must be a JSON Pointer into this file, like "
                '"#/color/blue/$value"',
                **where,
            )
        follow(stack, pointer, "$ref", lambda: where)
        if pointer.count("/") > MAX_JSON_DEPTH + 1:  # + "/$value" after the deepest key
            raise InputError(
                f"$ref {pointer[:40]}... has more parts than the file nests "
                f"({MAX_JSON_DEPTH} levels); it points at nothing",
                **where,
            )
        self.count(1, raw.doc, keys, raw.path)
        parts = pointer_parts(pointer[1:])
        # A pointer at a token (in any merged source: the last one wins, as for
        # aliases) is an alias; a pointer into its value walks the resolved value.
        for i in range(len(parts), 0, -1):
            token_path = ".".join(parts[:i])
            if token_path not in self.raw:
                continue
            rest = parts[i:]
            target = self._token(token_path, stack)
            if not rest or rest == ("$value",) or (self.legacy and rest == ("value",)):
                return target.value, target, self._sizes[token_path]
            if rest[0] not in ("$value", "value"):
                raise InputError(
                    f"$ref {pointer} points into token {token_path} but not at its $value",
                    **where,
                )
            # Measuring the part pointed at walks at most the whole value: counted first.
            self.count(self._sizes[token_path], raw.doc, keys, raw.path)
            node = _descend(target.value, rest[1:], pointer, where)
            return node, None, _size(node)
        memo = (id(raw.doc), pointer)
        if memo in self._pointers:
            value, size = self._pointers[memo]
            return value, None, size
        node = _descend(raw.doc.data, parts, pointer, where)
        value, _, size = self._value(raw, node, keys, [*stack, pointer])
        if size > MAX_VALUE_NODES:
            raise InputError(
                f"$ref {pointer} expands to more than {MAX_VALUE_NODES:,} JSON values", **where
            )
        self._pointers[memo] = (value, size)
        return value, None, size


def _descend(node: Any, parts: tuple[str, ...], pointer: str, where: TokenPlace) -> Any:
    """The JSON value ``parts`` (a pointer's unescaped steps) lead to from ``node``."""
    try:
        return walk_pointer(node, parts)
    except KeyError as exc:
        raise InputError(
            f"$ref {pointer} points at nothing (no {exc.args[0]!r})", **where
        ) from None


def _size(value: Any) -> int:
    """JSON values in ``value`` (an already resolved value: small, bounded when it was made)."""
    if isinstance(value, dict):
        return 1 + sum(_size(v) for v in value.values())
    if isinstance(value, list):
        return 1 + sum(_size(v) for v in value)
    return 1


def tokens_from_docs(docs: list[JsonDoc], *, legacy: bool = False) -> dict[str, Token]:
    """Merge ``docs`` in order (last wins) and resolve every token."""
    tree = TokenTree(legacy=legacy)
    for doc in docs:
        tree.add(doc)
    return tree.resolve()
