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
from pathlib import Path
from typing import Any

from alpha_audit.errors import InputError
from alpha_audit.load.tokens.jsondoc import JsonDoc, JsonPath
from alpha_audit.load.tokens.model import (
    MAX_ALIAS_CHAIN,
    MAX_TOKENS,
    Token,
    TokenPlace,
    token_error,
)

__all__ = ["ALIAS", "TokenTree"]

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


@dataclass
class TokenTree:
    """Token documents merged in order (last wins), resolved on demand."""

    legacy: bool = False
    raw: dict[str, _Raw] = field(default_factory=dict)
    groups: dict[str, _Group] = field(default_factory=dict)
    docs: list[JsonDoc] = field(default_factory=list)

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
        gtype = node.get("$type", group_type)
        if "$type" in node and not isinstance(node["$type"], str):
            raise token_error(
                f"$type must be a string, got {node['$type']!r}",
                file=doc.path,
                line=doc.line((*keys, "$type")),
                path=here or None,
            )
        if "$extends" in node:
            target = node["$extends"]
            match = ALIAS.fullmatch(target) if isinstance(target, str) else None
            if match is None:
                raise token_error(
                    f'$extends must be a group reference "{{group.name}}", got {target!r}',
                    file=doc.path,
                    line=doc.line((*keys, "$extends")),
                    path=here or None,
                )
            self.groups[here] = _Group(here, match.group(1), doc, keys, node.get("$type"))
        for name, child in node.items():
            if name in _GROUP_KEYS or (name.startswith("$") and name != "$root"):
                continue
            child_keys = (*keys, name)
            path = ".".join([*names, name])
            if "." in name or "{" in name or "}" in name or not name:
                raise token_error(
                    f"name {name!r} may not be empty or contain '.', '{{' or '}}'",
                    file=doc.path,
                    line=doc.line(child_keys),
                    path=path,
                )
            if not isinstance(child, dict):
                if self.legacy and name in ("type", "description", "extensions"):
                    continue
                raise token_error(
                    f"expected a token or a group (a JSON object), got {child!r:.40}",
                    file=doc.path,
                    line=doc.line(child_keys),
                    path=path,
                )
            if self._is_token(child):
                if len(self.raw) >= MAX_TOKENS and path not in self.raw:
                    raise token_error(
                        f"more than {MAX_TOKENS} tokens; not allowed",
                        file=doc.path,
                        line=doc.line(child_keys),
                        path=path,
                    )
                self.raw[path] = _Raw(path, child, doc, child_keys, gtype)
            else:
                self._walk(doc, child, child_keys, [*names, name], gtype)

    # ------------------------------------------------------------- $extends
    def _apply_extends(self) -> None:
        done: set[str] = set()

        def visit(group: _Group, stack: list[str]) -> None:
            if group.path in done:
                return
            if group.path in stack:
                chain = " -> ".join([*stack[stack.index(group.path) :], group.path])
                raise token_error(
                    f"$extends cycle: {chain}",
                    file=group.doc.path,
                    line=group.doc.line((*group.keys, "$extends")),
                    path=group.path,
                )
            prefix = group.extends + "."
            # The target and its subgroups get their own inherited tokens first.
            for other in list(self.groups.values()):
                if other.path == group.extends or other.path.startswith(prefix):
                    visit(other, [*stack, group.path])
            inherited = [r for p, r in self.raw.items() if p.startswith(prefix)]
            if not inherited:
                raise token_error(
                    f"$extends names {group.extends!r}, which is no group of tokens",
                    file=group.doc.path,
                    line=group.doc.line((*group.keys, "$extends")),
                    path=group.path,
                )
            for r in inherited:
                path = (group.path + "." if group.path else "") + r.path[len(prefix) :]
                if path not in self.raw:
                    if len(self.raw) >= MAX_TOKENS:
                        raise token_error(
                            f"$extends makes more than {MAX_TOKENS} tokens; not allowed",
                            file=group.doc.path,
                            line=group.doc.line((*group.keys, "$extends")),
                            path=group.path,
                        )
                    self.raw[path] = _Raw(path, r.node, r.doc, r.keys, r.group_type or group.type)
            done.add(group.path)

        for group in list(self.groups.values()):
            visit(group, [])

    # ------------------------------------------------------------ resolution
    def resolve(self) -> dict[str, Token]:
        """Every token with aliases and ``$ref`` followed and its type resolved."""
        self._apply_extends()
        self._cache: dict[str, Token] = {}
        return {path: self._token(path, []) for path in self.raw}

    def _field(self, node: dict[str, Any], name: str) -> Any:
        if f"${name}" in node:
            return node[f"${name}"]
        return node.get(name) if self.legacy else None

    def _token(self, path: str, stack: list[str]) -> Token:
        if path in self._cache:
            return self._cache[path]
        raw = self.raw[path]
        if path in stack:
            chain = " -> ".join([*stack[stack.index(path) :], path])
            raise token_error(
                f"alias cycle: {chain}", file=raw.doc.path, line=raw.line, path=stack[0]
            )
        if len(stack) >= MAX_ALIAS_CHAIN:
            raise token_error(
                f"alias chain longer than {MAX_ALIAS_CHAIN}: {' -> '.join(stack[:4])} -> ...",
                file=raw.doc.path,
                line=raw.line,
                path=stack[0],
            )
        stack = [*stack, path]
        value_key = "$value" if "$value" in raw.node else "value"
        value, target = self._value(raw, raw.node[value_key], (*raw.keys, value_key), stack)
        if target is not None and len(target.chain) >= MAX_ALIAS_CHAIN:
            raise token_error(
                f"alias chain longer than {MAX_ALIAS_CHAIN}: {path} -> {target.path} -> ...",
                file=raw.doc.path,
                line=raw.line,
                path=path,
            )
        declared = self._field(raw.node, "type")
        if declared is not None and not isinstance(declared, str):
            raise token_error(
                f"$type must be a string, got {declared!r}",
                file=raw.doc.path,
                line=raw.line,
                path=path,
            )
        ttype = declared or raw.group_type or (target.type if target else None)
        if ttype is None:
            raise token_error(
                "token has no $type (on itself or a parent group) and is no alias of a typed "
                'token; add "$type": "color" (DTCG 2025.10: tools must not guess types)',
                file=raw.doc.path,
                line=raw.line,
                path=path,
            )
        extensions = self._field(raw.node, "extensions")
        description = self._field(raw.node, "description")
        token = Token(
            path=path,
            type=ttype,
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
        )
        self._cache[path] = token
        return token

    def _value(
        self, raw: _Raw, value: Any, keys: JsonPath, stack: list[str]
    ) -> tuple[Any, Token | None]:
        """Resolved ``value`` and, when the whole value is a reference, the token it names."""
        if isinstance(value, str) and (match := ALIAS.fullmatch(value.strip())):
            name = match.group(1)
            if name not in self.raw:
                raise token_error(
                    f"alias {value} names no token",
                    file=raw.doc.path,
                    line=raw.doc.line(keys),
                    path=raw.path,
                )
            target = self._token(name, stack)
            return target.value, target
        if isinstance(value, dict) and "$ref" in value:
            return self._pointer(raw, value["$ref"], keys, stack)
        if isinstance(value, dict):
            return {k: self._value(raw, v, (*keys, k), stack)[0] for k, v in value.items()}, None
        if isinstance(value, list):
            return [self._value(raw, v, (*keys, i), stack)[0] for i, v in enumerate(value)], None
        return value, None

    def _pointer(
        self, raw: _Raw, pointer: Any, keys: JsonPath, stack: list[str]
    ) -> tuple[Any, Token | None]:
        """Follow a JSON Pointer ``#/a/b`` in the token's own document."""
        where: TokenPlace = {"file": raw.doc.path, "line": raw.doc.line(keys), "path": raw.path}
        if not isinstance(pointer, str) or not pointer.startswith("#"):
            raise token_error(
                f"$ref {pointer!r} must be a JSON Pointer into this file, like "
                '"#/color/blue/$value"',
                **where,
            )
        if pointer in stack:
            chain = " -> ".join([*stack[stack.index(pointer) :], pointer])
            raise token_error(f"$ref cycle: {chain}", **where)
        parts = [p.replace("~1", "/").replace("~0", "~") for p in pointer[1:].split("/")[1:]]
        # A pointer at a token (in any merged source: the last one wins, as for
        # aliases) is an alias; a pointer into its value walks the resolved value.
        for i in range(len(parts), 0, -1):
            token_path = ".".join(parts[:i])
            if token_path not in self.raw:
                continue
            rest = parts[i:]
            target = self._token(token_path, stack)
            if not rest or rest == ["$value"] or (self.legacy and rest == ["value"]):
                return target.value, target
            if rest[0] not in ("$value", "value"):
                raise token_error(
                    f"$ref {pointer} points into token {token_path} but not at its $value",
                    **where,
                )
            node: Any = target.value
            for part in rest[1:]:
                if isinstance(node, dict) and part in node:
                    node = node[part]
                elif isinstance(node, list) and part.isdigit() and int(part) < len(node):
                    node = node[int(part)]
                else:
                    raise token_error(f"$ref {pointer} points at nothing (no {part!r})", **where)
            return node, None
        node = raw.doc.data
        for part in parts:
            if isinstance(node, dict) and part in node:
                node = node[part]
            elif isinstance(node, list) and part.isdigit() and int(part) < len(node):
                node = node[int(part)]
            else:
                raise token_error(f"$ref {pointer} points at nothing (no {part!r})", **where)
        if len(stack) > MAX_ALIAS_CHAIN:
            raise token_error(f"$ref chain longer than {MAX_ALIAS_CHAIN}", **where)
        return self._value(raw, node, keys, [*stack, pointer])[0], None


def tokens_from_docs(docs: list[JsonDoc], *, legacy: bool = False) -> dict[str, Token]:
    """Merge ``docs`` in order (last wins) and resolve every token."""
    tree = TokenTree(legacy=legacy)
    for doc in docs:
        tree.add(doc)
    return tree.resolve()


def tokens_from_file(path: str | Path, *, legacy: bool = False) -> dict[str, Token]:
    """Resolve the tokens of one ``.tokens.json`` file."""
    from alpha_audit.load.tokens.jsondoc import load_json

    return tokens_from_docs([load_json(path)], legacy=legacy)
