"""DTCG 2025.10 tokens of the displayed colours: one file per mode, or a Resolver document."""

from __future__ import annotations

import json
from typing import Any

from alpha_audit.export.table import ExportMode, ExportTable, OneOwner, exported_paths

__all__ = ["mode_tokens", "render_dtcg", "render_resolver"]


def _color_value(hex_: str) -> dict[str, Any]:
    """A DTCG colour object of an 8-bit sRGB colour, with its hex."""
    comps = [int(hex_[i : i + 2], 16) / 255 for i in (1, 3, 5)]
    return {"colorSpace": "srgb", "components": comps, "hex": hex_}


def mode_tokens(mode: ExportMode, gamut: str | None, name: str | None = None) -> dict[str, Any]:
    """Nested DTCG groups of one mode's outputs (``$type: color`` on the root group).

    ``name`` is the mode name written in the extensions (an alias's own; default
    the mode's).  A token path that is also the group of another (``color.bg``
    and ``color.bg.body``) is the group's ``$root`` token (Format 2025.10, 6.3):
    DTCG has no token holding tokens.
    """
    root: dict[str, Any] = {"$type": "color"}
    for path, color, canvas, hex_ in exported_paths(mode):
        *groups, leaf = path.split(".")
        node = root
        for g in groups:
            child = node.setdefault(g, {})
            if "$value" in child:  # a token so far: it becomes this group's $root
                child = node[g] = {"$root": child}
            node = child
        token = {
            "$value": _color_value(hex_),
            "$description": f"{color.token} ({color.source}) at alpha {color.alpha} "
            f"on {canvas.token} ({canvas.hex})",
            "$extensions": {
                "com.alpha-audit": {
                    "source": color.source,
                    "alpha": color.alpha,
                    "canvas": canvas.token,
                    "mode": mode.name if name is None else name,
                    "pipeline": mode.pipeline,
                    "gamut": gamut,
                }
            },
        }
        if leaf in node:  # already a group of other tokens
            node[leaf]["$root"] = token
        else:
            node[leaf] = token
    return root


def render_dtcg(table: ExportTable) -> dict[str, str]:
    """``{"<mode>.tokens.json": text}``, one DTCG file per mode (and per alias of one)."""
    files = OneOwner("DTCG file")
    out = {}
    for m in table.modes:
        for name in m.names:
            file = f"{_file_stem(name)}.tokens.json"
            files.claim(file, f"mode {name}")
            out[file] = json.dumps(mode_tokens(m, table.gamut, name), indent=2) + "\n"
    return out


def render_resolver(table: ExportTable) -> str:
    """One Resolver Module 2025.10 document: a ``theme`` modifier with a context per mode."""
    doc = {
        "version": "2025.10",
        "name": "alpha-audit export",
        "modifiers": {
            "theme": {
                "contexts": {
                    name: [mode_tokens(m, table.gamut, name)]
                    for m in table.modes
                    for name in m.names
                },
                "default": table.modes[0].name,
            }
        },
        "resolutionOrder": [{"$ref": "#/modifiers/theme"}],
    }
    return json.dumps(doc, indent=2) + "\n"


def _file_stem(mode: str) -> str:
    """A file name from a mode name: no separators, no leading dot."""
    safe = "".join(ch if ch.isalnum() or ch in "-_" else "_" for ch in mode)
    return safe or "mode"
