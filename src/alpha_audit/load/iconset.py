"""Icon-set manifests: which SVG files, which source colour and coefficient each."""

from __future__ import annotations

import difflib
import itertools
import os
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any

from alpha_audit.color import GamutPolicy
from alpha_audit.errors import InputError
from alpha_audit.load.fields import (
    check_keys,
    describe,
    read_color,
    read_gamut,
    read_mapping,
    read_name,
    read_number,
    read_pipeline,
)
from alpha_audit.load.paths import (
    PathRefused,
    contain,
    contain_argument,
    glob_contained,
    resolve,
)
from alpha_audit.load.yamldoc import KeyPath, YamlDoc, load_yaml
from alpha_audit.model import GamutAdjustment, Icon, IconSet, Span
from alpha_audit.ranges import ALPHA, ICON_SIZE, MAX_ICON_SIZE
from alpha_audit.safe_text import safe_text

__all__ = [
    "ALPHA_LIMIT",
    "MAX_ICONS",
    "MAX_SIZE",
    "find_project_root",
    "iconset_from_doc",
    "load_iconset",
]

MAX_ICONS = 10_000
MAX_SIZE = MAX_ICON_SIZE  # px (alpha_audit.ranges says why)
ALPHA_LIMIT = ALPHA.high  # any finite real is valid maths; beyond this it is a typo
_ROOT_MARKERS = (".git", "pyproject.toml", "alpha-audit.yaml", ".alpha-audit.yaml")
_MANIFEST_KEYS = (
    "name",
    "icons",
    "palette",
    "color",
    "alpha",
    "sizes",
    "overrides",
    "description",
    "pipeline",
    "lock",
    "gamut",
)
_ICON_KEYS = ("file", "name", "color", "alpha")
_GLOB_KEYS = ("glob", "name")
# How a glob names its icons: the file's stem (``x``), or its path from the
# manifest's folder without the extension (``filled/x``), which keeps
# ``filled/x`` and ``outline/x`` apart.
_NAMINGS = ("stem", "path")
_PALETTE_KEYS = ("color", "alpha")
_OVERRIDE_KEYS = ("color", "alpha", "lock")


def find_project_root(start: Path) -> Path:
    """Nearest ancestor of ``start`` holding a repository or project marker.

    Icon files must resolve inside it; without a marker the manifest's own
    folder is the root.  The ancestors are those of ``start``'s name, never of
    where a link points (a link does not pick its own root).
    """
    name = Path(os.path.abspath(start))
    for folder in (name, *name.parents):
        if any((folder / marker).exists() for marker in _ROOT_MARKERS):
            return resolve(folder)
    return resolve(name)


def load_iconset(
    path: str | Path, *, root: str | Path | None = None, gamut: GamutPolicy | None = None
) -> IconSet:
    """Load and validate an icon-set manifest.

    ``root`` bounds where icon files may live (default: :func:`find_project_root`).
    ``gamut`` (the project's policy) wins over the manifest's own ``gamut:``;
    with neither, a colour outside sRGB is an error.
    """
    # The root is found from where the manifest's name is, not where a link points.
    folder = Path(path).absolute().parent
    chosen = Path(root).resolve() if root else find_project_root(folder)
    try:  # before a byte is read: inside every project its name lies in, and inside ``root``
        contain_argument(path)
        contain_argument(path, chosen)
    except PathRefused as err:
        raise InputError(str(err), path=path) from err
    return iconset_from_doc(load_yaml(path), root=chosen, gamut=gamut)


