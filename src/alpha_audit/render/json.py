"""``alpha-audit.check/4`` JSON: every number at full float precision.

One audit: the audit's fields at the top level plus ``gate``.  Several
audits (themes x icon sets): ``audits`` lists each audit's fields, and
``gate`` covers them all.  Documented field by field in ``docs/json.md``.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import asdict
from json.encoder import encode_basestring_ascii
from pathlib import Path
from typing import Any

import numpy as np

from alpha_audit.findings import Finding
from alpha_audit.gate import GateResult
from alpha_audit.model import GamutAdjustment
from alpha_audit.render.common import (
    EncodedRecords,
    RenderOptions,
    display_path,
    dumps,
    fix_to_dict,
    json_text,
    location_to_dict,
    policy_limits,
)
from alpha_audit.results import CheckReport
from alpha_audit.rows import AuditResult

__all__ = [
    "CHECK_SCHEMA",
    "check_to_dict",
    "gate_to_dict",
    "render_report",
    "report_to_dict",
]

# /4: findings are root causes folded over canvases (``canvases``, the worst in
# ``canvas``), located where their failing value is set (``locations``), worst
# first; baselines match (theme, icon set, rule, icons) (docs/json.md).
CHECK_SCHEMA = "alpha-audit.check/4"


def check_to_dict(result: AuditResult, base: Path | None = None) -> dict[str, Any]:
    """The JSON document as plain data (documented in docs/json.md), its rows already
    encoded (:class:`~alpha_audit.render.common.EncodedRecords`: :func:`dumps` writes them).

    File paths are relative to ``base`` where they are inside it (a report
    uploaded from CI names no folder of the machine that wrote it).
    """
    theme, iconset = result.theme, result.iconset
    return {
        "schema": CHECK_SCHEMA,
        "theme": {
            "name": theme.name,
            "path": display_path(theme.path, base) if theme.path else None,
            "canvases": [
                {"name": c.name, "color": c.color, "mode": c.mode, "stack": c.stack}
                for c in theme.canvases
            ],
        },
        "iconset": {
            "name": iconset.name,
            "path": display_path(iconset.path, base) if iconset.path else None,
            "icons": len(iconset.icons),
            "sizes": list(iconset.sizes),
        },
        "threshold": result.threshold,
        "pipeline": result.pipeline,
        "rows": _rows(result, base),
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
                "set_min_delta_e_ref": _finite(s.set_delta_e_ref),
                "icons": list(s.icons),
                "sources": list(s.sources),
                "decreases": s.decreases,
                "pairs": s.pairs,
            }
            for s in result.separations
        ],
        "problems": [
            {"icon": p.icon, "file": display_path(p.file, base), "message": p.message}
            for p in result.problems
        ],
        "summary": asdict(result.summary),
    }


def _finite(value: float) -> float | None:
    """Strict JSON has no NaN: a figure that does not exist (no ink at a size) is null."""
    return value if math.isfinite(value) else None


def _rows(result: AuditResult, base: Path | None = None) -> EncodedRecords:
    """Per paint x canvas, in :meth:`~alpha_audit.rows.AuditResult.rows` order: each row's
    record as json writes it, made column by column from the result's columns (no object
    per row; a column's distinct values encoded once); a row a browser drew carries its
    measurement (``observed``), last."""
    c = result.columns()
    m, p = len(result.theme.canvases), len(result.entries)
    if not len(c):
        return EncodedRecords()
    encode = json_text
    text = encode_basestring_ascii
    # A row is its entry's (icon, paint) and canvas's fields around its own figures:
    # the pieces of one entry or one canvas are written once and repeated.
    icon = [f'{{"icon": {text(i)}, "canvas": ' for i in c.icon[:p]]
    paint = [
        f', "paint": {text(n)}, "kinds": {encode(list(k))}, "source": {text(s)}, '
        f'"opacity": {encode(o)}, "background": '
        for n, k, s, o in zip(c.paint[:p], c.kinds[:p], c.source[:p], c.opacity[:p], strict=True)
    ]
    alpha = [
        f', "alpha": {encode(a)}, "pipeline": {text(c.pipeline)}, "output": ' for a in c.alpha[:p]
    ]
    columns = [
        icon * m,
        [text(n) for n in c.canvas[::p] for _ in range(p)],
        paint * m,
        [text(b) for b in c.background[::p] for _ in range(p)],
        alpha * m,
        _texts(c.output, text),
        *(
            _float_texts(figures)
            for figures in (
                c.contrast_ref, c.contrast, c.gain, c.contrast_ref_float, c.contrast_float
            )
        ),
        *(
            _texts(flags, encode)
            for flags in (c.passes_ref, c.passes, c.newly_passes, c.loss, c.newly_fails)
        ),
        _float_texts(c.drift),
        _float_texts(c.hue_shift, nulls=True),
    ]  # fmt: skip
    template = (
        "%s%s%s%s%s%s, "
        '"contrast_ref": %s, "contrast": %s, "gain": %s, "contrast_ref_float": %s, '
        '"contrast_float": %s, "passes_ref": %s, "passes": %s, "newly_passes": %s, '
        '"loss": %s, "newly_fails": %s, "drift": %s, "hue_shift": %s, "sizes": {'
    )
    for k, size in enumerate(c.sizes):
        # '"16": {"q50": ..., "full_share": ..., "contrast": ' per entry, the contrast per row.
        lead = f'{", " if k else ""}{text(str(size))}: {{"q50": '
        columns.append(
            [
                f'{lead}{q}, "full_share": {f}, "contrast": '
                for q, f in zip(
                    _float_texts(c.q50[k][:p], nulls=True),
                    _float_texts(c.full_share[k][:p], nulls=True),
                    strict=True,
                )
            ]
            * m
        )
        columns.append(_float_texts(c.size_contrast[k], nulls=True))
        template += "%s%s}"
    rows = EncodedRecords(map((template + "}}").__mod__, zip(*columns, strict=True)))
    if result.observed:
        from alpha_audit.render.pages import paint_record

        # canvas-major: row k draws entry k % p
        assert len(rows) == m * len(result.observed)
        for k, row in enumerate(rows):
            record = paint_record(result.observed[k % len(result.observed)], base)
            rows[k] = f'{row[:-1]}, "observed": {encode(record)}}}'
    return rows


def _texts(values: list[Any], encode: Callable[[Any], str]) -> list[str]:
    """``encode`` of each value of a long column of few distinct strings or flags, once each."""
    known = {v: encode(v) for v in set(values)}
    return list(map(known.__getitem__, values))


def _float_texts(values: Sequence[float | None], *, nulls: bool = False) -> list[str]:
    """Each float as json writes it (its ``repr``), once per distinct value: distinct bit
    patterns, so 0.0 and -0.0 stay apart.  With ``nulls`` None, NaN and infinities are
    null (strict JSON has none); without, json's own refusal stands."""
    if not values:
        return []
    figures = np.array([math.nan if v is None else v for v in values], dtype=np.float64)
    _, first, inverse = np.unique(figures.view(np.int64), return_index=True, return_inverse=True)
    texts = [
        "null" if nulls and not math.isfinite(f) else json_text(f) for f in figures[first].tolist()
    ]
    return list(map(texts.__getitem__, inverse.tolist()))


