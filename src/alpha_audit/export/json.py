"""``alpha-audit.export/1`` JSON: modes, canvases, icon colours and their outputs."""

from __future__ import annotations

import json
from typing import Any

from alpha_audit.export.table import ExportTable

__all__ = ["EXPORT_SCHEMA", "export_to_dict", "render_json"]

EXPORT_SCHEMA = "alpha-audit.export/1"


def export_to_dict(table: ExportTable) -> dict[str, Any]:
    """Plain data; ``outputs`` maps canvas token path to the displayed ``#rrggbb``."""
    return {
        "schema": EXPORT_SCHEMA,
        "source": table.source,
        "gamut": table.gamut,
        "modes": [
            {
                "name": m.name,
                "mode": m.kind,
                "aliases": list(m.aliases),
                "pipeline": m.pipeline,
                "canvases": [{"token": c.token, "color": c.hex} for c in m.canvases],
                "colors": [
                    {
                        "token": c.token,
                        "source": c.source,
                        "alpha": c.alpha,
                        "icons": list(c.icons),
                        "outputs": {
                            cv.token: out for cv, out in zip(m.canvases, c.outputs, strict=True)
                        },
                    }
                    for c in m.colors
                ],
            }
            for m in table.modes
        ],
        "gamut_adjusted": [
            {
                "mode": a.mode,
                "token": a.token,
                "value": a.text,
                "policy": a.policy,
                "output": a.output,
                "delta_e": a.delta_e,
                "file": str(a.file) if a.file else None,
                "line": a.line,
            }
            for a in table.adjusted
        ],
    }


def render_json(table: ExportTable) -> str:
    """The export as indented JSON."""
    return json.dumps(export_to_dict(table), indent=2, allow_nan=False) + "\n"
