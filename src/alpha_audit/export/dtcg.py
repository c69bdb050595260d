"""DTCG 2025.10 tokens of the displayed colours: one file per mode, or a Resolver document."""

from __future__ import annotations

import json
from typing import Any

from alpha_audit.errors import InputError
from alpha_audit.export.table import ExportMode, ExportTable, OneOwner, exported_paths

__all__ = ["mode_tokens", "render_dtcg", "render_resolver"]


def _color_value(hex_: str) -> dict[str, Any]:
    """A DTCG colour object of an 8-bit sRGB colour, with its hex."""
    comps = [int(hex_[i : i + 2], 16) / 255 for i in (1, 3, 5)]
    return {"colorSpace": "srgb", "components": comps, "hex": hex_}


def mode_tokens(mode: ExportMode, gamut: str) -> dict[str, Any]:
    """Nested DTCG groups of one mode's outputs (``$type: color`` on the root group)."""
    root: dict[str, Any] = {"$type": "color"}
    outputs = exported_paths(mode)
    made = {path: f"{color.token} on {canvas.token}" for path, color, canvas, _ in outputs}
    for path, color, canvas, hex_ in outputs:
        *groups, leaf = path.split(".")
        for i in range(1, len(groups) + 1):
            group = ".".join(groups[:i])
            if group in made:  # DTCG: a token holds no tokens (Format 2025.10, 6.1)
                raise InputError(
                    f"{made[group]} and {made[path]} (mode {mode.name}) become the DTCG "
                    f"tokens {group} and {path}, and a token cannot be a group; rename one"
                )
        node = root
        for g in groups:
            node = node.setdefault(g, {})
        node[leaf] = {
            "$value": _color_value(hex_),
            "$description": f"{color.token} ({color.source}) at alpha {color.alpha} "
            f"on {canvas.token} ({canvas.hex})",
            "$extensions": {
                "com.alpha-audit": {
                    "source": color.source,
                    "alpha": color.alpha,
                    "canvas": canvas.token,
                    "mode": mode.name,
                    "gamut": gamut,
                }
            },
        }
    return root


def render_dtcg(table: ExportTable) -> dict[str, str]:
    """``{"<mode>.tokens.json": text}``, one DTCG file per mode."""
    files = OneOwner("DTCG file")
    out = {}
    for m in table.modes:
        name = f"{_file_stem(m.name)}.tokens.json"
        files.claim(name, f"mode {m.name}")
        out[name] = json.dumps(mode_tokens(m, table.gamut), indent=2) + "\n"
    return out


def render_resolver(table: ExportTable) -> str:
    """One Resolver Module 2025.10 document: a ``theme`` modifier with a context per mode."""
    doc = {
        "version": "2025.10",
        "name": "alpha-audit export",
        "modifiers": {
            "theme": {
                "contexts": {m.name: [mode_tokens(m, table.gamut)] for m in table.modes},
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
