"""Figma Variables saved from the REST API (``GET /v1/files/:key/variables/local``).

``meta.variables[id]`` has ``name`` (``color/bg/canvas``: slashes are groups,
read as the token path ``color.bg.canvas``), ``variableCollectionId``,
``resolvedType`` and ``valuesByMode[modeId]``: a colour ``{r, g, b, a}`` in
0-1 (sRGB) or ``{"type": "VARIABLE_ALIAS", "id": ...}``.
``meta.variableCollections[id].modes`` lists ``{modeId, name}``.

The modes are those of the collection with the most modes (or the one
named by ``collection``); a variable of another collection takes the mode
of the same name there, else its collection's default mode.  Aliases are
followed across collections, cycles are errors naming the chain.  An alias
to a variable the response does not hold (a library's: the REST endpoint
lists local variables only) loads, and is an error only where selected.
The same data saved without the ``{"status", "error", "meta"}`` envelope
(``{"variables", "variableCollections"}`` at the top) is read the same way.
"""

from __future__ import annotations

from typing import Any

from alpha_audit.errors import InputError
from alpha_audit.load.names import check_name
from alpha_audit.load.tokens.jsondoc import JsonDoc, JsonPath
from alpha_audit.load.tokens.model import (
    Steps,
    Token,
    TokenModes,
    TokenPlace,
    Unresolved,
    check_mode_budget,
    follow,
)

__all__ = ["is_figma", "modes_from_figma"]

_TYPES = {"COLOR": "color", "FLOAT": "number", "STRING": "string", "BOOLEAN": "boolean"}


def _meta(data: Any) -> tuple[Any, JsonPath] | None:
    """``(meta, its keys)``: the REST response's ``meta``, or the envelope-less object."""
    if not isinstance(data, dict):
        return None
    meta = data.get("meta")
    if isinstance(meta, dict) and "variables" in meta and "variableCollections" in meta:
        return meta, ("meta",)
    if "variables" in data and "variableCollections" in data:
        return data, ()
    return None


def is_figma(data: Any) -> bool:
    """Figma's REST response (``meta.variables``, ``meta.variableCollections``), or its meta."""
    return _meta(data) is not None


def modes_from_figma(doc: JsonDoc, *, collection: str | None = None) -> TokenModes:
    """One mode per mode of the chosen collection."""
    found = _meta(doc.data)
    assert found is not None  # detect_format chose figma
    meta, top = found
    variables, collections = meta["variables"], meta["variableCollections"]
    if not isinstance(variables, dict) or not isinstance(collections, dict) or not collections:
        raise doc.error(top, "meta.variables and meta.variableCollections must be objects")
    reader = _Reader(doc, top, variables, collections)
    main = reader.main_collection(collection)
    names = list(reader.coll_modes(main))
    check_mode_budget(doc.path, len(names), len(variables))
    for name in names:
        check_name(name, path=doc.path, line=doc.line((*top, "variableCollections")), what="mode")
    read = reader.variables_once()
    modes = {mode_name: reader.mode(mode_name, read) for mode_name in names}
    default_id = collections[main].get("defaultModeId")
    default = next((n for n, m in reader.coll_modes(main).items() if m == default_id), names[0])
    return TokenModes(doc.path, "figma", modes, default)