class _Manifest:
    """Validation state for one manifest document."""

    def __init__(self, doc: YamlDoc, root: Path, gamut: GamutPolicy | None) -> None:
        self.doc = doc
        self.root = root
        # The manifest's own folder: a symlinked manifest never picks its target's.
        self.base = doc.path.absolute().parent.resolve()
        self.data = read_mapping(doc, (), doc.data, "an icon-set manifest")
        check_keys(doc, (), self.data, _MANIFEST_KEYS)
        own = self.data.get("gamut", "error")
        self.gamut: GamutPolicy = gamut or read_gamut(doc, ("gamut",), own)
        self.adjusted: list[GamutAdjustment] = []
        self.owner = str(self.data.get("name", ""))
        self.palette_spans: dict[str, Span] = {}  # where each palette entry's colour is written
        # A palette colour's own alpha (``red: {color: ..., alpha: 1.1}``) and where it is.
        self.palette_alpha: dict[str, tuple[float, KeyPath]] = {}
        self.palette = self.read_palette()

    def read_color(self, keys: KeyPath, value: Any) -> str:
        """A colour under the manifest's gamut policy, its adjustment recorded."""
        return read_color(
            self.doc, keys, value, gamut=self.gamut, adjusted=self.adjusted, owner=self.owner
        )

    def read_palette(self) -> dict[str, str]:
        """``{name: colour}``; an entry may be ``{color: ..., alpha: ...}`` (the colour's alpha)."""
        raw = self.data.get("palette", {})
        raw = read_mapping(self.doc, ("palette",), raw, "a palette {name: colour}")
        palette = {}
        for k, v in raw.items():
            name = read_name(self.doc, ("palette", k), k)
            keys: KeyPath = ("palette", k)
            if isinstance(v, dict):
                check_keys(self.doc, keys, v, _PALETTE_KEYS)
                if "color" not in v:
                    raise self.doc.error(keys, "a palette entry written as a mapping needs color:")
                if "alpha" in v:
                    alpha_keys: KeyPath = (*keys, "alpha")
                    self.palette_alpha[name] = (self.alpha(alpha_keys, v["alpha"]), alpha_keys)
                keys, v = (*keys, "color"), v["color"]
            palette[name] = self.read_color(keys, v)
            span = self.doc.spans.get(keys)
            if span is not None:
                self.palette_spans[name] = span
        return palette

    def color(self, keys: KeyPath, value: Any) -> tuple[str, str | None]:
        """A palette name or a colour string -> (colour, palette name or None)."""
        if isinstance(value, str) and value in self.palette:
            return self.palette[value], value
        if isinstance(value, str) and value.strip() == "cycle":
            raise self.doc.error(keys, "'cycle' is only allowed as the manifest-wide color")
        if isinstance(value, str) and self.palette:
            try:
                return self.read_color(keys, value), None
            except InputError as exc:
                names = ", ".join(self.palette)
                raise self.doc.error(
                    keys, f"{value!r} is neither a palette name ({names}) nor a colour"
                ) from exc
        return self.read_color(keys, value), None

    def alpha(self, keys: KeyPath, value: Any) -> float:
        return read_number(self.doc, keys, value, allowed=ALPHA)

    def sizes(self) -> tuple[int, ...]:
        raw = self.data.get("sizes", [24])
        if isinstance(raw, int) and not isinstance(raw, bool):
            raw = [raw]
        if not isinstance(raw, list) or not raw:
            raise self.doc.error(("sizes",), f"expected a list of pixel sizes, got {describe(raw)}")
        sizes = []
        for i, value in enumerate(raw):
            if isinstance(value, bool) or not isinstance(value, int) or value not in ICON_SIZE:
                raise self.doc.error(
                    ("sizes", i), f"{describe(value)} is not a size; use {ICON_SIZE.what}"
                )
            sizes.append(value)
        return tuple(sorted(set(sizes)))

    def resolve_file(self, keys: KeyPath, relative: str) -> Path:
        """A path relative to the manifest, resolved and contained (:mod:`.paths`)."""
        try:
            return contain(self.root, self.base, relative)
        except PathRefused as err:
            raise self.doc.error(keys, str(err)) from err

    def existing_file(self, keys: KeyPath, relative: str) -> Path:
        """A named icon file: inside the project root and present (a glob only finds real ones)."""
        path = self.resolve_file(keys, relative)
        if not path.is_file():
            what = "is a folder, not a file" if path.is_dir() else "does not exist"
            raise self.doc.error(keys, f"{relative!r} {what} (looked in {self.base})")
        return path

    def named_glob(self, raw: dict[str, Any]) -> list[tuple[KeyPath, Path, dict[str, Any]]]:
        """``icons: {glob: "**/*.svg", name: path}``: a glob whose icons are named by path."""
        keys: KeyPath = ("icons",)
        check_keys(self.doc, keys, raw, _GLOB_KEYS)
        pattern = raw.get("glob")
        if not isinstance(pattern, str) or not pattern.strip():
            raise self.doc.error(
                (*keys, "glob"), f"expected a glob like svg/*.svg, got {describe(pattern)}"
            )
        naming = raw.get("name", "stem")
        if naming not in _NAMINGS:
            raise self.doc.error(
                (*keys, "name"), f"expected one of {', '.join(_NAMINGS)}, got {describe(naming)}"
            )
        out: list[tuple[KeyPath, Path, dict[str, Any]]] = []
        for path in self.glob(pattern):
            if naming == "stem":
                out.append((keys, path, {}))
                continue
            within = path.relative_to(self.base) if path.is_relative_to(self.base) else path
            out.append((keys, path, {"name": within.with_suffix("").as_posix()}))
        return out

    def glob(self, pattern: str) -> list[Path]:
        keys: KeyPath = ("icons",)
        try:
            found = glob_contained(self.root, self.base, pattern, limit=MAX_ICONS)
        except PathRefused as err:
            raise self.doc.error(keys, str(err)) from err
        if not found:
            raise self.doc.error(keys, f"{safe_text(pattern)!r} matches no files under {self.base}")
        return sorted(set(found), key=lambda p: (p.name, str(p)))

    def entries(self) -> list[tuple[KeyPath, Path, dict[str, Any]]]:
        """(key path, file, explicit fields) for every icon, in manifest order."""
        raw = self.data.get("icons")
        if isinstance(raw, str):
            return [(("icons",), path, {}) for path in self.glob(raw)]
        if isinstance(raw, dict):
            return self.named_glob(raw)
        if not isinstance(raw, list) or not raw:
            raise self.doc.error(
                ("icons",),
                "expected a glob like svg/*.svg, {glob: ..., name: path} or a list of files / "
                "{file: ...}",
            )
        if len(raw) > MAX_ICONS:
            raise self.doc.error(("icons",), f"{len(raw)} icons; at most {MAX_ICONS} are allowed")
        out: list[tuple[KeyPath, Path, dict[str, Any]]] = []
        for i, item in enumerate(raw):
            keys: KeyPath = ("icons", i)
            if isinstance(item, str):
                out.append((keys, self.existing_file(keys, item), {}))
                continue
            item = read_mapping(self.doc, keys, item, "an icon (a path or {file: ...})")
            check_keys(self.doc, keys, item, _ICON_KEYS)
            if not isinstance(item.get("file"), str):
                raise self.doc.error((*keys, "file"), "each icon needs file: <path to .svg>")
            out.append((keys, self.existing_file((*keys, "file"), item["file"]), item))
        return out


