"""Measured paints as paint rows: a page run becomes ``check``'s report.

A paint a browser drew is one more paint row (:func:`alpha_audit.rows.observed_audit`):
its output is the colour the screen showed, its canvas the backdrop the browser
composited under it, both at the pixel where their contrast is least, judged by
the one judgement of every row (:func:`~alpha_audit.color.judged_contrast`).  So
the one gate (:func:`alpha_audit.gate.collect`, :func:`~alpha_audit.gate.judge`),
the one folding (a finding per rule and row, over its canvases), the fixes
(:func:`alpha_audit.fixes.with_fixes`, under the run's policy) and every
renderer read them as they read ``check``'s.

The rows of one story or page, state and engine are grouped by backdrop (one
audit each: every row of an audit is drawn on its canvas).  A row is what drew
the paint:

* the manifest's model where the page draws what it predicts (an icon mapped to
  the manifest, its drift within :data:`~alpha_audit.policy.RENDER_DRIFT_TOLERANCE`):
  the manifest's colour at its alpha and opacity, under the nearer prediction's
  pipeline, so fixes edit the manifest;
* else the page's CSS: the colour the engine computed for the paint at the
  opacity it is drawn at, under ``css`` (a browser's blending), so fixes are a
  colour or an opacity to write in CSS; an ``<img>`` is its drawn colour.

Instances of one row on one backdrop fold into the worst (least contrast).  A
paint no pixel shows at full coverage is not a row: it is ``not-audited``.
Pure computation: nothing is printed.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from alpha_audit.color import Pipeline, from_8bit
from alpha_audit.findings import colour_location
from alpha_audit.gate import Baseline, CanvasKey, collect, judge
from alpha_audit.model import Canvas, Icon, IconSet, Location, Theme
from alpha_audit.observed import MEASURED, MeasuredPaint, PageRun
from alpha_audit.paints import CURRENT_COLOR
from alpha_audit.policy import (
    RENDER_DRIFT_TOLERANCE,
    RENDER_POLICY,
    Policy,
    contrast_breaks,
    drift_breaks,
)
from alpha_audit.results import CheckReport
from alpha_audit.rows import AuditResult, PaintEntry, Unaudited, observed_audit
from alpha_audit.rules import Rule

__all__ = [
    "page_audits",
    "page_report",
    "shown_rule",
]


@dataclass(frozen=True)
class _Row:
    """What drew one measured paint: the row it becomes."""

    entry: PaintEntry
    alpha: float
    pipeline: Pipeline


def _faithful(paint: MeasuredPaint) -> bool:
    """Whether the page draws what the manifest's model predicts for this paint."""
    return (
        paint.icon is not None
        and paint.render_drift is not None
        and paint.nearer is not None
        and not bool(drift_breaks(paint.render_drift, RENDER_DRIFT_TOLERANCE))
    )


def _page_places(paint: MeasuredPaint) -> tuple[Location, ...]:
    """Where the page sets the paint (its CSS declarations), then its story or page file."""
    found = list(paint.locations)
    if paint.file is not None and not any(p.what in ("story", "page") for p in found):
        found.append(
            Location(paint.file, 1, "story" if paint.source_kind == "storybook" else "page")
        )
    return tuple(dict.fromkeys(found))


def _row(paint: MeasuredPaint, manifest: IconSet | None, icons: dict[str, Icon]) -> _Row:
    """The row of one measured paint (see the module's docstring)."""
    mapped = icons.get(paint.icon) if paint.icon is not None else None
    near = paint.nearer
    if mapped is not None and near is not None and _faithful(paint):
        assert paint.model_source is not None and paint.model_alpha is not None
        own = paint.paint == CURRENT_COLOR or paint.model_source == mapped.color
        entry = PaintEntry(
            mapped,
            CURRENT_COLOR if own else paint.model_source,
            paint.kinds,
            mapped.color if own else paint.model_source,
            float(paint.model_opacity if paint.model_opacity is not None else 1.0),
            where=_page_places(paint),
        )
        pipeline: Pipeline = "css" if near.pipeline == "css" else "linear"
        return _Row(entry, float(paint.model_alpha), pipeline)
    colour = paint.declared if paint.declared is not None else paint.drawn
    assert colour is not None  # measured paints have a drawn colour
    opacity = paint.declared_opacity if paint.declared is not None else 1.0
    # The page's own declaration of the colour first (it is what draws); for a mapped
    # icon the manifest's colour next (the icon's source, where the page follows it),
    # then the story or page file.
    said = colour_location(mapped, manifest.path) if mapped and manifest else None
    page = _page_places(paint)
    css = [p for p in page if p.what.startswith("css-")]
    rest = [p for p in page if not p.what.startswith("css-")]
    places = tuple(dict.fromkeys([*css, *([said] if said else []), *rest]))
    # The file that draws it: the manifest's SVG when it maps to one, else the story or page.
    file = mapped.file if mapped is not None else (paint.file or Path(paint.source))
    icon = Icon(paint.name, file, colour, 1.0)
    paint_label = CURRENT_COLOR if paint.paint == CURRENT_COLOR else icon.color
    entry = PaintEntry(icon, paint_label, paint.kinds, icon.color, float(opacity), where=places)
    return _Row(entry, 1.0, "css")


def _canvas_name(paint: MeasuredPaint, engines: int) -> str:
    assert paint.behind is not None
    return paint.behind if engines <= 1 else f"{paint.behind} ({paint.engine})"


