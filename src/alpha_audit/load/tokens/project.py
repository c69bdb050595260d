"""Icon sets whose colours name tokens: one (theme, icon set) pair per token mode.

A manifest's ``palette`` gains every icon-colour token of the mode, keyed by
token path, so an icon says ``color: color.icon.danger`` and gets that
mode's colour (a palette entry of the manifest's own wins on a clash).  A
coefficient in the token's ``$extensions`` replaces the manifest's for the
icons of that colour; ``--alpha`` still overrides everything.
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

from alpha_audit.load.iconset import find_project_root, iconset_from_doc
from alpha_audit.load.tokens.themes import TokenThemes
from alpha_audit.load.yamldoc import YamlDoc, load_yaml
from alpha_audit.model import IconSet, Theme

__all__ = ["token_audit_pairs"]


def _with_palette(doc: YamlDoc, palette: dict[str, str]) -> YamlDoc:
    data = doc.data
    if not isinstance(data, dict):
        return doc  # iconset_from_doc reports the bad document
    own = data.get("palette")
    merged = {**palette, **own} if isinstance(own, dict) else palette
    return YamlDoc(doc.path, {**data, "palette": merged}, doc.lines)


def token_audit_pairs(themes: TokenThemes, manifest: str | Path) -> list[tuple[Theme, IconSet]]:
    """``(mode theme, icon set with that mode's token colours)`` for every mode."""
    doc = load_yaml(manifest)
    root = find_project_root(Path(manifest).resolve().parent)
    pairs = []
    for mode in themes.modes:
        iconset = iconset_from_doc(_with_palette(doc, mode.theme_palette()), root=root)
        icons = tuple(
            replace(icon, alpha=alpha)
            if icon.color_name in mode.colors
            and (alpha := mode.colors[icon.color_name].alpha) is not None
            else icon
            for icon in iconset.icons
        )
        pairs.append(
            (mode.theme, replace(iconset, icons=icons, name=f"{iconset.name} ({mode.name})"))
        )
    return pairs