def iconset_from_doc(doc: YamlDoc, *, root: Path, gamut: GamutPolicy | None = None) -> IconSet:
    """Validate a parsed manifest; icon files must resolve inside ``root``."""
    m = _Manifest(doc, root, gamut)
    data = m.data
    name = read_name(doc, ("name",), data.get("name", doc.path.parent.name or doc.path.stem))
    default_alpha = m.alpha(("alpha",), data["alpha"]) if "alpha" in data else 1.0
    if "color" in data and data["color"] is None:
        read_color(doc, ("color",), None)  # raises the "quote it" hint
    color_spec = data.get("color", "cycle" if m.palette else None)
    cycle = isinstance(color_spec, str) and color_spec.strip() == "cycle"
    if cycle and not m.palette:
        raise doc.error(("color",), "color: cycle needs a non-empty palette:")
    # No manifest-wide colour is fine as long as every icon brings its own.
    default = None if cycle or color_spec is None else m.color(("color",), color_spec)
    palette_cycle = itertools.cycle(m.palette.items())

    # An empty `overrides:` (YAML null) means no overrides, as if the key were absent.
    raw_overrides = data.get("overrides")
    overrides = read_mapping(
        doc, ("overrides",), {} if raw_overrides is None else raw_overrides, "overrides by icon"
    )
    locked = set(_palette_locks(m))
    icons: list[Icon] = []
    seen: dict[str, str] = {}
    for keys, file, explicit in m.entries():
        icon_name = read_name(doc, (*keys, "name"), explicit.get("name", file.stem))
        where = str(file.relative_to(m.root)) if file.is_relative_to(m.root) else str(file)
        if icon_name in seen:
            raise doc.error(
                keys,
                f"duplicate icon name {icon_name!r} ({seen[icon_name]} and {where}); "
                "give one a name:, or name a glob's icons by path: icons: {glob: ..., name: path}",
            )
        seen[icon_name] = where
        if cycle:
            pname, pcolor = next(palette_cycle)
            choice = _Choice(pcolor, pname, ("color",), default_alpha, ("alpha",))
        else:
            color, color_name = default if default else (None, None)
            choice = _Choice(color, color_name, ("color",), default_alpha, ("alpha",))
        choice = _set_by(m, keys, explicit, choice)
        if icon_name in overrides:
            choice = _overridden(m, icon_name, overrides[icon_name], choice, locked)
        if choice.color is None:
            raise doc.error(
                keys,
                f"icon {icon_name!r} has no colour; set a manifest-wide color:, a palette: "
                "to cycle, or color: on the icon",
            )
        overridden = overrides.get(icon_name)
        own_alpha = "alpha" in explicit or (isinstance(overridden, dict) and "alpha" in overridden)
        if not own_alpha and choice.name in m.palette_alpha:
            alpha, alpha_keys = m.palette_alpha[choice.name]  # the colour's own alpha
            choice = replace(choice, alpha=alpha, alpha_keys=alpha_keys)
        icons.append(_icon(m, icon_name, file, choice))
    unknown = sorted(set(overrides) - set(seen))
    if unknown:
        close = difflib.get_close_matches(unknown[0], list(seen), n=1)
        hint = f"; did you mean {close[0]!r}?" if close else ""
        raise doc.error(("overrides", unknown[0]), f"no icon named {unknown[0]!r}{hint}")
    pipeline = read_pipeline(doc, ("pipeline",), data["pipeline"]) if "pipeline" in data else None
    return IconSet(
        name,
        tuple(icons),
        m.palette,
        m.sizes(),
        path=doc.path,
        root=m.root,
        pipeline=pipeline,
        locked=frozenset(locked),
        adjusted=tuple(replace(a, mode=name) for a in m.adjusted),
    )


