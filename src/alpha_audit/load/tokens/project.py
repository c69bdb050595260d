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
from typing import Any

from alpha_audit.color import GamutPolicy
from alpha_audit.load.iconset import find_project_root, iconset_from_doc
from alpha_audit.load.tokens.themes import TokenColor, TokenThemes
from alpha_audit.load.yamldoc import YamlDoc, load_yaml
from alpha_audit.model import Icon, IconSet, Theme

__all__ = ["token_audit_pairs"]


def _with_palette(doc: YamlDoc, palette: dict[str, str]) -> YamlDoc:
    data = doc.data
    if not isinstance(data, dict):
        return doc  # iconset_from_doc reports the bad document
    own = data.get("palette")
    merged = {**palette, **own} if isinstance(own, dict) else palette
    return YamlDoc(doc.path, {**data, "palette": merged}, doc.lines, doc.spans)


def _with_token(icon: Icon, color: TokenColor | None) -> Icon:
    """``icon`` with its token's location and (if the token has one) its coefficient.

    A colour the manifest's own palette sets keeps the palette entry's span;
    otherwise the token's value is where a colour fix goes.  A coefficient
    from the token is not the manifest's ``alpha:``, so no alpha span remains.
    """
    if color is None:
        return icon
    token = color.token
    changes: dict[str, Any] = {"token_file": token.file, "token_line": token.line}
    if icon.color_span is None:
        changes["color_span"] = token.span
    if color.alpha is not None:
        changes["alpha"] = color.alpha
        changes["alpha_span"] = None
    return replace(icon, **changes)


def token_audit_pairs(
    themes: TokenThemes, manifest: str | Path, *, gamut: GamutPolicy | None = None
) -> list[tuple[Theme, IconSet]]:
    """``(mode theme, icon set with that mode's token colours)`` for every mode.

    ``gamut`` is the project's policy for the manifest's own colours.
    """
    doc = load_yaml(manifest)
    root = find_project_root(Path(manifest).absolute().parent)
    pairs = []
    for mode in themes.modes:
        iconset = iconset_from_doc(_with_palette(doc, mode.theme_palette()), root=root, gamut=gamut)
        colors = mode.colors
        icons = tuple(_with_token(i, colors.get(i.color_name or "")) for i in iconset.icons)
        pairs.append(
            (mode.theme, replace(iconset, icons=icons, name=f"{iconset.name} ({mode.name})"))
        )
    return pairs
