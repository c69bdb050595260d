"""``alpha-audit.check/4`` JSON: every number at full float precision.

One audit: the audit's fields at the top level plus ``gate``.  Several
audits (themes x icon sets): ``audits`` lists each audit's fields, and
``gate`` covers them all.  Documented field by field in ``docs/json.md``.
"""

from __future__ import annotations

import math
from dataclasses import asdict, replace
from pathlib import Path
from typing import Any

from alpha_audit.findings import Finding
from alpha_audit.gate import GateResult
from alpha_audit.model import GamutAdjustment
from alpha_audit.render.common import (
    Records,
    RenderOptions,
    display_path,
    dumps,
    fix_to_dict,
    location_to_dict,
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
    """The JSON document as plain data (documented in docs/json.md).

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


def _rows(result: AuditResult, base: Path | None = None) -> list[dict[str, Any]]:
    """Per paint x canvas, in :meth:`~alpha_audit.rows.AuditResult.rows` order, written
    from the result's columns (no row object is made); a row a browser drew carries its
    measurement (``observed``)."""
    if result.observed:
        from alpha_audit.render.pages import paint_record

        records = _rows(replace(result, observed=()), base)
        m = len(result.theme.canvases)
        for k, record in enumerate(records):  # canvas-major: row k draws entry k % p
            record["observed"] = paint_record(result.observed[k % len(result.observed)], base)
        assert len(records) == m * len(result.observed)
        return records
    c = result.columns()
    sizes = [
        [
            {"q50": q, "full_share": f, "contrast": x}
            for q, f, x in zip(
                map(_finite, c.q50[k]),
                map(_finite, c.full_share[k]),
                map(_finite, c.size_contrast[k]),
                strict=True,
            )
        ]
        for k in range(len(c.sizes))
    ]
    names = [str(s) for s in c.sizes]
    kinds = {k: list(k) for k in set(c.kinds)}  # one list per distinct value
    return Records(
        {
            "icon": icon,
            "canvas": canvas,
            "paint": paint,
            "kinds": kinds[kind],
            "source": source,
            "opacity": opacity,
            "background": background,
            "alpha": alpha,
            "pipeline": c.pipeline,
            "output": output,
            "contrast_ref": contrast_ref,
            "contrast": contrast,
            "gain": gain,
            "contrast_ref_float": ref_float,
            "contrast_float": now_float,
            "passes_ref": passes_ref,
            "passes": passes,
            "newly_passes": newly_passes,
            "loss": loss,
            "newly_fails": newly_fails,
            "drift": drift,
            "hue_shift": hue,
            "sizes": dict(zip(names, figures, strict=True)),
        }
        for (
            icon, canvas, paint, kind, source, opacity, background, alpha, output,
            contrast_ref, contrast, gain, ref_float, now_float, passes_ref, passes,
            newly_passes, loss, newly_fails, drift, hue, figures,
        ) in zip(
            c.icon, c.canvas, c.paint, c.kinds, c.source, c.opacity, c.background, c.alpha,
            c.output, c.contrast_ref, c.contrast, c.gain, c.contrast_ref_float,
            c.contrast_float, c.passes_ref, c.passes, c.newly_passes, c.loss, c.newly_fails,
            c.drift, c.hue_shift,
            zip(*sizes, strict=True) if sizes else ((),) * len(c), strict=True,
        )
    )  # fmt: skip


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
            "max_loss": policy.max_loss,
            "min_delta_e": policy.min_delta_e,
            "max_drift": policy.max_drift,
            "min_size_contrast": policy.min_size_contrast,
            "visibility_floor": policy.visibility_floor,
            "loss_tolerance": policy.loss_tolerance,
            "near_duplicate_delta_e": policy.near_duplicate_delta_e,
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