class _Reader:
    """One response's variables and collections, each collection's modes read once."""

    def __init__(
        self, doc: JsonDoc, top: JsonPath, variables: dict[str, Any], collections: dict[str, Any]
    ) -> None:
        self.doc, self.top = doc, top
        self.variables, self.collections = variables, collections
        self.known: dict[str, dict[str, str]] = {}  # each collection's modes, read once
        self.steps = Steps()  # alias hops over every mode: linear in modes x variables, capped

    def _error(self, message: str, *keys: str) -> Exception:
        return self.doc.error((*self.top, "variableCollections", *keys), message)

    def coll_modes(self, cid: str) -> dict[str, str]:
        """A collection's modes, name -> modeId."""
        if cid in self.known:
            return self.known[cid]
        c = self.collections.get(cid)
        if not isinstance(c, dict) or not isinstance(c.get("modes"), list):
            raise self._error(f"collection {cid!r} is missing or has no modes")
        modes = {}
        for m in c["modes"]:
            if not isinstance(m, dict) or not isinstance(m.get("name"), str) or "modeId" not in m:
                raise self._error(f"collection {cid!r} has a mode without a name and a modeId", cid)
            modes[m["name"]] = str(m["modeId"])
        if not modes:
            raise self._error(f"collection {cid!r} has no modes", cid)
        self.known[cid] = modes
        return modes

    def main_collection(self, collection: str | None) -> str:
        """The collection whose modes are the modes: the named one, else the one with most;
        every collection's name checked."""
        if collection is None:
            main = max(self.collections, key=lambda cid: len(self.coll_modes(cid)))
        else:
            by_name = {
                str(c.get("name")): cid
                for cid, c in self.collections.items()
                if isinstance(c, dict)
            }
            if collection not in by_name:
                raise self._error(
                    f"no collection named {collection!r}; have {', '.join(sorted(by_name))}"
                )
            main = by_name[collection]
        for cid, coll in self.collections.items():
            if isinstance(coll, dict) and "name" in coll:
                line = self.doc.line((*self.top, "variableCollections", cid))
                check_name(str(coll["name"]), path=self.doc.path, line=line, what="collection name")
        return main

    def where(self, vid: str, mode_id: str | None = None) -> TokenPlace:
        """Where a variable (or its value in a mode) is, and its token path."""
        keys: JsonPath = (*self.top, "variables", vid)
        if mode_id is not None:
            keys = (*keys, "valuesByMode", mode_id)
        var = self.variables.get(vid)
        name = var.get("name") if isinstance(var, dict) else None
        shown = _path(name) if isinstance(name, str) and name else str(vid)
        return {"path": self.doc.path, "line": self.doc.line(keys), "key": shown}

    def label(self, vid: str) -> str:
        """A variable's token path (its id when it has no name)."""
        return str(self.where(vid)["key"])

    def mode_for(self, vid: str, mode_name: str) -> str:
        """The modeId a variable takes in mode ``mode_name``: its collection's mode of that
        name, else its collection's default mode."""
        cid = self.variables[vid].get("variableCollectionId")
        if not isinstance(cid, str) or cid not in self.collections:
            problem = f"names no known variableCollectionId ({cid!r:.40})"
            raise Unresolved(problem, self.where(vid)["line"])
        modes = self.coll_modes(cid)
        if mode_name in modes:
            return modes[mode_name]
        default = self.collections[cid].get("defaultModeId")
        return str(default) if default is not None else next(iter(modes.values()))

    def resolve(self, vid: str, mode_name: str, stack: list[str]) -> tuple[Any, str, str]:
        """A variable's value in a mode through its aliases: (value, origin, origin's mode)."""
        self.steps.take(1, "resolving aliases", lambda: self.where(stack[0] if stack else vid))
        if vid not in self.variables or not isinstance(self.variables[vid], dict):
            raise Unresolved(
                f"alias to variable {vid!r}, which this response does not hold (a library "
                "variable? the REST endpoint lists local variables only)",
                self.where(stack[-1])["line"],
            )
        follow(stack, vid, "alias", lambda: self.where(stack[0]), self.label)
        mode_id = self.mode_for(vid, mode_name)
        by_mode = self.variables[vid].get("valuesByMode")
        value = by_mode.get(mode_id) if isinstance(by_mode, dict) else None
        if isinstance(value, dict) and value.get("type") == "VARIABLE_ALIAS":
            return self.resolve(str(value.get("id")), mode_name, [*stack, vid])
        if value is None:
            raise Unresolved(f"has no value for mode {mode_name!r}", self.where(vid)["line"])
        return value, vid, mode_id

    def variables_once(self) -> list[tuple[str, dict[str, Any], str, str]]:
        """What does not depend on the mode, read once per variable: (id, variable, token
        path, type); names checked, token paths unique."""
        read: list[tuple[str, dict[str, Any], str, str]] = []
        named: dict[str, str] = {}  # token path: the variable name that made it
        for vid, var in self.variables.items():
            if not isinstance(var, dict) or not isinstance(var.get("name"), str):
                raise InputError("a variable needs a name", **self.where(vid))
            ttype = _TYPES.get(str(var.get("resolvedType")))
            if ttype is None:
                raise InputError(
                    f"resolvedType {var.get('resolvedType')!r} is not one of {', '.join(_TYPES)}",
                    **self.where(vid),
                )
            check_name(var["name"], **self.where(vid), what="variable name")
            path = _path(var["name"])
            if path in named:
                raise InputError(
                    f"variables {named[path]!r} and {var['name']!r} both name the token {path}; "
                    "token paths must be unique, rename one",
                    **self.where(vid),
                )
            named[path] = var["name"]
            read.append((vid, var, path, ttype))
        return read

    def mode(
        self, mode_name: str, read: list[tuple[str, dict[str, Any], str, str]]
    ) -> dict[str, Token]:
        """Every variable's token in one mode (a value that cannot be resolved is a token
        with a problem: an error only where selected)."""
        tokens: dict[str, Token] = {}
        path_of = self.doc.path
        for vid, var, path, ttype in read:
            try:
                value, origin, origin_mode = self.resolve(vid, mode_name, [])
            except Unresolved as exc:
                tokens[path] = Token(
                    path=path,
                    type=ttype,
                    value=None,
                    file=path_of,
                    line=exc.line,
                    problem=exc.problem,
                )
                continue
            loc = self.where(origin, origin_mode)
            if ttype == "color":
                value = _color(value, loc)
            aliased = origin != vid
            tokens[path] = Token(
                path=path,
                type=ttype,
                value=value,
                file=path_of,
                line=loc["line"],
                description=var.get("description") or None,
                chain=(self.label(origin),) if aliased else (),
                alias_file=path_of if aliased else None,
                alias_line=self.where(vid)["line"] if aliased else None,
            )
        return tokens


def _path(name: str) -> str:
    """Figma's ``color/bg/canvas`` to the token path ``color.bg.canvas``."""
    return ".".join(part.strip() for part in name.split("/"))


def _color(value: Any, where: TokenPlace) -> dict[str, Any]:
    """``{r, g, b, a}`` (sRGB, 0-1) to a DTCG colour object."""
    if not isinstance(value, dict) or not all(k in value for k in "rgb"):
        raise InputError(f"expected a colour {{r, g, b, a}}, got {value!r:.40}", **where)
    out: dict[str, Any] = {"colorSpace": "srgb", "components": [value[k] for k in "rgb"]}
    if "a" in value:
        out["alpha"] = value["a"]
    return out
