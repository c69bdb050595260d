"""DTCG Resolver Module 2025.10: sets, modifiers with contexts, and a resolution order.

A resolver document names token files (``sources``: ``{"$ref": "file.json"}``
or inline token groups) in ``sets`` and ``modifiers``.  Each modifier has
``contexts`` (``light``, ``dark``, ...) and a ``default``.
``resolutionOrder`` lists sets and modifiers (``{"$ref": "#/sets/base"}`` or
inline ``{"type": "set" | "modifier", ...}``); their tokens merge in that
order, the last occurrence winning.  Each context of the chosen modifier is
one mode; the other modifiers take their default context.

Source files must lie inside the project root (a pull request can change the
resolver); remote URLs are refused: no network.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from alpha_audit.errors import InputError
from alpha_audit.load.names import check_name
from alpha_audit.load.paths import PathRefused, contain
from alpha_audit.load.tokens.dtcg import TokenTree
from alpha_audit.load.tokens.jsondoc import JsonDoc, load_json, pointer_parts, walk_pointer
from alpha_audit.load.tokens.model import Steps, TokenModes, check_mode_budget

__all__ = ["MAX_SOURCES", "is_resolver", "modes_from_resolver"]

MAX_SOURCES = 256


def is_resolver(data: Any) -> bool:
    """A resolver document has ``resolutionOrder`` at its top level."""
    return isinstance(data, dict) and "resolutionOrder" in data


class _Resolver:
    def __init__(self, doc: JsonDoc, root: Path, legacy: bool) -> None:
        self.doc = doc
        self.root = root
        self.legacy = legacy
        self.base = doc.path.resolve().parent
        self.files: dict[Path, JsonDoc] = {}

    def file(self, keys: tuple[str | int, ...], ref: str) -> JsonDoc:
        if "://" in ref or ref.startswith("//"):
            raise self.doc.at(keys, f"$ref {ref!r} is remote; only files in the project are read")
        try:
            target = contain(self.root, self.base, ref.split("#", 1)[0])
        except PathRefused as err:
            raise self.doc.at(keys, f"$ref: {err}") from err
        if target not in self.files:
            if len(self.files) >= MAX_SOURCES:
                raise self.doc.at(keys, f"more than {MAX_SOURCES} source files")
            if not target.is_file():  # named here, at the $ref, not as a file alone
                raise self.doc.at(keys, f"$ref {ref!r} names no file")
            self.files[target] = load_json(target)
        return self.files[target]

    def pointer(self, keys: tuple[str | int, ...], ref: str) -> tuple[Any, tuple[str, ...]]:
        try:
            return walk_pointer(self.doc.data, parts := pointer_parts(ref[1:])), parts
        except KeyError:
            raise self.doc.at(keys, f"$ref {ref!r} points at nothing") from None

    def sources(self, tree: TokenTree, keys: tuple[str | int, ...], items: Any) -> None:
        if not isinstance(items, list):
            raise self.doc.at(keys, "expected a list of sources ({$ref: file} or token groups)")
        for i, item in enumerate(items):
            ikeys = (*keys, i)
            if isinstance(item, dict) and set(item) == {"$ref"} and isinstance(item["$ref"], str):
                ref = item["$ref"]
                if ref.startswith("#/"):
                    node, parts = self.pointer(ikeys, ref)
                    tree.add(self.doc, node, parts)
                else:
                    doc = self.file(ikeys, ref)
                    if "#" in ref:
                        node, parts = _walk_pointer(doc, ref.split("#", 1)[1])
                        tree.add(doc, node, parts)
                    else:
                        tree.add(doc)
            elif isinstance(item, dict):
                tree.add(self.doc, item, ikeys)
            else:
                raise self.doc.at(ikeys, f"expected a source object, got {item!r:.40}")

    def entries(self) -> list[tuple[str, Any, tuple[str | int, ...]]]:
        """``("set" | "modifier", definition, keys)`` in resolution order."""
        order = self.doc.data.get("resolutionOrder")
        if not isinstance(order, list) or not order:
            raise self.doc.at(("resolutionOrder",), "expected a non-empty list")
        out: list[tuple[str, Any, tuple[str | int, ...]]] = []
        for i, item in enumerate(order):
            keys: tuple[str | int, ...] = ("resolutionOrder", i)
            if isinstance(item, dict) and isinstance(item.get("$ref"), str):
                ref = item["$ref"]
                if not ref.startswith("#/sets/") and not ref.startswith("#/modifiers/"):
                    raise self.doc.at(
                        keys, f"$ref {ref!r} must point at #/sets/... or #/modifiers/..."
                    )
                node, parts = self.pointer(keys, ref)
                kind = "set" if parts[0] == "sets" else "modifier"
                if not isinstance(node, dict):
                    raise self.doc.at(
                        parts, f"expected a {kind} object, got {_json_type(node)} (via {ref})"
                    )
                out.append((kind, node, parts))
            elif isinstance(item, dict) and item.get("type") in ("set", "modifier"):
                out.append((item["type"], item, keys))
            else:
                raise self.doc.at(keys, "expected {$ref: #/sets/...} or an inline set or modifier")
        return out


def _json_type(value: Any) -> str:
    """The JSON name of a value's type (``null``, ``array``, ``string``, ...)."""
    names = {bool: "boolean", int: "number", float: "number", str: "string", list: "array"}
    return "null" if value is None else names.get(type(value), "object")


