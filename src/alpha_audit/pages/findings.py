"""Measured paints as the audit's findings: ``below-threshold`` and ``render-drift``.

A paint measured in a browser is one more source of paint rows: its worst
pixel's contrast against the backdrop the browser composited is judged by the
same statement of ``below-threshold`` as a manifest paint
(:func:`~alpha_audit.policy.contrast_breaks`), and its distance from the
model's nearer prediction by the statement of ``drift``
(:func:`~alpha_audit.policy.drift_breaks`) with :data:`RENDER_DRIFT_TOLERANCE`.
Findings are :class:`~alpha_audit.findings.Finding` objects, so the gate, the
baseline and every renderer read them as they read ``check``'s:

* ``theme`` is the state (``theme:dark``), ``iconset`` the story id or page
  path, ``icons`` the manifest icon (or, for an icon that maps to none, its
  DOM path), ``canvas`` the backdrop measured behind it;
* a root cause is one rule on one icon in one story and state, folded over
  every instance and paint of it there (the worst one's figures, every
  backdrop named in ``canvases``), as ``check`` folds canvases;
* ``locations``: the manifest line (or design token) that sets the mapped
  icon's colour and its ``alpha:``, then the story's source file (its
  ``importPath``) or the HTML page.

Pure computation: nothing is printed.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from pathlib import Path

from alpha_audit.findings import Finding, Location, alpha_location, colour_location
from alpha_audit.model import Icon, IconSet
from alpha_audit.pages.measured import MeasuredPaint, Prediction
from alpha_audit.policy import Policy, contrast_breaks, drift_breaks
from alpha_audit.rules import Rule

__all__ = [
    "RENDER_DRIFT_TOLERANCE",
    "nearer_prediction",
    "paint_findings",
    "paint_key",
    "worst_paints",
]

# CIEDE2000 between the drawn colour and the model's nearer prediction above which
# the page draws another colour than the manifest says.  One 8-bit code step in one
# channel moves a colour by at most 1.21 (200,000 random sRGB colours, green), and a
# browser rounds each composite to a code, so a paint drawn as predicted measures
# within about one step; the fixture Storybook's icons that draw the manifest colour
# measure 0.00, its CSS overrides 17.7 to 28.6.  2.0 (two of `lock`'s just-noticeable
# differences) leaves rounding a margin and misses no override a reviewer could see.
RENDER_DRIFT_TOLERANCE = 2.0

_BELOW = "worst pixel {now:.2f}:1 (median {median:.2f}:1) is below {t:g}:1 on {behind}"
_DRIFT = (
    "draws {drawn} where the model predicts {predicted} ({pipeline}, from {source} at alpha "
    "{a:g}; CIEDE2000 {drift:.1f} > {tol:g})"
)


def nearer_prediction(paint: MeasuredPaint) -> Prediction | None:
    """The model's prediction nearest (CIEDE2000) to what the browser drew, if any."""
    if not paint.predictions:
        return None
    return min(paint.predictions, key=lambda p: p.drift)


def paint_key(paint: MeasuredPaint) -> str:
    """The icon a finding names: the manifest icon, else the DOM path of the instance."""
    return paint.icon if paint.icon is not None else paint.dom_path


def _figures(p: MeasuredPaint) -> dict[str, float | str]:
    """What every finding of a measured paint carries (reports show them as properties)."""
    numbers: dict[str, float | str] = {
        "story" if p.source_kind == "storybook" else "page": p.source,
        "state": p.state,
        "engine": p.engine,
        "dom_path": p.dom_path,
        "element": p.element,
        "match": str(p.match),
        "threshold": p.threshold,
    }
    optional: dict[str, float | str | None] = {
        "contrast": p.contrast_worst,
        "contrast_median": p.contrast_median,
        "drawn": p.drawn,
        "background": p.behind,
        "around": p.around,
        "source": p.model_source,
        "alpha": p.model_alpha,
        "opacity": p.model_opacity,
        "render_drift": p.render_drift,
    }
    near = nearer_prediction(p)
    if near is not None:
        optional |= {
            "model_contrast": near.contrast,
            "model_output": near.output,
            "pipeline": near.pipeline,
        }
    numbers |= {k: v for k, v in optional.items() if v is not None}
    return numbers


def _below(p: MeasuredPaint) -> tuple[str, dict[str, float | str]]:
    assert p.contrast_worst is not None and p.contrast_median is not None
    message = _BELOW.format(
        now=p.contrast_worst, median=p.contrast_median, t=p.threshold, behind=p.behind
    )
    near = nearer_prediction(p)
    if near is not None:
        message += f"; the model predicts {near.contrast:.2f}:1 ({near.pipeline})"
    return message, _figures(p)


def _drift(p: MeasuredPaint) -> tuple[str, dict[str, float | str]]:
    near = nearer_prediction(p)
    assert near is not None and p.render_drift is not None
    message = _DRIFT.format(
        drawn=p.drawn,
        predicted=near.output,
        pipeline=near.pipeline,
        source=p.model_source,
        a=p.model_alpha,
        drift=p.render_drift,
        tol=RENDER_DRIFT_TOLERANCE,
    )
    return message, {**_figures(p), "drift": p.render_drift, "tolerance": RENDER_DRIFT_TOLERANCE}


def _breaks(rule: Rule, p: MeasuredPaint, policy: Policy) -> bool:
    """Whether ``rule`` objects to ``p`` (the rules' one statement, on the measured figures)."""
    if rule is Rule.BELOW_THRESHOLD:
        worst = p.contrast_worst
        return worst is not None and bool(contrast_breaks(rule, policy, worst, worst, p.threshold))
    if rule is Rule.RENDER_DRIFT:
        return p.render_drift is not None and bool(
            drift_breaks(p.render_drift, RENDER_DRIFT_TOLERANCE)
        )
    return False


