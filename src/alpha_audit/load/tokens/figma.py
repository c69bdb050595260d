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

from alpha_audit.load.names import check_name
from alpha_audit.load.tokens.jsondoc import JsonDoc, JsonPath
from alpha_audit.load.tokens.model import (
    MAX_ALIAS_CHAIN,
    Steps,
    Token,
    TokenModes,
    TokenPlace,
    check_mode_budget,
    token_error,
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


class _Missing(Exception):
    def __init__(self, problem: str, place: TokenPlace) -> None:
        super().__init__(problem)
        self.problem = problem
        self.place = place


def modes_from_figma(doc: JsonDoc, *, collection: str | None = None) -> TokenModes:
    """One mode per mode of the chosen collection."""
    found = _meta(doc.data)
    assert found is not None  # detect_format chose figma
    meta, top = found
    variables, collections = meta["variables"], meta["variableCollections"]
    if not isinstance(variables, dict) or not isinstance(collections, dict) or not collections:
        raise token_error(
            "meta.variables and meta.variableCollections must be objects",
            file=doc.path,
            line=doc.line(top),
            path=None,
        )

    known: dict[str, dict[str, str]] = {}  # each collection's modes, read once

    def coll_modes(cid: str) -> dict[str, str]:
        if cid in known:
            return known[cid]
        c = collections.get(cid)
        if not isinstance(c, dict) or not isinstance(c.get("modes"), list):
            raise token_error(
                f"collection {cid!r} is missing or has no modes",
                file=doc.path,
                line=doc.line((*top, "variableCollections")),
                path=None,
            )
        modes = {}
        for m in c["modes"]:
            if not isinstance(m, dict) or not isinstance(m.get("name"), str) or "modeId" not in m:
                raise token_error(
                    f"collection {cid!r} has a mode without a name and a modeId",
                    file=doc.path,
                    line=doc.line((*top, "variableCollections", cid)),
                    path=None,
                )
            modes[m["name"]] = str(m["modeId"])
        if not modes:
            raise token_error(
                f"collection {cid!r} has no modes",
                file=doc.path,
                line=doc.line((*top, "variableCollections", cid)),
                path=None,
            )
        known[cid] = modes
        return modes

    if collection is None:
        main = max(collections, key=lambda cid: len(coll_modes(cid)))
    else:
        by_name = {str(c.get("name")): cid for cid, c in collections.items() if isinstance(c, dict)}
        if collection not in by_name:
            raise token_error(
                f"no collection named {collection!r}; have {', '.join(sorted(by_name))}",
                file=doc.path,
                line=doc.line((*top, "variableCollections")),
                path=None,
            )
        main = by_name[collection]
    for cid, coll in collections.items():
        if isinstance(coll, dict) and "name" in coll:
            line = doc.line((*top, "variableCollections", cid))
            check_name(str(coll["name"]), path=doc.path, line=line, what="collection name")
    names = list(coll_modes(main))
    check_mode_budget(doc.path, len(names), len(variables))
    for name in names:
        check_name(name, path=doc.path, line=doc.line((*top, "variableCollections")), what="mode")

    def where(vid: str, mode_id: str | None = None) -> TokenPlace:
        keys: JsonPath = (*top, "variables", vid)
        if mode_id is not None:
            keys = (*keys, "valuesByMode", mode_id)
        var = variables.get(vid)
        name = var.get("name") if isinstance(var, dict) else None
        shown = _path(name) if isinstance(name, str) and name else str(vid)
        return {"file": doc.path, "line": doc.line(keys), "path": shown}

    def mode_for(vid: str, mode_name: str) -> str:
        var = variables[vid]
        cid = var.get("variableCollectionId")
        if not isinstance(cid, str) or cid not in collections:
            raise _Missing(f"names no known variableCollectionId ({cid!r:.40})", where(vid))
        modes = coll_modes(cid)
        if mode_name in modes:
            return modes[mode_name]
        default = collections[cid].get("defaultModeId")
        return str(default) if default is not None else next(iter(modes.values()))

    steps = Steps()  # alias hops over every mode: linear in modes x variables, capped

    def resolve(vid: str, mode_name: str, stack: list[str]) -> tuple[Any, str, str]:
        steps.take(1, "resolving aliases", lambda: where(stack[0] if stack else vid))
        if vid not in variables or not isinstance(variables[vid], dict):
            raise _Missing(
                f"alias to variable {vid!r}, which this response does not hold (a library "
                "variable? the REST endpoint lists local variables only)",
                where(stack[-1]),
            )
        if vid in stack:
            chain = " -> ".join(str(where(v)["path"]) for v in [*stack, vid])
            raise token_error(f"alias cycle: {chain}", **where(stack[0]))
        if len(stack) > MAX_ALIAS_CHAIN:
            raise token_error(f"alias chain longer than {MAX_ALIAS_CHAIN}", **where(stack[0]))
        mode_id = mode_for(vid, mode_name)
        by_mode = variables[vid].get("valuesByMode")
        value = by_mode.get(mode_id) if isinstance(by_mode, dict) else None
        if isinstance(value, dict) and value.get("type") == "VARIABLE_ALIAS":
            return resolve(str(value.get("id")), mode_name, [*stack, vid])
        if value is None:
            raise _Missing(f"has no value for mode {mode_name!r}", where(vid))
        return value, vid, mode_id

    # What does not depend on the mode is read once per variable, not once per mode.
    read: list[tuple[str, dict[str, Any], str, str]] = []  # vid, variable, path, type
    named: dict[str, str] = {}  # token path: the variable name that made it
    for vid, var in variables.items():
        if not isinstance(var, dict) or not isinstance(var.get("name"), str):
            raise token_error("a variable needs a name", **where(vid))
        ttype = _TYPES.get(str(var.get("resolvedType")))
        if ttype is None:
            raise token_error(
                f"resolvedType {var.get('resolvedType')!r} is not one of {', '.join(_TYPES)}",
                **where(vid),
            )
        check_name(var["name"], **_named(where(vid)), what="variable name")
        path = _path(var["name"])
        if path in named:
            raise token_error(
                f"variables {named[path]!r} and {var['name']!r} both name the token {path}; "
                "token paths must be unique, rename one",
                **where(vid),
            )
        named[path] = var["name"]
        read.append((vid, var, path, ttype))

    modes: dict[str, dict[str, Token]] = {}
    for mode_name in names:
        tokens: dict[str, Token] = {}
        for vid, var, path, ttype in read:
            try:
                value, origin, origin_mode = resolve(vid, mode_name, [])
            except _Missing as exc:
                tokens[path] = Token(
                    path=path,
                    type=ttype,
                    value=None,
                    file=doc.path,
                    line=exc.place["line"],
                    problem=exc.problem,
                )
                continue
            loc = where(origin, origin_mode)
            if ttype == "color":
                value = _color(value, loc)
            tokens[path] = Token(
                path=path,
                type=ttype,
                value=value,
                file=doc.path,
                line=loc["line"],
                description=var.get("description") or None,
                chain=(str(where(origin)["path"]),) if origin != vid else (),
                alias_file=doc.path if origin != vid else None,
                alias_line=where(vid)["line"] if origin != vid else None,
            )
        modes[mode_name] = tokens
    default_id = collections[main].get("defaultModeId")
    default = next((n for n, m in coll_modes(main).items() if m == default_id), names[0])
    return TokenModes(doc.path, "figma", modes, default)


def _named(place: TokenPlace) -> dict[str, Any]:
    return {"path": place["file"], "line": place["line"], "key": place["path"]}


def _path(name: str) -> str:
    """Figma's ``color/bg/canvas`` to the token path ``color.bg.canvas``."""
    return ".".join(part.strip() for part in name.split("/"))


def _color(value: Any, where: TokenPlace) -> dict[str, Any]:
    """``{r, g, b, a}`` (sRGB, 0-1) to a DTCG colour object."""
    if not isinstance(value, dict) or not all(k in value for k in "rgb"):
        raise token_error(f"expected a colour {{r, g, b, a}}, got {value!r:.40}", **where)
    out: dict[str, Any] = {"colorSpace": "srgb", "components": [value[k] for k in "rgb"]}
    if "a" in value:
        out["alpha"] = value["a"]
    return out
