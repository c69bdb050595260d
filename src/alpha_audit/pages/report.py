"""The measured paints as a JSON document (``alpha-audit.render/1``, provisional).

A pure function of the :class:`RenderResult`; floats keep full precision,
colours are ``#rrggbb`` beside their linear sRGB triples, and the order is
the result's (source, state, engine, DOM order).
"""

from __future__ import annotations

import math
from dataclasses import asdict
from typing import Any

from alpha_audit.pages.measured import MeasuredPaint, RenderResult

__all__ = ["RENDER_SCHEMA", "paint_record", "render_document"]

RENDER_SCHEMA = "alpha-audit.render/1"


def _clean(value: Any) -> Any:
    """NaN (no coverage) as null: JSON has no NaN."""
    if isinstance(value, float) and math.isnan(value):
        return None
    if isinstance(value, dict):
        return {k: _clean(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [_clean(v) for v in value]
    return value


def paint_record(paint: MeasuredPaint) -> dict[str, Any]:
    """One measured paint as JSON data (every field of :class:`MeasuredPaint`, and ``passes``)."""
    record = asdict(paint)
    record["match"] = str(paint.match)
    record["passes"] = paint.passes
    return dict(_clean(record))


def render_document(result: RenderResult) -> dict[str, Any]:
    """The whole result: engines, counts, measured paints, problems and blocked requests."""
    return {
        "schema": RENDER_SCHEMA,
        "engines": [{"name": n, "version": v} for n, v in result.engines],
        "summary": {
            "audited": result.audited,
            "icons": result.icons,
            "paints": len(result.paints),
            "failing": len(result.failing),
            "problems": len(result.problems),
            "blocked": len(result.blocked),
        },
        "paints": [paint_record(p) for p in result.paints],
        "problems": [asdict(p) for p in result.problems],
        "blocked": [asdict(b) for b in result.blocked],
    }
