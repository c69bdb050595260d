"""Figma Variables saved from the REST API (``GET /v1/files/:key/variables/local``).

``meta.variables[id]`` has ``name`` (``color/bg/canvas``: slashes are groups,
read as the token path ``color.bg.canvas``), ``variableCollectionId``,
``resolvedType`` and ``valuesByMode[modeId]``: a colour ``{r, g, b, a}`` in
0-1 (sRGB) or ``{"type": "VARIABLE_ALIAS", "id": ...}``.
``meta.variableCollections[id].modes`` lists ``{modeId, name}``.

The modes are those of the collection with the most modes (or the one
named by ``collection``); a variable of another collection takes the mode
of the same name there, else its collection's default mode.  Aliases are
followed across collections, cycles are errors naming the chain.
"""

from __future__ import annotations

from typing import Any

from alpha_audit.load.tokens.jsondoc import JsonDoc
from alpha_audit.load.tokens.model import (
    MAX_ALIAS_CHAIN,
    Token,
    TokenModes,
    TokenPlace,
    token_error,
)

__all__ = ["is_figma", "modes_from_figma"]

_TYPES = {"COLOR": "color", "FLOAT": "number", "STRING": "string", "BOOLEAN": "boolean"}


def is_figma(data: Any) -> bool:
    """Figma's REST response has ``meta.variables`` and ``meta.variableCollections``."""
    meta = data.get("meta") if isinstance(data, dict) else None
    return isinstance(meta, dict) and "variables" in meta and "variableCollections" in meta


def modes_from_figma(doc: JsonDoc, *, collection: str | None = None) -> TokenModes:
    """One mode per mode of the chosen collection."""
    meta = doc.data["meta"]
    variables, collections = meta["variables"], meta["variableCollections"]
    if not isinstance(variables, dict) or not isinstance(collections, dict) or not collections:
        raise token_error(
            "meta.variables and meta.variableCollections must be objects",
            file=doc.path,
            line=doc.line(("meta",)),
            path=None,
        )

    def coll_modes(cid: str) -> dict[str, str]:
        c = collections.get(cid)
        if not isinstance(c, dict) or not isinstance(c.get("modes"), list):
            raise token_error(
                f"collection {cid!r} is missing or has no modes",
                file=doc.path,
                line=doc.line(("meta", "variableCollections")),
                path=None,
            )
        return {str(m["name"]): str(m["modeId"]) for m in c["modes"] if isinstance(m, dict)}

    if collection is None:
        main = max(collections, key=lambda cid: len(coll_modes(cid)))
    else:
        by_name = {str(c.get("name")): cid for cid, c in collections.items() if isinstance(c, dict)}
        if collection not in by_name:
            raise token_error(
                f"no collection named {collection!r}; have {', '.join(sorted(by_name))}",
                file=doc.path,
                line=doc.line(("meta", "variableCollections")),
                path=None,
            )
        main = by_name[collection]
    names = list(coll_modes(main))

    def where(vid: str, mode_id: str | None = None) -> TokenPlace:
        keys: tuple[str, ...] = ("meta", "variables", vid)
        if mode_id is not None:
            keys = (*keys, "valuesByMode", mode_id)
        name = variables.get(vid, {}).get("name") if isinstance(variables.get(vid), dict) else None
        return {"file": doc.path, "line": doc.line(keys), "path": _path(name) if name else vid}

    def mode_for(vid: str, mode_name: str) -> str:
        var = variables[vid]
        cid = var.get("variableCollectionId")
        modes = coll_modes(cid)
        if mode_name in modes:
            return modes[mode_name]
        default = collections[cid].get("defaultModeId")
        return str(default) if default is not None else next(iter(modes.values()))

    def resolve(vid: str, mode_name: str, stack: list[str]) -> tuple[Any, str, str]:
        if vid not in variables or not isinstance(variables[vid], dict):
            raise token_error(f"alias to unknown variable {vid!r}", **where(stack[-1]))
        if vid in stack:
            chain = " -> ".join(_path(variables[v]["name"]) for v in [*stack, vid])
            raise token_error(f"alias cycle: {chain}", **where(stack[0]))
        if len(stack) > MAX_ALIAS_CHAIN:
            raise token_error(f"alias chain longer than {MAX_ALIAS_CHAIN}", **where(stack[0]))
        mode_id = mode_for(vid, mode_name)
        value = variables[vid].get("valuesByMode", {}).get(mode_id)
        if isinstance(value, dict) and value.get("type") == "VARIABLE_ALIAS":
            return resolve(str(value.get("id")), mode_name, [*stack, vid])
        if value is None:
            raise token_error(f"has no value for mode {mode_name!r}", **where(vid))
        return value, vid, mode_id

    modes: dict[str, dict[str, Token]] = {}
    for mode_name in names:
        tokens: dict[str, Token] = {}
        for vid, var in variables.items():
            if not isinstance(var, dict) or not isinstance(var.get("name"), str):
                raise token_error("a variable needs a name", **where(vid))
            ttype = _TYPES.get(str(var.get("resolvedType")))
            if ttype is None:
                raise token_error(
                    f"resolvedType {var.get('resolvedType')!r} is not one of {', '.join(_TYPES)}",
                    **where(vid),
                )
            path = _path(var["name"])
            if path in tokens:
                raise token_error(
                    f"two variables are named {var['name']!r}; token paths must be unique",
                    **where(vid),
                )
            value, origin, origin_mode = resolve(vid, mode_name, [])
            if ttype == "color":
                value = _color(value, where(origin, origin_mode))
            loc = where(origin, origin_mode)
            tokens[path] = Token(
                path=path,
                type=ttype,
                value=value,
                file=doc.path,
                line=loc["line"],
                description=var.get("description") or None,
                chain=(_path(variables[origin]["name"]),) if origin != vid else (),
                alias_file=doc.path if origin != vid else None,
                alias_line=where(vid, mode_for(vid, mode_name))["line"] if origin != vid else None,
            )
        modes[mode_name] = tokens
    default_id = collections[main].get("defaultModeId")
    default = next((n for n, m in coll_modes(main).items() if m == default_id), names[0])
    return TokenModes(doc.path, "figma", modes, default)


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
