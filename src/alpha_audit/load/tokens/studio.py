"""Tokens Studio: token sets with ``value``/``type`` (or ``$value``/``$type``) and themes.

Two layouts: one JSON file whose top-level keys are token sets, beside
``$themes`` and ``$metadata``; or a folder of ``<set>.json`` files with
``$themes.json`` and ``$metadata.json``.  A theme's ``selectedTokenSets``
maps set names to ``enabled``, ``source`` (used for references) or
``disabled``; enabled and source sets merge in ``$metadata.tokenSetOrder``
order, the last occurrence winning.  Each theme is one mode.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from alpha_audit.load.tokens.dtcg import TokenTree
from alpha_audit.load.tokens.jsondoc import JsonDoc, load_json
from alpha_audit.load.tokens.model import TokenModes, token_error

__all__ = ["is_studio_file", "modes_from_studio"]

_USED = ("enabled", "source")


def is_studio_file(doc: JsonDoc) -> bool:
    """A Tokens Studio file: ``$themes.json`` itself, or a single file with ``$themes``."""
    return doc.path.name == "$themes.json" or (
        isinstance(doc.data, dict) and ("$themes" in doc.data or "$metadata" in doc.data)
    )


def modes_from_studio(doc: JsonDoc, *, root: Path) -> TokenModes:
    """One mode per Tokens Studio theme (all sets in one mode when there are no themes)."""
    folder = doc.path.name == "$themes.json"
    base = doc.path.resolve().parent
    if folder:
        themes: Any = doc.data
        meta_path = base / "$metadata.json"
        meta = load_json(meta_path).data if meta_path.is_file() else {}
        sets: dict[str, tuple[JsonDoc, Any]] = {}
    else:
        themes = doc.data.get("$themes", [])
        meta = doc.data.get("$metadata", {})
        sets = {k: (doc, v) for k, v in doc.data.items() if not k.startswith("$")}
    if not isinstance(themes, list):
        raise token_error("$themes must be a list of themes", file=doc.path, line=1, path=None)
    order = meta.get("tokenSetOrder") if isinstance(meta, dict) else None

    def load_set(name: str, keys: tuple[str | int, ...]) -> tuple[JsonDoc, Any]:
        if name not in sets:
            if not folder:
                raise token_error(
                    f"names token set {name!r}, which this file does not have",
                    file=doc.path,
                    line=doc.line(keys),
                    path=".".join(map(str, keys)),
                )
            target = (base / f"{name}.json").resolve()
            if not target.is_relative_to(root):
                raise token_error(
                    f"token set {name!r} resolves outside {root}; not allowed",
                    file=doc.path,
                    line=doc.line(keys),
                    path=".".join(map(str, keys)),
                )
            loaded = load_json(target)
            sets[name] = (loaded, loaded.data)
        return sets[name]

    def build(selected: list[str], keys: tuple[str | int, ...]) -> dict[str, Any]:
        if isinstance(order, list):
            selected = sorted(selected, key=lambda s: order.index(s) if s in order else len(order))
        tree = TokenTree(legacy=True)
        for name in selected:
            sdoc, data = load_set(name, keys)
            tree.add(sdoc, data, (name,) if sdoc is doc else ())
        return tree.resolve()

    modes = {}
    for i, theme in enumerate(themes):
        keys: tuple[str | int, ...] = ("$themes", i) if not folder else (i,)
        if not isinstance(theme, dict) or not isinstance(theme.get("selectedTokenSets"), dict):
            raise token_error(
                "a theme needs name and selectedTokenSets",
                file=doc.path,
                line=doc.line(keys),
                path=".".join(map(str, keys)),
            )
        name = str(theme.get("name", i))
        chosen = [s for s, state in theme["selectedTokenSets"].items() if state in _USED]
        modes[name] = build(chosen, (*keys, "selectedTokenSets"))
    if not modes:
        modes["default"] = build(list(sets), ())
    return TokenModes(doc.path, "tokens-studio", modes, next(iter(modes)))