def _badness(rule: Rule, p: MeasuredPaint) -> float:
    """Higher is worse: least contrast, largest drift."""
    if rule is Rule.BELOW_THRESHOLD:
        return -(p.contrast_worst or 0.0)
    return p.render_drift or 0.0


def _locations(
    rule: Rule, p: MeasuredPaint, icon: Icon | None, manifest: Path | None, policy: Policy
) -> tuple[Location, ...]:
    """The manifest lines setting the mapped icon's colour and alpha, then the story or page.

    The colour comes first for ``render-drift`` (the page draws another colour than it
    says) and for ``below-threshold`` unless the manifest's alpha is not 1 and the page
    draws the model's colour: then the alpha is the value that made it fail.
    """
    found: list[Location | None] = []
    if icon is not None:
        colour, alpha = colour_location(icon, manifest), alpha_location(icon, manifest)
        alpha_first = (
            rule is Rule.BELOW_THRESHOLD
            and p.model_alpha not in (None, 1.0)
            and not _breaks(Rule.RENDER_DRIFT, p, policy)
        )
        found += [alpha, colour] if alpha_first else [colour, alpha]
    if p.file is not None:
        found.append(Location(p.file, 1, "story" if p.source_kind == "storybook" else "page"))
    return tuple(dict.fromkeys(loc for loc in found if loc is not None))


_BUILD = {Rule.BELOW_THRESHOLD: _below, Rule.RENDER_DRIFT: _drift}


def _groups(
    paints: Iterable[MeasuredPaint], policy: Policy
) -> dict[tuple[str, str, Rule, str], list[MeasuredPaint]]:
    """The paints of each root cause: (state, story or page, rule, icon), in paint order."""
    groups: dict[tuple[str, str, Rule, str], list[MeasuredPaint]] = {}
    paints = list(paints)
    for rule in Rule:
        if rule not in _BUILD or rule not in policy.reported:
            continue
        for p in paints:
            if _breaks(rule, p, policy):
                groups.setdefault((p.state, p.source, rule, paint_key(p)), []).append(p)
    return groups


def _worst(rule: Rule, found: Sequence[MeasuredPaint]) -> MeasuredPaint:
    """The paint a finding folded over ``found`` takes its figures from (the first if tied)."""
    return max(found, key=lambda p: _badness(rule, p))


def worst_paints(
    paints: Iterable[MeasuredPaint], policy: Policy
) -> list[tuple[Rule, MeasuredPaint]]:
    """The paint each finding of ``paints`` would take its figures from, with its rule.

    What :func:`paint_findings` folds, without the findings: over the paints of
    one page state, the instances a report may show (``render`` crops them).
    """
    groups = _groups(paints, policy)
    return [(rule, _worst(rule, found)) for (_, _, rule, _), found in groups.items()]


def paint_findings(
    paints: Iterable[MeasuredPaint], policy: Policy, iconset: IconSet | None = None
) -> list[Finding]:
    """Every finding of the rules ``policy`` fails on or reports, from measured paints.

    One finding per (state, story or page, rule, icon), folded over the instances
    and paints of that icon there; in the order of the paints (source, state,
    DOM order).  :func:`alpha_audit.gate.judge` ranks them and decides the verdict.

    >>> from alpha_audit.pages.measured import Coverage, IconMatch
    >>> p = MeasuredPaint("icons--alert", "storybook", "u", "theme:dark", "chromium", "l",
    ...     None, IconMatch.NONE, "svg", "div > svg", "currentColor", ("stroke",), "#6e1a1f",
    ...     None, "#0d1117", None, None, None, Coverage(1, 1, 1.0, 1.0, 1.0), 1.63, 1.65,
    ...     None, None, None, (), None, (0, 0, 24, 24))
    >>> [(f.rule.value, f.theme, f.iconset, f.icons, f.canvas) for f in
    ...     paint_findings([p], Policy(rules=frozenset({Rule.BELOW_THRESHOLD})))]
    [('below-threshold', 'theme:dark', 'icons--alert', ('div > svg',), '#0d1117')]
    """
    by_name: Mapping[str, Icon] = {i.name: i for i in iconset.icons} if iconset else {}
    manifest = iconset.path if iconset is not None else None
    out: list[Finding] = []
    for (state, source, rule, name), found in _groups(paints, policy).items():
        worst = _worst(rule, found)
        message, numbers = _BUILD[rule](worst)
        canvases = tuple(dict.fromkeys(p.behind for p in found if p.behind is not None))
        icon = by_name.get(worst.icon) if worst.icon is not None else None
        lines = () if icon is None else (icon.color_line, icon.alpha_line)
        out.append(
            Finding(
                rule=rule,
                theme=state,
                iconset=source,
                canvas=worst.behind,
                icons=(name,),
                message=message,
                numbers=numbers,
                files=() if icon is None else (Path(icon.file),),
                manifest=manifest if icon is not None else None,
                lines=tuple(sorted({n for n in lines if n is not None})),
                exemption=policy.exempt(rule, worst.behind, (name,)),
                level=policy.level(rule),
                canvases=canvases,
                locations=_locations(rule, worst, icon, manifest, policy),
            )
        )
    return out


def instances(paints: Sequence[MeasuredPaint]) -> dict[tuple[str, str], set[str]]:
    """The icons audited per (story or page, state): what a report's matrix counts."""
    out: dict[tuple[str, str], set[str]] = {}
    for p in paints:
        out.setdefault((p.source, p.state), set()).add(paint_key(p))
    return out