def page_audits(
    paints: Iterable[MeasuredPaint],
    manifest: IconSet | None = None,
    *,
    threshold: float = 3.0,
) -> list[AuditResult]:
    """The paint rows of measured ``paints``: one audit per story or page, state, engine,
    backdrop and pipeline, in the paints' order (story, state, engine, DOM order).

    ``manifest`` is the icon set the icons were mapped to (rows of the model point
    at its lines).
    """
    paints = list(paints)
    engines = len({p.engine for p in paints})
    icons = {i.name: i for i in manifest.icons} if manifest is not None else {}
    groups: dict[tuple[str, str, str, str, str], dict[object, tuple[_Row, MeasuredPaint]]] = {}
    skipped: dict[tuple[str, str, str], list[tuple[MeasuredPaint, Icon]]] = {}
    for paint in paints:
        if paint.status != MEASURED or paint.drawn is None or paint.behind is None:
            file = paint.file if paint.file is not None else Path(paint.source)
            icon = Icon(paint.name, file, paint.declared or "#000000", 1.0)
            skipped.setdefault((paint.source, paint.state, paint.engine), []).append((paint, icon))
            continue
        row = _row(paint, manifest, icons)
        key = (paint.source, paint.state, paint.engine, _canvas_name(paint, engines), row.pipeline)
        identity = (row.entry.icon.name, row.entry.paint, row.entry.source, row.alpha,
                    row.entry.opacity, row.entry.kinds)  # fmt: skip
        rows = groups.setdefault(key, {})
        worst = rows.get(identity)
        if worst is None or (paint.contrast or 0.0) < (worst[1].contrast or 0.0):
            rows[identity] = (row, paint)
    out: list[AuditResult] = []
    for (source, state, engine, canvas, pipeline), rows in groups.items():
        found = list(rows.values())
        behind = found[0][1].behind
        assert behind is not None
        theme = Theme(state, (Canvas(canvas, behind),), threshold)
        own = {r.entry.icon.name: r.entry.icon for r, _ in found}
        unaudited = _unaudited(skipped.pop((source, state, engine), []), own)
        iconset = IconSet(
            source,
            tuple(own.values()),
            sizes=(),
            path=manifest.path if manifest is not None else None,
        )
        drawn = np.array([from_8bit(_codes(p.drawn)) for _, p in found]).reshape(-1, 1, 3)
        out.append(
            observed_audit(
                theme,
                iconset,
                [r.entry for r, _ in found],
                [r.alpha for r, _ in found],
                drawn,
                [p for _, p in found],
                pipeline=pipeline,  # type: ignore[arg-type]  # the key holds a Pipeline
                threshold=threshold,
                unaudited=unaudited,
            )
        )
    for (source, state, _), left in skipped.items():  # page states where nothing was judged
        own = {icon.name: icon for _, icon in left}
        around = next((p.around for p, _ in left if p.around is not None), "#ffffff")
        theme = Theme(state, (Canvas(around, around),), threshold)
        iconset = IconSet(source, tuple(own.values()), sizes=())
        out.append(
            observed_audit(
                theme, iconset, [], [], np.zeros((0, 1, 3)), [], pipeline="css",
                threshold=threshold, unaudited=_unaudited(left, own),
            )
        )  # fmt: skip
    return out


def _codes(text: str | None) -> list[int]:
    assert text is not None
    return [int(text[k : k + 2], 16) for k in (1, 3, 5)]


def _unaudited(left: Sequence[tuple[MeasuredPaint, Icon]], own: dict[str, Icon]) -> list[Unaudited]:
    """Paints no pixel shows at full coverage: not judged, said so (``not-audited``)."""
    out = []
    for paint, icon in left:
        own.setdefault(icon.name, icon)
        out.append(
            Unaudited(
                paint.name,
                paint.dom_path,
                None,
                f"{paint.paint} ({'/'.join(paint.kinds) or 'paint'}): {paint.status}: no pixel "
                "shows it at full coverage (a stroke too thin for this device scale, a fill "
                "with no area, or a paint under the icon's other paints); not judged",
            )
        )
    return out


def shown_rule(paint: MeasuredPaint, policy: Policy, threshold: float) -> Rule | None:
    """The rule a finding about ``paint`` would be of, if any (what the HTML report crops).

    The rules' own statements on the paint's figures (``below-threshold`` first).
    """
    reported = policy.reported
    c = paint.contrast
    if (
        Rule.BELOW_THRESHOLD in reported
        and c is not None
        and bool(contrast_breaks(Rule.BELOW_THRESHOLD, policy, c, c, threshold))
    ):
        return Rule.BELOW_THRESHOLD
    if (
        Rule.RENDER_DRIFT in reported
        and paint.render_drift is not None
        and bool(drift_breaks(paint.render_drift, RENDER_DRIFT_TOLERANCE))
    ):
        return Rule.RENDER_DRIFT
    return None


def page_report(
    run: PageRun,
    paints: Iterable[MeasuredPaint],
    policy: Policy = RENDER_POLICY,
    manifest: IconSet | None = None,
    *,
    threshold: float = 3.0,
    baseline: Baseline | Iterable[tuple[str, str, str, tuple[str, ...]] | CanvasKey] | None = None,
    fixes: bool = True,
) -> CheckReport:
    """``render``'s report: the measured paints as rows, gated and fixed as ``check``'s.

    ``manifest`` is the icon set the icons were mapped to.  The page states that
    could not be audited are ``run.problems`` (``render`` exits 2 for them).
    """
    from alpha_audit.fixes import with_fixes

    audits = page_audits(paints, manifest, threshold=threshold)
    gate = judge(audits, policy, collect(audits, policy), baseline)
    report = CheckReport(tuple(audits), gate, pages=run)
    return with_fixes(report) if fixes else report
