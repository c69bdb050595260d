"""Mapping a found icon to the manifest by its geometry, without a browser.

The probe sends an icon's geometry as text (hashing in the page would read a
TypedArray across Firefox's Xray wrappers); here it is hashed exactly as the
manifest's SVG files are.
"""

from __future__ import annotations

from pathlib import Path

from alpha_audit.model import Icon, IconSet
from alpha_audit.observed import IconMatch
from alpha_audit.pages.mapping import ManifestIndex


def _index(tmp_path: Path) -> ManifestIndex:
    star = tmp_path / "star.svg"
    star.write_text(
        '<svg xmlns="http://www.w3.org/2000/svg"><g><path d="M1,2  L3 4"/></g>'
        '<circle cx="5" cy="6" r="7"/></svg>',
        encoding="utf-8",
    )
    return ManifestIndex.of(IconSet("s", (Icon("star", star, "#000000", 1.0),)))


def test_geometry_text_as_the_probe_writes_it_maps_by_path_hash(tmp_path: Path) -> None:
    icon, how = _index(tmp_path).match({"geometry": "path d=M1 2 L3 4\ncircle cx=5 cy=6 r=7"})
    assert (icon.name if icon else None, how) == ("star", IconMatch.PATH_HASH)


def test_other_geometry_maps_to_nothing(tmp_path: Path) -> None:
    index = _index(tmp_path)
    assert index.match({"geometry": "path d=M1 2 L3 5\ncircle cx=5 cy=6 r=7"}) == (
        None,
        IconMatch.NONE,
    )
    assert index.match({"geometry": None}) == (None, IconMatch.NONE)
