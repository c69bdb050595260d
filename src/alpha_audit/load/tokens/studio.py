"""Tokens Studio: token sets with ``value``/``type`` (or ``$value``/``$type``) and themes.

Two layouts: one JSON file whose top-level keys are token sets, beside
``$themes`` and ``$metadata``; or a folder of ``<set>.json`` files with
``$themes.json`` and ``$metadata.json``.  A theme's ``selectedTokenSets``
maps set names to ``enabled``, ``source`` (used for references) or
``disabled``.  Source sets merge first and enabled sets after, each group in
``$metadata.tokenSetOrder`` order, the last occurrence winning: references
resolve into a source set, and an enabled set's token wins over a source
set's (Tokens Studio leaves source sets out of its output).  Each theme is
one mode.  Without themes the sets merge into one mode, ``default``, only
when no token path is set by two of them; otherwise which set wins is a
guess (a dark set would override the light one), so it is an error.

Every file opened (sets, ``$metadata.json``) is resolved and must lie inside
the project root (:func:`alpha_audit.load.paths.contain`), symlinks included.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from itertools import product
from pathlib import Path
from typing import Any

from alpha_audit.errors import InputError
from alpha_audit.load.names import check_name
from alpha_audit.load.paths import PathRefused, contain
from alpha_audit.load.tokens.dtcg import TokenTree
from alpha_audit.load.tokens.jsondoc import JsonDoc, load_json
from alpha_audit.load.tokens.model import Steps, TokenModes, check_mode_budget

__all__ = ["is_studio_file", "modes_from_studio"]

_USED = ("enabled", "source")


def is_studio_file(doc: JsonDoc) -> bool:
    """A Tokens Studio file: ``$themes.json`` itself, or a single file with ``$themes``."""
    return doc.path.name == "$themes.json" or (
        isinstance(doc.data, dict) and ("$themes" in doc.data or "$metadata" in doc.data)
    )


def modes_from_studio(
    doc: JsonDoc, *, root: Path, groups: Sequence[str] | None = None
) -> TokenModes:
    """One mode per Tokens Studio theme (all sets in one mode when there are no themes).

    Themes with a ``group`` are combined, one theme of each group, as Tokens
    Studio applies them (and as ``permutateThemes`` of
    ``@tokens-studio/sd-transforms`` names them: ``<theme>-<theme>``, groups in
    the order they first appear).  ``groups`` picks the groups combined, in
    that order (``()``: none, each theme alone).
    """
    folder = doc.path.name == "$themes.json"
    themes, meta, sets = _parts(doc, root, folder)
    if not isinstance(themes, list):
        raise InputError("$themes must be a list of themes", path=doc.path, line=1)
    order = meta.get("tokenSetOrder") if isinstance(meta, dict) else None
    store = _Sets(doc, root, folder, sets, order if isinstance(order, list) else None)
    if len(themes) > 0:
        check_mode_budget(doc.path, len(themes), 0)
    combined = _combined(doc, _read_themes(doc, themes, folder), groups)
    modes = {}
    for name, states, keys in combined:
        chosen = store.ordered([s for s, st in states.items() if st == "source"])
        chosen += store.ordered([s for s, st in states.items() if st == "enabled"])
        modes[name] = store.build(chosen, (*keys, "selectedTokenSets"))
        check_mode_budget(doc.path, len(combined), len(modes[name]))
    if not modes:
        names = store.ordered(list(sets))
        _no_overlap(doc, names, sets)
        modes["default"] = store.build(names, ())
    return TokenModes(doc.path, "tokens-studio", modes, next(iter(modes)))


def _parts(
    doc: JsonDoc, root: Path, folder: bool
) -> tuple[Any, Any, dict[str, tuple[JsonDoc, Any]]]:
    """The themes, the metadata and the token sets held in ``doc`` (a folder's
    ``$themes.json`` holds none: its sets are files beside it, read when named)."""
    if folder:
        try:
            meta_path = contain(root, doc.path.resolve().parent, "$metadata.json")
        except PathRefused as err:
            raise InputError(str(err), path=doc.path) from err
        meta = load_json(meta_path).data if meta_path.is_file() else {}
        return doc.data, meta, {}
    sets = {
        check_name(k, path=doc.path, line=doc.line((k,)), what="token set"): (doc, v)
        for k, v in doc.data.items()
        if not k.startswith("$")
    }
    return doc.data.get("$themes", []), doc.data.get("$metadata", {}), sets


class _Sets:
    """The token sets a source's themes name: loaded once (a folder's from files beside its
    ``$themes.json``, inside the project), ordered by ``tokenSetOrder``, merged per theme."""

    def __init__(
        self,
        doc: JsonDoc,
        root: Path,
        folder: bool,
        sets: dict[str, tuple[JsonDoc, Any]],
        order: list[Any] | None,
    ) -> None:
        self.doc, self.root, self.folder, self.sets = doc, root, folder, sets
        self.base = doc.path.resolve().parent
        self.order = order
        # Each set's first place in tokenSetOrder, looked up once (not a list scan per set).
        self.rank: dict[Any, int] = {}
        for place, set_name in enumerate(order or []):
            if isinstance(set_name, str):
                self.rank.setdefault(set_name, place)
        self.steps = Steps()  # every theme walks its sets again: one budget for the source

    def load(self, name: str, keys: tuple[str | int, ...]) -> tuple[JsonDoc, Any]:
        """A set by name (``keys``: where a theme names it, for errors)."""
        if name not in self.sets:
            if not self.folder:
                raise self.doc.at(keys, f"names token set {name!r}, which this file does not have")
            try:
                target = contain(self.root, self.base, f"{name}.json")
            except PathRefused as err:
                raise self.doc.at(keys, f"token set {name!r}: {err}") from err
            if not target.is_file():  # named here, where a theme selects it
                raise self.doc.at(
                    keys, f"token set {name!r} has no file {name}.json beside this one"
                )
            loaded = load_json(target)
            self.sets[name] = (loaded, loaded.data)
        return self.sets[name]

    def ordered(self, names: list[str]) -> list[str]:
        """``names`` in ``tokenSetOrder`` (unlisted ones last), as given without one."""
        if self.order is None:
            return names
        return sorted(names, key=lambda s: self.rank.get(s, len(self.order or ())))

    def build(self, selected: list[str], keys: tuple[str | int, ...]) -> dict[str, Any]:
        """The resolved tokens of ``selected`` sets merged in order."""
        tree = TokenTree(legacy=True, steps=self.steps)
        for name in selected:
            sdoc, data = self.load(name, keys)
            tree.add(sdoc, data, (name,) if sdoc is self.doc else ())
        return tree.resolve()


def _read_themes(doc: JsonDoc, themes: list[Any], folder: bool) -> list[_Theme]:
    """Each theme's name, group, set states and place, names checked."""
    read: list[_Theme] = []
    for i, theme in enumerate(themes):
        keys: tuple[str | int, ...] = ("$themes", i) if not folder else (i,)
        if not isinstance(theme, dict) or not isinstance(theme.get("selectedTokenSets"), dict):
            raise doc.at(keys, "a theme needs name and selectedTokenSets")
        name = check_name(
            str(theme.get("name", i)), path=doc.path, line=doc.line(keys), what="theme name"
        )
        states = theme["selectedTokenSets"]
        for set_name in states:
            set_keys = (*keys, "selectedTokenSets", set_name)
            check_name(str(set_name), path=doc.path, line=doc.line(set_keys), what="token set")
        group = theme.get("group")
        read.append(_Theme(name, group if isinstance(group, str) else None, states, keys))
    return read


