"""Benchmark the check JSON report on 300 icons x 17 canvases (5,100 rows; issue 10).

The straightforward version: a ``Row`` object and ``dataclasses.asdict`` for every
row, and ``json.dumps(..., indent=2)``, which falls back to the pure-Python encoder.
Ours: each row's line written column by column from the result's columns (no object
per row; each distinct value of a column encoded once, by json's own encoder) and laid
out by :func:`alpha_audit.render.common.dumps`.  Both documents must parse to the same
data.  Run as a script:

    .venv/bin/python benchmarks/bench_json.py
"""

from __future__ import annotations

import json
import math
import time
from dataclasses import asdict
from pathlib import Path
from typing import Any

from alpha_audit.gate import evaluate
from alpha_audit.model import Canvas, Icon, IconSet, Theme
from alpha_audit.policy import Policy
from alpha_audit.render import json as render_json
from alpha_audit.render.common import RenderOptions
from alpha_audit.render.json import render_report, report_to_dict
from alpha_audit.results import CheckReport
from alpha_audit.rows import Row, audit


def report(icons: int = 300, canvases: int = 17) -> CheckReport:
    theme = Theme(
        "t",
        tuple(Canvas(f"c{j}", f"#{j * 15:02x}{j * 15:02x}{j * 15:02x}") for j in range(canvases)),
    )
    icon_set = IconSet(
        "s",
        tuple(
            Icon(f"i{i}", Path(f"i{i}.svg"), f"#{(i * 2654435761) % 0xFFFFFF:06x}", 1.2)
            for i in range(icons)
        ),
    )
    result = audit(theme, icon_set)
    return CheckReport((result,), evaluate([result], Policy()))


def _row_dict(row: Row) -> dict[str, Any]:
    """One row as the report writes it, from ``asdict`` (NaN size figures: null)."""
    doc = asdict(row)
    doc["kinds"] = list(row.kinds)
    doc["newly_passes"], doc["newly_fails"] = row.newly_passes, row.newly_fails
    doc["sizes"] = {
        str(size): {k: (v if math.isfinite(v) else None) for k, v in asdict(f).items()}
        for size, f in row.sizes.items()
    }
    return doc


def straightforward(r: CheckReport) -> str:
    """The same document with a ``Row`` and ``asdict`` per row, encoded with ``indent=2``."""
    original = render_json._rows
    render_json._rows = lambda result, base=None: [_row_dict(row) for row in result.rows()]
    try:
        doc = report_to_dict(r)
    finally:
        render_json._rows = original
    return json.dumps(doc, indent=2, allow_nan=False, ensure_ascii=False) + "\n"


def best_of(fn, repeat: int = 3) -> tuple[float, str]:
    times, out = [], ""
    for _ in range(repeat):
        start = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - start)
    return min(times), out


if __name__ == "__main__":
    r = report()
    rows = len(list(r.audits[0].rows()))
    t_ref, ref = best_of(lambda: straightforward(r))
    t_ours, ours = best_of(lambda: render_report(r, RenderOptions()))
    assert json.loads(ours) == json.loads(ref), "the two documents differ"
    print(f"check JSON, {rows} rows: straightforward {t_ref:.3f} s, ours {t_ours:.3f} s, "
          f"ratio {t_ref / t_ours:.1f}x (same parsed document)")  # fmt: skip