def _walk_pointer(doc: JsonDoc, fragment: str) -> tuple[Any, tuple[str, ...]]:
    try:
        return walk_pointer(doc.data, parts := pointer_parts("/" + fragment.lstrip("/"))), parts
    except KeyError:
        raise InputError(f"#{fragment} points at nothing", path=doc.path, line=1) from None


def modes_from_resolver(
    doc: JsonDoc, *, root: Path, modifier: str | None = None, legacy: bool = False
) -> TokenModes:
    """One mode per context of ``modifier`` (default: the only modifier with contexts)."""
    r = _Resolver(doc, root, legacy)
    entries = r.entries()
    modifiers = [(node, keys) for kind, node, keys in entries if kind == "modifier"]
    names = [str(node.get("name", keys[-1])) for node, keys in modifiers]
    if modifier is None:
        if len(modifiers) > 1:
            raise doc.at(
                ("modifiers",),
                f"{len(modifiers)} modifiers ({', '.join(names)}); say which one gives the "
                "modes with tokens: {modifier: <name>} in the config",
            )
        chosen = names[0] if names else None
    else:
        if modifier not in names:
            raise doc.at(("modifiers",), f"no modifier {modifier!r}; have {', '.join(names)}")
        chosen = modifier
    contexts: list[str] = ["default"]
    context_keys: tuple[str | int, ...] = ("modifiers",)
    default: str | None = None
    for kind, node, keys in entries:
        if kind == "set":
            set_name = str(node.get("name", keys[-1]))
            check_name(set_name, path=doc.path, line=doc.line(keys), what="set name")
    for (node, keys), name in zip(modifiers, names, strict=True):
        check_name(name, path=doc.path, line=doc.line(keys), what="modifier name")
        ctx = node.get("contexts")
        if not isinstance(ctx, dict) or not ctx:
            raise doc.at((*keys, "contexts"), "expected a mapping of contexts to sources")
        if name == chosen:
            contexts = list(ctx)
            context_keys = (*keys, "contexts")
            default = node.get("default") if isinstance(node.get("default"), str) else None
    check_mode_budget(doc.path, len(contexts), 0)
    for context in contexts:
        line = doc.line((*context_keys, context))
        check_name(context, path=doc.path, line=line, what="context name")
    modes = {}
    steps = Steps()  # every mode walks the sets again: one budget for the file
    for context in contexts:
        tree = TokenTree(legacy=legacy, steps=steps)
        for kind, node, keys in entries:
            if kind == "set":
                r.sources(tree, (*keys, "sources"), node.get("sources"))
                continue
            name = str(node.get("name", keys[-1]))
            ctx = node["contexts"]
            pick = context if name == chosen else node.get("default", next(iter(ctx)))
            if pick not in ctx:
                raise doc.at((*keys, "default"), f"default {pick!r} is not one of its contexts")
            r.sources(tree, (*keys, "contexts", pick), ctx[pick])
        check_mode_budget(doc.path, len(contexts), len(tree.raw))
        modes[context] = tree.resolve()
    return TokenModes(doc.path, "resolver", modes, default)