def _no_overlap(doc: JsonDoc, names: list[str], sets: dict[str, tuple[JsonDoc, Any]]) -> None:
    """Without themes, sets merge only when none sets a token path another sets."""
    owner: dict[str, str] = {}
    for name in names:
        tree = TokenTree(legacy=True)
        sdoc, data = sets[name]
        tree.add(sdoc, data, (name,))
        for path in tree.raw:
            if path in owner:
                raise doc.error(
                    (name,),
                    f"has no $themes, and token sets {owner[path]!r} and {name!r} both set "
                    f"{path}; merging them would let the later set win (a dark set over the "
                    "light one): add themes in Tokens Studio that say which sets make a mode",
                    path,
                )
            owner[path] = name


@dataclass(frozen=True)
class _Theme:
    name: str
    group: str | None
    states: dict[str, Any]  # set name -> enabled | source | disabled
    keys: tuple[str | int, ...]  # where the theme is in the file


def _combined(
    doc: JsonDoc, themes: list[_Theme], groups: Sequence[str] | None
) -> list[tuple[str, dict[str, Any], tuple[str | int, ...]]]:
    """``(mode name, set states, keys)``: each theme, or one theme of each group combined.

    A set enabled in any theme of a combination is enabled, else a source set
    in any is a source.
    """
    order = list(dict.fromkeys(t.group for t in themes if t.group is not None))
    chosen = order if groups is None else list(groups)
    if not chosen or (groups is None and len(order) < 2):
        return [(t.name, t.states, t.keys) for t in themes]
    by_group: dict[str, list[_Theme]] = {g: [] for g in chosen}
    for theme in themes:
        if theme.group is None and groups is None:
            raise doc.at(
                theme.keys,
                f"theme {theme.name!r} has no group, and themes of groups "
                f"{', '.join(chosen)} are combined; give it a group, or set the config's "
                "tokens: {modes: {groups: false}} to audit each theme alone",
            )
        if theme.group is not None and theme.group in by_group:
            by_group[theme.group].append(theme)
    for group, members in by_group.items():
        if not members:
            raise InputError(
                f"tokens.modes.groups names {group!r}, which no theme has; groups: "
                f"{', '.join(order)}",
                path=doc.path,
            )
    count = 1
    for members in by_group.values():
        count *= len(members)
    check_mode_budget(doc.path, count, 0)
    out = []
    for combination in product(*by_group.values()):
        states: dict[str, Any] = {}
        for theme in combination:
            for set_name, state in theme.states.items():
                if state == "enabled" or (state == "source" and states.get(set_name) != "enabled"):
                    states[set_name] = state
        name = "-".join(t.name for t in combination)
        check_name(name, path=doc.path, line=doc.line(combination[0].keys), what="theme name")
        out.append((name, states, combination[0].keys))
    return out