@dataclass(frozen=True)
class _Choice:
    """An icon's colour and alpha as read so far, and the keys that set each."""

    color: str | None
    name: str | None
    color_keys: KeyPath
    alpha: float
    alpha_keys: KeyPath


def _icon(m: _Manifest, name: str, file: Path, choice: _Choice) -> Icon:
    """The icon as read, with the lines and spans that set its colour and alpha."""
    assert choice.color is not None  # refused before
    doc = m.doc
    return Icon(
        name,
        file,
        choice.color,
        choice.alpha,
        choice.name,
        color_line=_line_if_set(doc, choice.color_keys),
        alpha_line=_line_if_set(doc, choice.alpha_keys),
        # A palette colour is fixed at its palette entry, whoever names it.
        color_span=m.palette_spans.get(choice.name)
        if choice.name is not None
        else doc.spans.get(choice.color_keys),
        alpha_span=doc.spans.get(choice.alpha_keys),
    )


def _set_by(m: _Manifest, keys: KeyPath, given: dict[str, Any], choice: _Choice) -> _Choice:
    """``choice`` with the ``color`` and ``alpha`` that ``given`` (at ``keys``) sets."""
    if "color" in given:
        color, color_name = m.color((*keys, "color"), given["color"])
        choice = replace(choice, color=color, name=color_name, color_keys=(*keys, "color"))
    if "alpha" in given:
        alpha = m.alpha((*keys, "alpha"), given["alpha"])
        choice = replace(choice, alpha=alpha, alpha_keys=(*keys, "alpha"))
    return choice


def _overridden(
    m: _Manifest, icon_name: str, raw: Any, choice: _Choice, locked: set[str]
) -> _Choice:
    """``overrides: {icon: {color, alpha, lock}}`` applied to an icon (a lock is added to
    ``locked``)."""
    doc = m.doc
    okeys: KeyPath = ("overrides", icon_name)
    override = read_mapping(doc, okeys, raw, "{color: ..., alpha: ...}")
    check_keys(doc, okeys, override, _OVERRIDE_KEYS)
    choice = _set_by(m, okeys, override, choice)
    if "lock" in override:
        if not isinstance(override["lock"], bool):
            got = describe(override["lock"])
            raise doc.error((*okeys, "lock"), f"expected true or false, got {got}")
        if override["lock"]:
            locked.add(icon_name)
    return choice


def _palette_locks(m: _Manifest) -> list[str]:
    """``lock: [palette names]``: brand colours that may not drift (docs/model.md)."""
    if "lock" not in m.data:
        return []
    raw = m.data["lock"]
    items = [raw] if isinstance(raw, str) else raw
    if not isinstance(items, list):
        raise m.doc.error(("lock",), f"expected a list of palette names, got {describe(raw)}")
    for i, item in enumerate(items):
        if not isinstance(item, str) or item not in m.palette:
            names = ", ".join(m.palette) or "none defined"
            raise m.doc.error(
                ("lock", i), f"{describe(item)} is not a palette name (palette: {names})"
            )
    return list(items)


def _line_if_set(doc: YamlDoc, keys: KeyPath) -> int | None:
    """Line of ``keys`` only if the manifest really contains it (not a default)."""
    return doc.lines.get(keys)
