"""Tie an icon found on a page to the manifest's icon: data attribute, sprite id, file, paths.

The page probe (``probe.js``) reports, per icon, the value of the data
attribute (``data-icon`` by default), the sprite id of a ``<use>``, the file
name of an ``<img>`` or ``mask-image``, and a hash of its geometry; the
manifest side computes the same hash from each icon's SVG file here, with the
same attribute list and normalisation, so an inline copy of an SVG maps to
its file whatever its colours or classes.
"""

from __future__ import annotations

import hashlib
import re
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from defusedxml import ElementTree

from alpha_audit.model import Icon, IconSet
from alpha_audit.observed import IconMatch

__all__ = ["GEOMETRY", "ManifestIndex", "geometry_hash"]

_SHAPES = frozenset({"path", "circle", "ellipse", "line", "polyline", "polygon", "rect"})
_SKIPPED = frozenset({"defs", "mask", "clipPath"})
# The same list, in the same order, as probe.js's GEOMETRY.
GEOMETRY = ("d", "cx", "cy", "r", "rx", "ry", "x", "y", "x1", "y1", "x2", "y2", "width",
            "height", "points")  # fmt: skip
_SPACES = re.compile(r"[\s,]+")
# A bundler's content hash after the name: star-DxYz12ab.svg (Vite, webpack, Parcel).
_HASHED = re.compile(r"^(?P<stem>.+?)[-.][A-Za-z0-9_]{8,}$")
MAX_SVG_BYTES = 1 << 20


def _local(tag: str) -> str:
    return tag.rsplit("}", 1)[-1]


def geometry_hash(svg: bytes) -> str | None:
    """The first 16 hex digits of SHA-256 over the SVG's shapes and their geometry.

    >>> geometry_hash(b'<svg xmlns="http://www.w3.org/2000/svg"><path d="M1,2  L3 4"/></svg>')
    'd95136580fd8fd8a'
    """
    try:
        root = ElementTree.fromstring(svg)
    except Exception:
        return None
    lines: list[str] = []

    def walk(element: Any) -> None:
        for child in element:
            tag = _local(str(child.tag))
            if tag in _SHAPES:
                parts = [tag]
                parts += [
                    f"{name}={_SPACES.sub(' ', child.attrib[name]).strip()}"
                    for name in GEOMETRY
                    if name in child.attrib
                ]
                lines.append(" ".join(parts))
            if tag not in _SKIPPED:
                walk(child)

    walk(root)
    return hashlib.sha256("\n".join(lines).encode()).hexdigest()[:16]


def _file_stem(name: str) -> tuple[str, ...]:
    """Names a file may stand for: its stem, and the stem without a bundler's hash."""
    stem = name.rsplit("/", 1)[-1]
    stem = stem[: -len(".svg")] if stem.lower().endswith(".svg") else stem
    match = _HASHED.match(stem)
    return (stem, match.group("stem")) if match else (stem,)


@dataclass(frozen=True)
class ManifestIndex:
    """The manifest's icons by name, file stem and geometry hash."""

    icons: Mapping[str, Icon] = field(default_factory=dict)
    stems: Mapping[str, str] = field(default_factory=dict)
    hashes: Mapping[str, str] = field(default_factory=dict)

    @classmethod
    def of(cls, iconset: IconSet | None) -> ManifestIndex:
        """Index ``iconset`` (an empty index for None)."""
        if iconset is None:
            return cls()
        icons = {icon.name: icon for icon in iconset.icons}
        stems = {icon.file.stem: icon.name for icon in iconset.icons}
        hashes: dict[str, str] = {}
        for icon in iconset.icons:
            try:
                data = Path(icon.file).read_bytes()[:MAX_SVG_BYTES]
            except OSError:
                continue
            digest = geometry_hash(data)
            if digest is not None:
                hashes.setdefault(digest, icon.name)
        return cls(icons, stems, hashes)

    def match(self, keys: Mapping[str, object]) -> tuple[Icon | None, IconMatch]:
        """The manifest icon for a probe's ``keys`` and how it matched, in that order."""
        data, sprite, file, geometry = (keys.get(k) for k in ("data", "sprite", "file", "geometry"))
        if isinstance(data, str) and data in self.icons:
            return self.icons[data], IconMatch.DATA_ATTRIBUTE
        if isinstance(sprite, str):
            for name in (sprite, *_file_stem(sprite)):
                if name in self.icons:
                    return self.icons[name], IconMatch.SPRITE_ID
        if isinstance(file, str) and file:
            for stem in _file_stem(file):
                known = stem if stem in self.icons else self.stems.get(stem)
                if known is not None:
                    return self.icons[known], IconMatch.FILE_NAME
        if isinstance(geometry, str):  # the probe's geometry text, hashed as the files are
            digest = hashlib.sha256(geometry.encode("utf-8", "replace")).hexdigest()[:16]
            if digest in self.hashes:
                return self.icons[self.hashes[digest]], IconMatch.PATH_HASH
        return None, IconMatch.NONE