def finding_to_dict(finding: Finding, base: Path | None = None) -> dict[str, Any]:
    """One gate finding: rule, where, what, and the numbers behind it."""
    return {
        "rule": finding.rule.value,
        "theme": finding.theme,
        "iconset": finding.iconset,
        "canvas": finding.canvas,
        "canvases": list(finding.canvases),
        "icons": list(finding.icons),
        "message": finding.message,
        "numbers": finding.figures.to_dict(),
        "files": [display_path(f, base) for f in finding.files],
        "manifest": display_path(finding.manifest, base),
        "lines": list(finding.lines),
        "locations": [location_to_dict(loc, base) for loc in finding.locations],
        "sources": [{"file": display_path(p, base), "line": n} for p, n in finding.sources],
        "exemption": None if finding.exemption is None else finding.exemption.reason,
        "baselined": finding.baselined,
        "level": finding.level.value,
        "fixes": list(finding.fixes),
        "edits": [
            {
                "kind": e.kind,
                "description": e.description,
                "file": display_path(e.span.file, base),
                "line": e.span.start_line,
                "value": e.value,
            }
            for e in finding.edits
        ],
    }


def gate_to_dict(gate: GateResult, base: Path | None = None) -> dict[str, Any]:
    """The ``gate`` section: policy, verdict and every finding by status."""
    policy = gate.policy
    return {
        "passed": gate.passed,
        "policy": {
            "rules": sorted(r.value for r in policy.rules),
            "warnings": sorted(r.value for r in policy.warnings - policy.rules),
            **policy_limits(policy),
            "exemptions": [
                {
                    "canvas": e.canvas,
                    "icon": e.icon,
                    "rule": None if e.rule is None else e.rule.value,
                    "reason": e.reason,
                }
                for e in policy.exemptions
            ],
        },
        "counts": gate.counts(),
        "failures": [finding_to_dict(f, base) for f in gate.failures],
        "exempted": [finding_to_dict(f, base) for f in gate.exempted],
        "baselined": [finding_to_dict(f, base) for f in gate.baselined],
        "warnings": [finding_to_dict(f, base) for f in gate.warnings],
        "baseline": None
        if gate.baseline is None
        else {"kind": gate.baseline.kind, "name": gate.baseline.name},
        "stale_baseline": [
            {"theme": t, "iconset": s, "rule": r, "icons": list(i)} for t, s, r, i in gate.stale
        ],
    }


def gamut_to_dict(note: GamutAdjustment, base: Path | None = None) -> dict[str, Any]:
    """One colour outside sRGB: where it is written, the policy, before, after, CIEDE2000."""
    return {
        "file": display_path(note.file, base),
        "line": note.line,
        "key": note.token,
        "mode": note.mode,
        "policy": note.policy,
        "before": note.text,
        "after": note.output,
        "delta_e": note.delta_e,
    }


def report_to_dict(report: CheckReport, base: Path | None = None) -> dict[str, Any]:
    """The whole document: one audit flat at the top level, several under ``audits``.

    ``gamut`` lists every input colour outside sRGB that the gamut policy moved.
    """
    gate = gate_to_dict(report.gate, base)
    # The fixes of the failures: docs/json.md, `gate.fixes`; each failure names its
    # fixes by index there.
    gate["fixes"] = [fix_to_dict(f, base) for f in report.fixes]
    gate["fixes_left_out"] = report.fixes_left_out
    gamut = [gamut_to_dict(a, base) for a in report.gamut]
    pages: dict[str, Any] = {}
    if report.pages is not None:
        from alpha_audit.render.pages import page_json

        pages = {"pages": page_json(report.pages, base)}
    if len(report.audits) == 1 and report.pages is None:
        return {**check_to_dict(report.audits[0], base), "gamut": gamut, "gate": gate}
    audits = []
    for result in report.audits:
        doc = check_to_dict(result, base)
        del doc["schema"]
        audits.append(doc)
    return {"schema": CHECK_SCHEMA, "audits": audits, "gamut": gamut, "gate": gate, **pages}


def render_report(report: CheckReport, options: RenderOptions) -> str:
    """Render a report as ``alpha-audit.check/4`` JSON."""
    return dumps(report_to_dict(report, options.base))
