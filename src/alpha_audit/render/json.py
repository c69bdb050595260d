"""``alpha-audit.check/1`` JSON: every number at full float precision."""

from __future__ import annotations

import json
from dataclasses import asdict
from typing import Any

from alpha_audit.audit import AuditResult

__all__ = ["CHECK_SCHEMA", "check_to_dict", "dumps", "render_check"]

CHECK_SCHEMA = "alpha-audit.check/1"


def check_to_dict(result: AuditResult) -> dict[str, Any]:
    """The JSON document as plain data (documented in docs/json.md)."""
    theme, iconset = result.theme, result.iconset
    return {
        "schema": CHECK_SCHEMA,
        "theme": {
            "name": theme.name,
            "path": str(theme.path) if theme.path else None,
            "canvases": [
                {"name": c.name, "color": c.color, "mode": c.mode} for c in theme.canvases
            ],
        },
        "iconset": {
            "name": iconset.name,
            "path": str(iconset.path) if iconset.path else None,
            "icons": len(iconset.icons),
            "sizes": list(iconset.sizes),
        },
        "threshold": result.threshold,
        "rows": [asdict(row) for row in result.rows()],
        "collisions": [
            {
                "canvas": c.canvas,
                "output": c.output,
                "sources": list(c.sources),
                "icons": list(c.icons),
                "new": c.new,
            }
            for c in result.collisions
        ],
        "separation": [
            {
                "canvas": s.canvas,
                "min_delta_e": s.delta_e,
                "min_delta_e_ref": s.delta_e_ref,
                "icons": list(s.icons),
                "sources": list(s.sources),
                "decreases": s.decreases,
                "pairs": s.pairs,
            }
            for s in result.separations
        ],
        "problems": [
            {"icon": p.icon, "file": str(p.file), "message": p.message} for p in result.problems
        ],
        "summary": asdict(result.summary),
    }


def dumps(document: dict[str, Any]) -> str:
    """Strict JSON (NaN/inf refused), stable key order, trailing newline."""
    return json.dumps(document, indent=2, allow_nan=False, ensure_ascii=False) + "\n"


def render_check(result: AuditResult, options: object = None) -> str:
    """Render ``result`` as ``alpha-audit.check/1`` JSON."""
    return dumps(check_to_dict(result))
